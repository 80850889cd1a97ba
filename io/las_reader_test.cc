#include "io/las_reader.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/las_writer.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

std::vector<uint8_t> ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
void WriteBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}
void PutU16(std::vector<uint8_t>* b, size_t at, uint16_t v) {
  (*b)[at] = static_cast<uint8_t>(v);
  (*b)[at + 1] = static_cast<uint8_t>(v >> 8);
}
void PutU32(std::vector<uint8_t>* b, size_t at, uint32_t v) {
  for (int i = 0; i < 4; ++i) (*b)[at + i] = static_cast<uint8_t>(v >> (8 * i));
}
void PutU64(std::vector<uint8_t>* b, size_t at, uint64_t v) {
  for (int i = 0; i < 8; ++i) (*b)[at + i] = static_cast<uint8_t>(v >> (8 * i));
}

// A valid file made by our writer: `n` points, optionally one VLR of `vlr_size` bytes.
std::string MakeValidFile(const TempDir& dir, const std::string& name, int version_minor, size_t n,
                          size_t vlr_size = 0) {
  const std::string path = (dir / name).string();
  LasWriterOptions options;
  options.version_minor = version_minor;
  if (vlr_size > 0) {
    LasVlr vlr;
    vlr.user_id = "LASF_Projection";
    vlr.record_id = 2112;
    std::string wkt = "GEOGCS[\"WGS 84\"]";
    wkt.resize(vlr_size, '\0');
    vlr.data.assign(wkt.begin(), wkt.end());
    options.vlrs = {vlr};
  }
  LasWriter writer(path, options);
  std::vector<FusedPoint> points(n);
  for (size_t i = 0; i < n; ++i) {
    points[i].point_in_world = {600000.0 + 0.37 * i, 5400000.0 - 0.11 * i, 100.0 + 0.01 * i};
    points[i].rgb = {static_cast<uint8_t>(i), 2, 3};
    points[i].view_index = static_cast<uint32_t>(i % 50);
  }
  writer.Write(points.data(), points.size());
  writer.Close();
  return path;
}

// Expects an InputError naming `path` whose message contains `fragment`.
void ExpectInputError(const std::string& path, const std::string& fragment) {
  try {
    LasReader reader(path);
    std::vector<LasPoint> points;
    while (reader.Read(&points, 1000) > 0) {
    }
    ADD_FAILURE() << path << ": no InputError (expected '" << fragment << "')";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

// Copies a valid file, applies `edit` to its bytes, and returns the new path.
std::string Corrupt(const TempDir& dir, const std::string& source, const std::string& name,
                    const std::function<void(std::vector<uint8_t>*)>& edit) {
  std::vector<uint8_t> bytes = ReadBytes(source);
  edit(&bytes);
  const std::string path = (dir / name).string();
  WriteBytes(path, bytes);
  return path;
}

TEST(LasReaderTest, ReadsInChunksAndRewinds) {
  TempDir dir;
  const std::string path = MakeValidFile(dir, "ok.las", 4, 1000, 40);
  LasHeader header;
  const std::vector<LasPoint> all = ReadAllLasPoints(path, &header);
  ASSERT_EQ(all.size(), 1000u);
  EXPECT_EQ(header.Wkt(), "GEOGCS[\"WGS 84\"]");  // trailing NULs dropped
  ASSERT_EQ(header.vlrs.size(), 1u);
  EXPECT_EQ(header.vlrs[0].data.size(), 40u);
  LasReader reader(path);
  std::vector<LasPoint> chunk;
  size_t seen = 0;
  while (size_t n = reader.Read(&chunk, 7)) {
    ASSERT_LE(n, 7u);
    ASSERT_EQ(chunk.size(), n);
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(chunk[i].xyz, all[seen + i].xyz);
    seen += n;
  }
  EXPECT_EQ(seen, 1000u);
  EXPECT_EQ(reader.Read(&chunk, 7), 0u);
  EXPECT_TRUE(chunk.empty());
  reader.Rewind();
  ASSERT_EQ(reader.Read(&chunk, 3), 3u);
  EXPECT_EQ(chunk[2].xyz, all[2].xyz);
  EXPECT_EQ(chunk[2].point_source_id, 3);
}

TEST(LasReaderTest, TruncatedFileSaysHowManyPointsFit) {
  TempDir dir;
  for (int minor : {2, 4}) {
    const std::string valid = MakeValidFile(dir, "v" + std::to_string(minor) + ".las", minor, 100);
    const std::string cut = Corrupt(dir, valid, "cut" + std::to_string(minor) + ".las",
                                    [](std::vector<uint8_t>* b) { b->resize(b->size() - 10); });
    ExpectInputError(cut, "truncated");
    ExpectInputError(cut, "can hold only 99");
    ExpectInputError(cut, "says 100 points");
  }
}

TEST(LasReaderTest, RejectsCorruptHeaders) {
  TempDir dir;
  const std::string v12 = MakeValidFile(dir, "v12.las", 2, 10);
  const std::string v14 = MakeValidFile(dir, "v14.las", 4, 10, 16);
  ExpectInputError(Corrupt(dir, v12, "sig.las", [](auto* b) { (*b)[3] = 'X'; }), "signature");
  ExpectInputError(Corrupt(dir, v12, "short.las", [](auto* b) { b->resize(100); }), "smaller than a LAS header");
  ExpectInputError(Corrupt(dir, v14, "short14.las", [](auto* b) { b->resize(300); }), "smaller than its header");
  ExpectInputError(Corrupt(dir, v12, "reclen.las", [](auto* b) { PutU16(b, 105, 20); }),
                   "point record length 20 is smaller than the 34 bytes of point format 3");
  ExpectInputError(Corrupt(dir, v14, "hsize.las", [](auto* b) { PutU16(b, 94, 227); }),
                   "header size 227 is smaller than the 375 bytes of LAS 1.4");
  ExpectInputError(Corrupt(dir, v12, "offlow.las", [](auto* b) { PutU32(b, 96, 100); }),
                   "offset to point data 100 is smaller than the header size 227");
  ExpectInputError(Corrupt(dir, v12, "offhigh.las", [](auto* b) { PutU32(b, 96, 1u << 30); }),
                   "beyond the end of the file");
  ExpectInputError(Corrupt(dir, v12, "pdrf.las", [](auto* b) { (*b)[104] = 11; }),
                   "unknown point data record format 11");
  ExpectInputError(Corrupt(dir, v12, "v15.las", [](auto* b) { (*b)[25] = 5; }), "LAS version 1.5");
  ExpectInputError(Corrupt(dir, v14, "vlrlen.las", [](auto* b) { PutU16(b, 375 + 20, 500); }),
                   "flows into point data");
  ExpectInputError(Corrupt(dir, v14, "evlr.las",
                           [](auto* b) {
                             PutU64(b, 235, b->size());  // 20 bytes where a 60-byte EVLR header is due
                             b->resize(b->size() + 20);
                             PutU32(b, 243, 1);
                           }),
                   "EVLR 1 of 1");
  ExpectInputError(Corrupt(dir, v14, "evlrin.las",
                           [](auto* b) {
                             PutU64(b, 235, 400);
                             PutU32(b, 243, 1);
                           }),
                   "inside the point data");
}

TEST(LasReaderTest, DetectsLazByContentNotByName) {
  TempDir dir;
  const std::string v12 = MakeValidFile(dir, "v12.las", 2, 10);
  ExpectInputError(Corrupt(dir, v12, "bit7.las", [](auto* b) { (*b)[104] |= 0x80; }),
                   "LAZ compression bit set but there is no laszip VLR");
  // An uncompressed file named .laz is read as what it is.
  EXPECT_EQ(ReadAllLasPoints(Corrupt(dir, v12, "named.laz", [](auto*) {})).size(), 10u);
  const std::string v14 = MakeValidFile(dir, "v14.las", 4, 10, 16);
  ExpectInputError(Corrupt(dir, v14, "vlr.las",
                           [](auto* b) {
                             std::memset(&(*b)[375 + 2], 0, 16);
                             std::memcpy(&(*b)[375 + 2], "laszip encoded", 14);
                             PutU16(b, 375 + 18, 22204);
                           }),
                   "LAZ");
}

TEST(LasReaderTest, ToleratesOverstatedVlrCountOnlyWhenVlrsEndAtThePoints) {
  TempDir dir;
  const std::string v14 = MakeValidFile(dir, "v14.las", 4, 10, 16);
  const std::string extra = Corrupt(dir, v14, "count.las", [](auto* b) { PutU32(b, 100, 3); });
  LasHeader header;
  EXPECT_EQ(ReadAllLasPoints(extra, &header).size(), 10u);
  EXPECT_EQ(header.vlrs.size(), 1u);
  // With a gap of 30 bytes left before the points, the second "VLR" header would overlap them.
  const std::string gap = Corrupt(dir, v14, "gap.las", [](std::vector<uint8_t>* b) {
    PutU32(b, 100, 2);
    b->insert(b->begin() + 375 + 54 + 16, 30, 0);
    PutU32(b, 96, 375 + 54 + 16 + 30);
  });
  ExpectInputError(gap, "flows into point data");
}

TEST(LasReaderTest, ExtraBytesPerRecordAreSkipped) {
  TempDir dir;
  const std::string v12 = MakeValidFile(dir, "v12.las", 2, 50);
  const std::vector<LasPoint> expected = ReadAllLasPoints(v12);
  const std::string wide = Corrupt(dir, v12, "wide.las", [](std::vector<uint8_t>* b) {
    std::vector<uint8_t> out(b->begin(), b->begin() + 227);
    for (size_t i = 0; i < 50; ++i) {
      out.insert(out.end(), b->begin() + 227 + 34 * i, b->begin() + 227 + 34 * (i + 1));
      out.insert(out.end(), {0xEE, 0xEE, 0xEE, 0xEE, 0xEE});
    }
    PutU16(&out, 105, 39);
    *b = out;
  });
  LasHeader header;
  const std::vector<LasPoint> got = ReadAllLasPoints(wide, &header);
  EXPECT_EQ(header.point_record_length, 39);
  ASSERT_EQ(got.size(), expected.size());
  for (size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].xyz, expected[i].xyz);
    ASSERT_EQ(got[i].rgb, expected[i].rgb);
    ASSERT_EQ(got[i].point_source_id, expected[i].point_source_id);
  }
}

TEST(LasReaderTest, Las14FallsBackToTheLegacyCountWhenThe64BitCountIsZero) {
  TempDir dir;
  const std::string v14 = MakeValidFile(dir, "v14.las", 4, 25);
  const std::string legacy = Corrupt(dir, v14, "legacy.las", [](auto* b) {
    PutU64(b, 247, 0);
    PutU32(b, 107, 25);
  });
  LasHeader header;
  EXPECT_EQ(ReadAllLasPoints(legacy, &header).size(), 25u);
  EXPECT_EQ(header.point_count, 25u);
  // Both set but different: the 64-bit count wins (PDAL, laspy), checked against the file size.
  const std::string both = Corrupt(dir, v14, "both.las", [](auto* b) { PutU32(b, 107, 7); });
  EXPECT_EQ(ReadAllLasPoints(both).size(), 25u);
}

TEST(LasReaderTest, MissingFileIsAnInputError) {
  TempDir dir;
  ExpectInputError((dir / "nope.las").string(), "cannot open");
}

}  // namespace
}  // namespace sacfuse
