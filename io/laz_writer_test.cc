// LasWriter with compressed = true writes LAZ that LasReader decodes to exactly the points of the LAS twin
// written from the same points: every point format we write (0-3 with LAS 1.2 and 1.4, 6-8 with LAS 1.4), a
// multi-chunk file, an empty file and a 1-point file; the LASzip framing (format bit 7, laszip VLR, chunk table
// offset, EVLRs after the chunk table); no file when a writer dies before Close(); and truncated or corrupted
// LAZ give an InputError naming the file, never a crash, hang or huge allocation.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "core/error.h"
#include "io/las_format.h"
#include "io/las_reader.h"
#include "io/las_writer.h"
#include "io/laz_chunk_table.h"
#include "io/laz_chunk_writer.h"
#include "io/laz_point_reader.h"
#include "tests/support/las_points.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

using testing::ExpectSamePoints;

namespace fs = std::filesystem;
namespace lf = las_format;
using testing::TempDir;

std::vector<uint8_t> ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void WriteBytes(const fs::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                              static_cast<std::streamsize>(bytes.size()));
}

// Points using every field `pdrf` holds, varying like aerial data (returns, flight lines, channels).
std::vector<LasPoint> MakePoints(int pdrf, size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<LasPoint> pts(n);
  double t = 412345.25;
  for (size_t i = 0; i < n; ++i) {
    LasPoint& p = pts[i];
    p.xyz = {391234.567 + 0.01 * static_cast<double>(rng() % 100000), 5706543.21 + 0.731 * static_cast<double>(i % 5000),
             87.5 + 0.001 * static_cast<double>(rng() % 20000)};
    p.intensity = static_cast<uint16_t>(i % 9 == 0 ? rng() : 300 + i % 17);
    const bool extended = pdrf >= 6;
    p.number_of_returns = static_cast<uint8_t>(1 + (i / 4) % (extended ? 15 : 7));
    p.return_number = static_cast<uint8_t>(1 + i % p.number_of_returns);
    p.classification = static_cast<uint8_t>(extended ? (i / 50) % 256 : (i / 50) % 32);
    p.flags = static_cast<uint8_t>(i % 23 == 0 ? (extended ? 9 : 5) : 0);
    p.scanner_channel = static_cast<uint8_t>(extended ? (i / 1000) % 4 : 0);
    p.scan_direction = (i / 30) % 2 == 1;
    p.edge_of_flight_line = i % 101 == 0;
    p.scan_angle_deg = extended ? static_cast<float>(static_cast<int>(i % 4001) - 2000) * 0.006f
                                : static_cast<float>(static_cast<int>(i % 61) - 30);
    p.user_data = static_cast<uint8_t>(i / 777);
    p.point_source_id = static_cast<uint16_t>(1 + i / 3000);
    if (lf::HasGpsTime(pdrf)) {
      t += (i % 3 == 0) ? 1e-5 * (1 + rng() % 3) : 0.0;
      if (i % 10007 == 0) t += 3600.0;
      p.gps_time = t;
    }
    if (lf::HasRgb(pdrf)) {
      p.rgb = {static_cast<uint16_t>(256 * (i % 256)), static_cast<uint16_t>(rng() % 65536),
               static_cast<uint16_t>(i % 5 == 0 ? 0 : 4096)};
    }
    if (lf::HasNir(pdrf)) p.nir = static_cast<uint16_t>(i % 4 == 0 ? rng() : 1234);
  }
  return pts;
}

void Write(const fs::path& path, int minor, int pdrf, const std::vector<LasPoint>& pts, bool compressed,
           const std::vector<LasVlr>& vlrs = {}) {
  LasWriterOptions o;
  o.version_minor = minor;
  o.point_format = pdrf;
  o.compressed = compressed;
  o.offset = Eigen::Vector3d(391000, 5706000, 0);
  o.vlrs = vlrs;
  LasWriter w(path.string(), o);
  // Uneven batches: chunk boundaries fall inside them.
  for (size_t at = 0; at < pts.size();) {
    const size_t n = std::min<size_t>(pts.size() - at, 7919);
    w.WritePoints(pts.data() + at, n);
    at += n;
  }
  w.Close();
}

// `n` points of PDRF 6 (LAS 1.4) written as LAZ to `laz` and as LAS to DIR/twin.las beside it: the twin's points.
std::vector<LasPoint> WriteLazAndTwin(const fs::path& laz, size_t n, uint32_t seed) {
  const std::vector<LasPoint> pts = MakePoints(6, n, seed);
  Write(laz, 4, 6, pts, true);
  Write(laz.parent_path() / "twin.las", 4, 6, pts, false);
  return ReadAllLasPoints((laz.parent_path() / "twin.las").string());
}

struct Layout {
  int minor;
  int pdrf;
};
const Layout kLayouts[] = {{2, 0}, {2, 1}, {2, 2}, {2, 3}, {4, 0}, {4, 3}, {4, 6}, {4, 7}, {4, 8}};

TEST(LazWriterTest, EveryFormatDecodesToItsLasTwin) {
  TempDir dir;
  for (const Layout& l : kLayouts) {
    for (size_t n : {size_t{0}, size_t{1}, size_t{2}, size_t{3000}}) {
      SCOPED_TRACE("LAS 1." + std::to_string(l.minor) + " PDRF " + std::to_string(l.pdrf) + " n=" + std::to_string(n));
      const std::vector<LasPoint> pts = MakePoints(l.pdrf, n, 5);
      const fs::path las = dir / "twin.las";
      const fs::path laz = dir / "twin.laz";
      Write(las, l.minor, l.pdrf, pts, false);
      Write(laz, l.minor, l.pdrf, pts, true);
      LasHeader hs, hz;
      const std::vector<LasPoint> from_las = ReadAllLasPoints(las.string(), &hs);
      const std::vector<LasPoint> from_laz = ReadAllLasPoints(laz.string(), &hz);
      ExpectSamePoints(from_laz, from_las);
      EXPECT_EQ(hz.point_format, hs.point_format);
      EXPECT_EQ(hz.point_record_length, hs.point_record_length);
      EXPECT_EQ(hz.point_count, n);
      EXPECT_EQ(hz.points_by_return, hs.points_by_return);
      EXPECT_EQ(hz.min, hs.min);
      EXPECT_EQ(hz.max, hs.max);
      EXPECT_EQ(hz.vlrs.size(), 0u);  // the laszip VLR is the reader's business
      const std::vector<uint8_t> b = ReadBytes(laz);
      EXPECT_EQ(b[lf::kOffPdrf], l.pdrf | 0x80);
      const size_t header_size = lf::GetU16(&b[lf::kOffHeaderSize]);
      EXPECT_EQ(std::string(reinterpret_cast<const char*>(&b[header_size + 2])), "laszip encoded");
      EXPECT_EQ(lf::GetU16(&b[header_size + 18]), 22204);
      const uint64_t table = lf::GetU64(&b[lf::GetU32(&b[lf::kOffPointOffset])]);
      EXPECT_EQ(lf::GetU32(&b[table + 4]), n == 0 ? 0u : 1u);  // chunks
      if (n == 3000) {
        EXPECT_LT(b.size() * 2, fs::file_size(las));
      }
    }
  }
}

TEST(LazWriterTest, MultiChunkFileWithEvlrsAndFusedPoints) {
  TempDir dir;
  const std::vector<LasPoint> pts = MakePoints(7, 123457, 9);
  LasVlr evlr;
  evlr.user_id = "sacfuse";
  evlr.record_id = 7;
  evlr.data = {1, 2, 3, 4, 5};
  evlr.extended = true;
  Write(dir / "big.las", 4, 7, pts, false, {evlr});
  Write(dir / "big.laz", 4, 7, pts, true, {evlr});
  LasHeader h;
  ExpectSamePoints(ReadAllLasPoints((dir / "big.laz").string(), &h), ReadAllLasPoints((dir / "big.las").string()));
  ASSERT_EQ(h.vlrs.size(), 1u);
  EXPECT_EQ(h.vlrs[0].data, evlr.data);
  const std::vector<uint8_t> b = ReadBytes(dir / "big.laz");
  const uint64_t table = lf::GetU64(&b[lf::GetU32(&b[lf::kOffPointOffset])]);
  EXPECT_EQ(lf::GetU32(&b[table + 4]), 3u);  // 50,000 + 50,000 + 23,457
  EXPECT_GT(lf::GetU64(&b[lf::kOffEvlrStart]), table);

  // Fused points through Write(), LAS 1.2 format 3 and LAS 1.4 format 7.
  for (int minor : {2, 4}) {
    std::vector<FusedPoint> fused(60001);
    for (size_t i = 0; i < fused.size(); ++i) {
      fused[i].point_in_world = {390123.4567 + 0.013 * static_cast<double>(i % 977), 5705123.4567 + 0.002 * i, 52.3};
      fused[i].rgb = {static_cast<uint8_t>(i), static_cast<uint8_t>(i / 7), 200};
      fused[i].view_index = static_cast<uint32_t>(i / 5000);
    }
    for (bool compressed : {false, true}) {
      LasWriterOptions o;
      o.version_minor = minor;
      o.compressed = compressed;
      LasWriter w((dir / (compressed ? "fused.laz" : "fused.las")).string(), o);
      w.Write(fused.data(), fused.size());
      w.Close();
    }
    ExpectSamePoints(ReadAllLasPoints((dir / "fused.laz").string()), ReadAllLasPoints((dir / "fused.las").string()));
  }
}

// Chunks are compressed in batches of 8 (LazChunkWriter::kBatchChunks), one chunk per thread at a time
// (parallel_chunks): the same bytes on 1 and 2 threads, every chunk of 50,000 points but the last, and the points of
// the LAS twin.
TEST(LazWriterTest, ParallelBatchesGiveTheSameFileForAnyThreadCount) {
  TempDir dir;
  const size_t n = 9 * 50000 + 7;  // two batches of chunks, the last chunk 7 points
  const std::vector<LasPoint> pts = MakePoints(6, n, 4);
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    EXPECT_EQ(LazChunkWriter(6, lf::BaseRecordSize(6)).parallel_chunks(), 1u);
    Write(dir / "one.laz", 4, 6, pts, true);
  }
  {
    tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
    EXPECT_EQ(LazChunkWriter(6, lf::BaseRecordSize(6)).parallel_chunks(), 2u);
    Write(dir / "two.laz", 4, 6, pts, true);
  }
  {
    tbb::global_control many(tbb::global_control::max_allowed_parallelism, 64);
    EXPECT_EQ(LazChunkWriter(6, lf::BaseRecordSize(6)).parallel_chunks(), LazChunkWriter::kBatchChunks);
  }
  Write(dir / "twin.las", 4, 6, pts, false);
  std::vector<uint8_t> a = ReadBytes(dir / "one.laz");
  std::vector<uint8_t> b = ReadBytes(dir / "two.laz");
  ASSERT_EQ(a.size(), b.size());
  // The header's creation day and year may differ if the two writes straddle midnight; compare the rest.
  for (size_t i = lf::kOffCreationDay; i < lf::kOffCreationDay + 4; ++i) a[i] = b[i] = 0;
  EXPECT_TRUE(a == b);
  const uint64_t table = lf::GetU64(&a[lf::GetU32(&a[lf::kOffPointOffset])]);
  EXPECT_EQ(lf::GetU32(&a[table + 4]), 10u);
  ExpectSamePoints(ReadAllLasPoints((dir / "two.laz").string()), ReadAllLasPoints((dir / "twin.las").string()));
}

// The reader decodes batches of chunks in parallel (LazPointReader::BatchChunks) but behaves as a one-chunk-at-a-time
// decoder: on 1 and 2 threads, a file of 10 chunks (two batches) whose chunk k says it holds a wrong number of
// points delivers exactly the 50,000 * k points before it, equal to those of the LAS twin, then an InputError naming
// chunk k; a chunk in the middle of the first batch and the first chunk of the second.
TEST(LazWriterTest, ParallelDecodingDeliversEveryPointBeforeACorruptChunk) {
  TempDir dir;
  const std::vector<LasPoint> twin = WriteLazAndTwin(dir / "good.laz", 9 * 50000 + 7, 5);
  const std::vector<uint8_t> good = ReadBytes(dir / "good.laz");
  const size_t point_offset = lf::GetU32(&good[lf::kOffPointOffset]);
  const size_t record_length = lf::GetU16(&good[lf::kOffRecordLength]);
  const uint64_t table = lf::GetU64(&good[point_offset]);
  const std::vector<laz::ChunkEntry> entries =
      laz::DecodeChunkTable(&good[table + 8], good.size() - table - 8, 10, false);
  ASSERT_EQ(entries.size(), 10u);
  for (size_t bad : {3u, 8u}) {
    std::vector<uint8_t> b = good;
    size_t start = point_offset + 8;
    for (size_t i = 0; i < bad; ++i) start += entries[i].bytes;
    lf::PutU32(&b[start + record_length], 1);  // a layered chunk's point count follows its raw first record
    WriteBytes(dir / "bad.laz", b);
    for (int threads : {1, 2}) {
      SCOPED_TRACE(::testing::Message() << "chunk " << bad << ", " << threads << " threads");
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      LasReader reader((dir / "bad.laz").string());
      std::vector<LasPoint> got, block;
      try {
        while (reader.Read(&block, 1000) > 0) got.insert(got.end(), block.begin(), block.end());
        ADD_FAILURE() << "the corrupt chunk was read";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("LAZ chunk " + std::to_string(bad) + " of 10"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("chunk says it holds 1 points"), std::string::npos) << e.what();
      }
      ASSERT_EQ(got.size(), bad * 50000);
      ExpectSamePoints(got, std::vector<LasPoint>(twin.begin(), twin.begin() + static_cast<std::ptrdiff_t>(got.size())));
    }
  }
}

// A batch of the reader holds two chunks per thread, at least 8. A file of 13 chunks, more than a batch holds on
// 1, 2 and 6 threads (8, 8 and 12 chunks), reads as the same points as its LAS twin on each, whether a Read takes
// fewer points than a chunk or more than a batch (the records are converted where the decoder put them, a batch's
// end falling inside a Read).
TEST(LazWriterTest, ReadingGivesTheSamePointsOnAnyThreadCount) {
  EXPECT_EQ(LazPointReader::BatchChunks(1), 8u);
  EXPECT_EQ(LazPointReader::BatchChunks(2), 8u);
  EXPECT_EQ(LazPointReader::BatchChunks(8), 16u);
  EXPECT_EQ(LazPointReader::BatchChunks(64), 128u);
  TempDir dir;
  const size_t n = 12 * 50000 + 13;
  const std::vector<LasPoint> twin = WriteLazAndTwin(dir / "many.laz", n, 6);
  ASSERT_EQ(twin.size(), n);
  struct Case {
    int threads;
    size_t step;  // points per Read
  };
  for (const Case c : {Case{1, 1000}, Case{2, 700001}, Case{6, 700001}}) {
    SCOPED_TRACE(::testing::Message() << c.threads << " threads, reads of " << c.step);
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, c.threads);
    tbb::task_arena arena(c.threads);
    std::vector<LasPoint> got, block;
    arena.execute([&] {
      LasReader reader((dir / "many.laz").string());
      while (reader.Read(&block, c.step) > 0) got.insert(got.end(), block.begin(), block.end());
    });
    ASSERT_EQ(got.size(), n);
    ExpectSamePoints(got, twin);
  }
}

// A LAZ file whose chunk 10 of 12 was cut to its first 40 bytes, chunk 11 and the chunk table following it: with
// the table unchanged, the chunks listed run into the table (an error when the file is opened); with the table
// saying 40 bytes, the reading delivers every point of chunks 0-9 and then fails in chunk 10. Either way an
// InputError naming the file (and the chunk), on 1 and 2 threads.
TEST(LazWriterTest, ACutChunkGivesAnErrorNamingTheFileAndTheChunk) {
  TempDir dir;
  const size_t n = 11 * 50000 + 5;  // 12 chunks: two batches
  Write(dir / "good.laz", 4, 6, MakePoints(6, n, 8), true);
  const std::vector<uint8_t> good = ReadBytes(dir / "good.laz");
  const size_t point_offset = lf::GetU32(&good[lf::kOffPointOffset]);
  const uint64_t table = lf::GetU64(&good[point_offset]);
  std::vector<laz::ChunkEntry> entries = laz::DecodeChunkTable(&good[table + 8], good.size() - table - 8, 12, false);
  ASSERT_EQ(entries.size(), 12u);
  size_t start = point_offset + 8;  // chunk 10's
  for (size_t i = 0; i < 10; ++i) start += entries[i].bytes;
  std::vector<uint8_t> cut(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(start + 40));
  cut.insert(cut.end(), good.begin() + static_cast<std::ptrdiff_t>(start + entries[10].bytes),
             good.begin() + static_cast<std::ptrdiff_t>(table));
  lf::PutU64(&cut[point_offset], cut.size());
  const size_t table_at = cut.size();
  for (const bool table_says_cut : {false, true}) {
    cut.resize(table_at);
    if (table_says_cut) entries[10].bytes = 40;
    const std::vector<uint8_t> coded = laz::EncodeChunkTable(entries, false);  // with its version and count
    cut.insert(cut.end(), coded.begin(), coded.end());
    const std::string path = (dir / "cut.laz").string();
    WriteBytes(path, cut);
    for (const int threads : {1, 2}) {
      SCOPED_TRACE(::testing::Message() << threads << " threads, table says cut: " << table_says_cut);
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      size_t read = 0;
      try {
        LasReader reader(path);
        std::vector<LasPoint> block;
        while (size_t k = reader.Read(&block, 50000)) read += k;  // a chunk per Read: the last one fails whole
        ADD_FAILURE() << "the cut chunk was read";
      } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(path), std::string::npos) << what;
        EXPECT_NE(what.find(table_says_cut ? "LAZ chunk 10 of 12" : "runs into the chunk table"), std::string::npos)
            << what;
      }
      EXPECT_EQ(read, table_says_cut ? 10 * 50000 : 0);
    }
  }
}

// AppendLaz (the tile merge) copies the full chunks of LAZ files of the writer's layout as stored and codes only
// their last, shorter chunks: the file holds exactly the points of a point-by-point merge, full chunks first as
// they come and buffered points after, with the header (count, bounds, returns) of the LAS twin of that order;
// files of another layout, scale or offset, LAS files and LAS output are refused before anything is written.
TEST(LazWriterTest, AppendLazCopiesFullChunksAndCodesTheLastOnes) {
  TempDir dir;
  for (const Layout& l : {Layout{4, 7}, Layout{2, 3}}) {
    SCOPED_TRACE("LAS 1." + std::to_string(l.minor) + " PDRF " + std::to_string(l.pdrf));
    const std::vector<LasPoint> a = MakePoints(l.pdrf, 123457, 11);  // 2 full chunks + 23,457
    const std::vector<LasPoint> b = MakePoints(l.pdrf, 100000, 12);  // 2 full chunks, no last one
    const std::vector<LasPoint> c = MakePoints(l.pdrf, 777, 13);     // no full chunk
    const std::vector<LasPoint> first = MakePoints(l.pdrf, 500, 14);   // written before, still buffered
    Write(dir / "a.laz", l.minor, l.pdrf, a, true);
    Write(dir / "b.laz", l.minor, l.pdrf, b, true);
    Write(dir / "c.laz", l.minor, l.pdrf, c, true);
    Write(dir / "a.las", l.minor, l.pdrf, a, false);
    LasWriterOptions o;
    o.version_minor = l.minor;
    o.point_format = l.pdrf;
    o.compressed = true;
    o.offset = Eigen::Vector3d(391000, 5706000, 0);
    {
      LasWriter w((dir / "merged.laz").string(), o);
      w.WritePoints(first.data(), first.size());
      // Refused, nothing written: a LAS file, another offset, another point format.
      LasReader as_las((dir / "a.las").string());
      EXPECT_FALSE(w.AppendLaz(as_las));
      LasWriterOptions shifted = o;
      shifted.offset = Eigen::Vector3d(391000, 5706000, 100);
      {
        LasWriter other((dir / "shifted.laz").string(), shifted);
        other.WritePoints(c.data(), c.size());
        other.Close();
      }
      LasReader shifted_reader((dir / "shifted.laz").string());
      EXPECT_FALSE(w.AppendLaz(shifted_reader));
      Write(dir / "other_format.laz", 4, l.pdrf == 7 ? 6 : 1, MakePoints(l.pdrf == 7 ? 6 : 1, 50, 1), true);
      LasReader other_format((dir / "other_format.laz").string());
      EXPECT_FALSE(w.AppendLaz(other_format));
      EXPECT_EQ(w.num_points(), first.size());
      for (const char* name : {"a.laz", "b.laz", "c.laz"}) {
        LasReader reader((dir / name).string());
        std::vector<LasPoint> some;
        reader.Read(&some, 10);  // AppendLaz rewinds
        EXPECT_TRUE(w.AppendLaz(reader)) << name;
      }
      w.Close();
    }
    // Copied: a's and b's full chunks; then the buffered points: first, a's last 23,457, c.
    std::vector<LasPoint> expected(a.begin(), a.begin() + 100000);
    expected.insert(expected.end(), b.begin(), b.end());
    expected.insert(expected.end(), first.begin(), first.end());
    expected.insert(expected.end(), a.begin() + 100000, a.end());
    expected.insert(expected.end(), c.begin(), c.end());
    Write(dir / "expected.las", l.minor, l.pdrf, expected, false);
    LasHeader got_header, twin_header;
    const std::vector<LasPoint> got = ReadAllLasPoints((dir / "merged.laz").string(), &got_header);
    ExpectSamePoints(got, ReadAllLasPoints((dir / "expected.las").string(), &twin_header));
    EXPECT_EQ(got_header.point_count, expected.size());
    EXPECT_EQ(got_header.points_by_return, twin_header.points_by_return);
    EXPECT_EQ(got_header.min, twin_header.min);
    EXPECT_EQ(got_header.max, twin_header.max);
    const std::vector<uint8_t> bytes = ReadBytes(dir / "merged.laz");
    const uint64_t table = lf::GetU64(&bytes[lf::GetU32(&bytes[lf::kOffPointOffset])]);
    EXPECT_EQ(lf::GetU32(&bytes[table + 4]), 5u);  // 4 copied, 1 coded
    // LAS output: every file is refused (the merge then decodes it).
    LasWriterOptions las = o;
    las.compressed = false;
    LasWriter w((dir / "merged.las").string(), las);
    LasReader reader((dir / "a.laz").string());
    EXPECT_FALSE(w.AppendLaz(reader));
  }
}

// The merge's point order depends on how many records the writer buffers (copied chunks land ahead of them), so
// that must not follow the thread count: five files of one full chunk and a 30,000-point tail each (150,000 tail
// points, more than one chunk buffered) merge to the same bytes on 1 and 2 threads.
TEST(LazWriterTest, AppendLazGivesTheSameFileForAnyThreadCount) {
  TempDir dir;
  for (int i = 0; i < 5; ++i) {
    Write(dir / ("part" + std::to_string(i) + ".laz"), 4, 6, MakePoints(6, 80000, 20 + i), true);
  }
  auto merge = [&](const std::string& name, int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
    LasWriterOptions o;
    o.version_minor = 4;
    o.point_format = 6;
    o.compressed = true;
    o.offset = Eigen::Vector3d(391000, 5706000, 0);
    LasWriter w((dir / name).string(), o);
    for (int i = 0; i < 5; ++i) {
      LasReader reader((dir / ("part" + std::to_string(i) + ".laz")).string());
      EXPECT_TRUE(w.AppendLaz(reader));
    }
    w.Close();
    std::vector<uint8_t> bytes = ReadBytes(dir / name);
    for (size_t k = lf::kOffCreationDay; k < lf::kOffCreationDay + 4; ++k) bytes[k] = 0;
    return bytes;
  };
  const std::vector<uint8_t> one = merge("one.laz", 1);
  EXPECT_TRUE(one == merge("two.laz", 2));
  EXPECT_EQ(ReadAllLasPoints((dir / "one.laz").string()).size(), 5u * 80000u);
}

TEST(LazWriterTest, NoFileWithoutCloseAndReaderRewinds) {
  TempDir dir;
  const std::vector<LasPoint> pts = MakePoints(3, 70000, 2);
  {
    LasWriterOptions o;
    o.version_minor = 2;
    o.compressed = true;
    LasWriter w((dir / "killed.laz").string(), o);
    w.WritePoints(pts.data(), pts.size());
  }
  EXPECT_TRUE(fs::is_empty(dir.path()));
  Write(dir / "a.laz", 2, 3, pts, true);
  LasReader reader((dir / "a.laz").string());
  std::vector<LasPoint> first, again;
  ASSERT_EQ(reader.Read(&first, 60000), 60000u);
  reader.Rewind();
  ASSERT_EQ(reader.Read(&again, 60000), 60000u);
  ExpectSamePoints(first, again);
}

void ExpectInputError(const fs::path& path, const std::string& word) {
  try {
    ReadAllLasPoints(path.string());
    ADD_FAILURE() << path << " was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
  }
}

TEST(LazWriterTest, TruncatedOrCorruptLazGivesInputError) {
  TempDir dir;
  for (int pdrf : {3, 7}) {
    SCOPED_TRACE(pdrf);
    Write(dir / "ok.laz", pdrf == 3 ? 2 : 4, pdrf, MakePoints(pdrf, 120000, 4), true);
    const std::vector<uint8_t> good = ReadBytes(dir / "ok.laz");
    const size_t point_offset = lf::GetU32(&good[lf::kOffPointOffset]);
    const uint64_t table = lf::GetU64(&good[point_offset]);
    // Truncated anywhere in the point data or the chunk table.
    for (size_t keep : {point_offset + 4, point_offset + 1000, static_cast<size_t>(table) - 10,
                        static_cast<size_t>(table) + 3, static_cast<size_t>(table) + 9}) {
      std::vector<uint8_t> b(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(keep));
      WriteBytes(dir / "cut.laz", b);
      ExpectInputError(dir / "cut.laz", "LAZ");
    }
    // A chunk table offset pointing nowhere, an impossible number of chunks.
    std::vector<uint8_t> b = good;
    lf::PutU64(&b[point_offset], uint64_t{1} << 40);
    WriteBytes(dir / "offset.laz", b);
    ExpectInputError(dir / "offset.laz", "chunk table offset");
    b = good;
    lf::PutU32(&b[table + 4], 0xFFFFFFF0u);
    WriteBytes(dir / "chunks.laz", b);
    ExpectInputError(dir / "chunks.laz", "chunks");
    // Garbage inside the compressed points: an InputError or wrong values, never a crash or hang.
    std::mt19937 rng(1);
    for (int trial = 0; trial < 20; ++trial) {
      b = good;
      const size_t at = point_offset + 8 + rng() % (static_cast<size_t>(table) - point_offset - 8);
      for (int k = 0; k < 16 && at + k < table; ++k) b[at + k] = static_cast<uint8_t>(rng());
      WriteBytes(dir / "garbage.laz", b);
      try {
        ReadAllLasPoints((dir / "garbage.laz").string());
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("LAZ"), std::string::npos) << e.what();
      }
    }
  }
}

}  // namespace
}  // namespace sacfuse
