#include "io/las_validate.h"

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/crs.h"
#include "io/las_crs.h"
#include "io/las_format.h"
#include "io/las_reader.h"
#include "io/las_writer.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace lf = las_format;
using testing::TempDir;

constexpr size_t kPoints = 300;

std::vector<uint8_t> ReadBytes(const std::string& path) {
  const std::string s = testing::ReadFileBytes(path);
  return std::vector<uint8_t>(s.begin(), s.end());
}
void WriteBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

LasVlr DummyVlr() {
  LasVlr v;
  v.user_id = "sacfuse";
  v.record_id = 1;
  v.description = "test payload";
  v.data.assign(20, 7);
  return v;
}

// Points within 100 m of the automatic offset (500000, 5706000, 0), UTM-sized; distinct colours and sources.
std::vector<LasPoint> TestPoints(bool gps_week_time = true) {
  std::vector<LasPoint> pts(kPoints);
  for (size_t i = 0; i < kPoints; ++i) {
    LasPoint& p = pts[i];
    p.xyz = {500010.0 + 0.137 * i, 5706020.0 + 0.071 * i, 95.0 + 0.013 * i};
    p.rgb = {static_cast<uint16_t>(256 * (i % 256)), 512, 1024};
    p.point_source_id = static_cast<uint16_t>(1 + i % 9);
    p.gps_time = gps_week_time ? 1000.0 + i : 1.0e9 + i;
  }
  return pts;
}

struct FileSpec {
  int minor = 4;
  std::string crs = "EPSG:25832";
  bool dummy_vlr = true;
  size_t points = kPoints;
  bool gps_week_time = true;
  std::function<void(LasWriterOptions*)> edit_options;
};

std::string MakeFile(const TempDir& dir, const std::string& name, const FileSpec& spec) {
  const std::string path = (dir / name).string();
  LasWriterOptions o;
  o.version_minor = spec.minor;
  AddCrsToLasOptions(ParseProjectCrs(spec.crs), &o);
  if (spec.dummy_vlr) o.vlrs.push_back(DummyVlr());  // last, just before the points
  if (spec.edit_options) spec.edit_options(&o);
  LasWriter w(path, o);
  const std::vector<LasPoint> pts = TestPoints(spec.gps_week_time);
  w.WritePoints(pts.data(), spec.points);
  w.Close();
  return path;
}

// Copies `source` with `edit` applied to its bytes.
std::string Patched(const TempDir& dir, const std::string& source, const std::string& name,
                    const std::function<void(std::vector<uint8_t>*)>& edit) {
  std::vector<uint8_t> b = ReadBytes(source);
  edit(&b);
  const std::string path = (dir / name).string();
  WriteBytes(path, b);
  return path;
}

size_t PointOffset(const std::vector<uint8_t>& b) { return lf::GetU32(&b[lf::kOffPointOffset]); }
size_t RecordLength(const std::vector<uint8_t>& b) { return lf::GetU16(&b[lf::kOffRecordLength]); }

// Exactly one finding, of `rule`, mentioning `detail`.
void ExpectOnly(const std::string& path, const std::string& rule, const std::string& detail = "") {
  const std::vector<std::string> findings = ValidateLasFile(path);
  ASSERT_EQ(findings.size(), 1u) << ::testing::PrintToString(findings);
  EXPECT_EQ(findings[0].rfind(rule + ": ", 0), 0u) << findings[0];
  EXPECT_NE(findings[0].find(detail), std::string::npos) << findings[0];
}

class LasValidateTest : public ::testing::Test {
 protected:
  TempDir dir;
  std::string good14 = MakeFile(dir, "good14.las", FileSpec{});
  std::string good12 = MakeFile(dir, "good12.las", Las12());

  static FileSpec Las12() {
    FileSpec s;
    s.minor = 2;
    return s;
  }
};

TEST_F(LasValidateTest, OurFilesHaveNoFindings) {
  EXPECT_EQ(ValidateLasFile(good14), std::vector<std::string>{});
  EXPECT_EQ(ValidateLasFile(good12), std::vector<std::string>{});
  for (const char* crs : {"", "EPSG:32633", "ENU:51.5,7.46,120"}) {
    for (int minor : {2, 4}) {
      FileSpec s;
      s.minor = minor;
      s.crs = crs;
      s.dummy_vlr = false;
      EXPECT_EQ(ValidateLasFile(MakeFile(dir, "x.las", s)), std::vector<std::string>{}) << crs << " " << minor;
    }
  }
  FileSpec one;
  one.points = 1;
  EXPECT_EQ(ValidateLasFile(MakeFile(dir, "one.las", one)), std::vector<std::string>{});
  FileSpec absolute_gps;
  absolute_gps.gps_week_time = false;
  absolute_gps.edit_options = [](LasWriterOptions* o) { o->global_encoding_extra_bits |= 0x1; };
  EXPECT_EQ(ValidateLasFile(MakeFile(dir, "gps.las", absolute_gps)), std::vector<std::string>{});
  FileSpec empty14;
  empty14.points = 0;
  EXPECT_EQ(ValidateLasFile(MakeFile(dir, "empty14.las", empty14)), std::vector<std::string>{});  // a 1.4 warning only
}

TEST_F(LasValidateTest, NotALasFile) {
  const std::string path = (dir / "text.las").string();
  WriteBytes(path, std::vector<uint8_t>(300, 'x'));
  ExpectOnly(path, "file", "signature");
  ExpectOnly((dir / "missing.las").string(), "file", "cannot open");
}

TEST_F(LasValidateTest, HeaderSizeTooSmall) {
  FileSpec s;
  s.minor = 2;
  s.dummy_vlr = false;
  s.crs = "";
  const std::string plain = MakeFile(dir, "plain12.las", s);
  ExpectOnly(Patched(dir, plain, "b.las", [](auto* b) { lf::PutU16(&(*b)[lf::kOffHeaderSize], 226); }),
             "header size", "at least 227");
}

TEST_F(LasValidateTest, VlrFlowsIntoPointData) {
  // The last VLR (the dummy, 20 bytes) claims 30: header + VLRs end 10 bytes past the point offset.
  ExpectOnly(Patched(dir, good14, "b.las",
                     [](auto* b) { lf::PutU16(&(*b)[PointOffset(*b) - 20 - lf::kVlrHeaderSize + 20], 30); }),
             "offset to point data", "flows into the point data");
}

TEST_F(LasValidateTest, RecordLengthSmallerThanTheFormat) {
  ExpectOnly(Patched(dir, good14, "b.las", [](auto* b) { lf::PutU16(&(*b)[lf::kOffRecordLength], 35); }),
             "record length", "needs at least 36");
}

TEST_F(LasValidateTest, PointFormatNotAllowedForTheVersion) {
  ExpectOnly(Patched(dir, good12, "b.las", [](auto* b) { (*b)[lf::kOffVersionMinor] = 1; }), "point format",
             "not allowed in LAS 1.1");
}

TEST_F(LasValidateTest, FileSizeTruncatedOrTrailingBytes) {
  ExpectOnly(Patched(dir, good14, "t.las", [](auto* b) { b->resize(b->size() - 10); }), "file size", "truncated");
  ExpectOnly(Patched(dir, good12, "x.las", [](auto* b) { b->insert(b->end(), 7, 0); }), "file size",
             "7 bytes after the points");
}

TEST_F(LasValidateTest, LegacyCountsInLas14) {
  ExpectOnly(Patched(dir, good14, "b.las", [](auto* b) { lf::PutU32(&(*b)[lf::kOffLegacyCount], kPoints); }),
             "legacy counts", "must be 0 for point format 7");
  FileSpec pdrf3;
  pdrf3.edit_options = [](LasWriterOptions* o) { o->point_format = 3; };
  const std::string legacy14 = MakeFile(dir, "pdrf3.las", pdrf3);
  EXPECT_EQ(ValidateLasFile(legacy14), std::vector<std::string>{});
  ExpectOnly(Patched(dir, legacy14, "c.las", [](auto* b) { lf::PutU32(&(*b)[lf::kOffLegacyCount], 0); }),
             "legacy counts", "must equal the 64-bit ones");
}

TEST_F(LasValidateTest, PointsByReturnDisagreeWithThePoints) {
  ExpectOnly(Patched(dir, good14, "b.las", [](auto* b) { lf::PutU64(&(*b)[lf::kOffByReturn64 + 8], 1); }),
             "points by return", "sum 301");
  ExpectOnly(Patched(dir, good12, "c.las", [](auto* b) { lf::PutU32(&(*b)[lf::kOffLegacyByReturn], kPoints - 1); }),
             "points by return", "[299,0,0,0,0]");
}

TEST_F(LasValidateTest, ZeroPointsBeforeLas14) {
  FileSpec s;
  s.minor = 2;
  s.points = 0;
  ExpectOnly(MakeFile(dir, "empty12.las", s), "zero points");
}

TEST_F(LasValidateTest, HeaderBoundsSmallerThanThePoints) {
  ExpectOnly(Patched(dir, good14, "maxx.las",
                     [](auto* b) {
                       const double max_x = lf::GetF64(&(*b)[lf::kOffBounds]);
                       lf::PutF64(&(*b)[lf::kOffBounds], max_x - 0.002);
                     }),
             "bounds", "header max X");
  ExpectOnly(Patched(dir, good12, "minz.las",
                     [](auto* b) {
                       const double min_z = lf::GetF64(&(*b)[lf::kOffBounds + 40]);
                       lf::PutF64(&(*b)[lf::kOffBounds + 40], min_z + 0.01);
                     }),
             "bounds", "header min Z");
  // Within half a step is fine; a box larger than the data is not flagged.
  const std::string ok = Patched(dir, good14, "ok.las", [](auto* b) {
    lf::PutF64(&(*b)[lf::kOffBounds], lf::GetF64(&(*b)[lf::kOffBounds]) - 0.0004);
    lf::PutF64(&(*b)[lf::kOffBounds + 8], lf::GetF64(&(*b)[lf::kOffBounds + 8]) - 5.0);
  });
  EXPECT_EQ(ValidateLasFile(ok), std::vector<std::string>{});
}

TEST_F(LasValidateTest, InvalidReturnNumbers) {
  // Point 5: number of returns 0 (PDRF 7: high nibble of byte 14; PDRF 3: bits 3-5).
  ExpectOnly(Patched(dir, good14, "b.las",
                     [](auto* b) { (*b)[PointOffset(*b) + 5 * RecordLength(*b) + 14] = 0x01; }),
             "return numbers", "first: point 5");
  ExpectOnly(Patched(dir, good12, "c.las",
                     [](auto* b) { (*b)[PointOffset(*b) + 7 * RecordLength(*b) + 14] = 0x01; }),
             "return numbers", "first: point 7");
  // 1.2: 6 returns exceed the legacy maximum of 5 (return 1 of 6 keeps the by-return counts right).
  ExpectOnly(Patched(dir, good12, "d.las",
                     [](auto* b) { (*b)[PointOffset(*b) + 9 * RecordLength(*b) + 14] = 0x01 | (6 << 3); }),
             "return numbers", "> 5");
}

TEST_F(LasValidateTest, GlobalEncodingBits) {
  ExpectOnly(Patched(dir, good12, "b.las", [](auto* b) { lf::PutU16(&(*b)[lf::kOffGlobalEncoding], 0x10); }),
             "global encoding", "not defined for LAS 1.2");
  ExpectOnly(Patched(dir, good14, "c.las", [](auto* b) { lf::PutU16(&(*b)[lf::kOffGlobalEncoding], 0x0); }),
             "global encoding", "WKT bit (4) is clear");
  FileSpec no_crs;
  no_crs.crs = "";
  const std::string plain = MakeFile(dir, "plain.las", no_crs);
  ExpectOnly(Patched(dir, plain, "d.las", [](auto* b) { lf::PutU16(&(*b)[lf::kOffGlobalEncoding], 0x10); }),
             "global encoding", "no WKT");
  FileSpec absolute_gps;
  absolute_gps.minor = 2;
  absolute_gps.gps_week_time = false;
  ExpectOnly(MakeFile(dir, "gps.las", absolute_gps), "global encoding", "outside [0, 604800]");
  ExpectOnly(Patched(dir, good14, "w.las", [](auto* b) { lf::PutU64(&(*b)[lf::kOffWaveformStart], 12345); }),
             "global encoding", "start of waveform data 12345");
}

TEST_F(LasValidateTest, ScaleAndOffset) {
  // A scale off the 10^k x {1, 0.5, 0.25} grid by 1e-6 relative (coordinates move < 0.1 step: bounds hold).
  ExpectOnly(Patched(dir, good14, "s.las", [](auto* b) { lf::PutF64(&(*b)[lf::kOffScale], 0.001000001); }), "scale",
             "X scale");
  ExpectOnly(Patched(dir, good14, "o.las",
                     [](auto* b) {
                       lf::PutF64(&(*b)[lf::kOffOffset + 8], lf::GetF64(&(*b)[lf::kOffOffset + 8]) + 0.0004);
                     }),
             "offset", "translation fluff");
}

TEST_F(LasValidateTest, IdentifierFieldsAndCreationDate) {
  ExpectOnly(Patched(dir, good14, "b.las", [](auto* b) { (*b)[lf::kOffSystemId + 20] = 'x'; }), "system identifier",
             "NUL-padded");
  ExpectOnly(Patched(dir, good14, "c.las",
                     [](auto* b) {
                       for (size_t i = 0; i < 32; ++i) (*b)[lf::kOffSoftware + i] = 'a';
                     }),
             "generating software", "not NUL-terminated");
  ExpectOnly(Patched(dir, good14, "d.las",
                     [](auto* b) {
                       lf::PutU16(&(*b)[lf::kOffCreationDay], 0);
                       lf::PutU16(&(*b)[lf::kOffCreationYear], 0);
                     }),
             "creation date", "not set");
  ExpectOnly(Patched(dir, good14, "e.las", [](auto* b) { lf::PutU16(&(*b)[lf::kOffCreationYear], 3000); }),
             "creation date", "future");
}

TEST_F(LasValidateTest, CrsRecords) {
  FileSpec geotiff14;
  geotiff14.crs = "";
  geotiff14.edit_options = [](LasWriterOptions* o) {
    for (const LasVlr& v : LasCrsVlrs(ParseProjectCrs("EPSG:25832"), 2).vlrs) o->vlrs.push_back(v);
  };
  ExpectOnly(MakeFile(dir, "geotiff14.las", geotiff14), "CRS", "GeoTIFF (LASF_Projection/34735) records in a point");
  FileSpec both12;
  both12.minor = 2;
  both12.edit_options = [](LasWriterOptions* o) {
    o->vlrs.push_back(LasCrsVlrs(ParseProjectCrs("EPSG:25832"), 4).vlrs[0]);
  };
  ExpectOnly(MakeFile(dir, "both12.las", both12), "CRS", "both GeoTIFF and WKT");
  FileSpec two_wkt;
  two_wkt.edit_options = [](LasWriterOptions* o) {
    o->vlrs.push_back(LasCrsVlrs(ParseProjectCrs("EPSG:32632"), 4).vlrs[0]);
  };
  ExpectOnly(MakeFile(dir, "two.las", two_wkt), "CRS", "2 WKT records");
  FileSpec bad_wkt;
  bad_wkt.crs = "";
  bad_wkt.edit_options = [](LasWriterOptions* o) {
    LasVlr v = LasCrsVlrs(ParseProjectCrs("EPSG:32632"), 4).vlrs[0];
    v.data.resize(40);
    v.data.push_back(0);
    o->vlrs.push_back(v);
    o->global_encoding_extra_bits = 0x10;
  };
  ExpectOnly(MakeFile(dir, "badwkt.las", bad_wkt), "CRS", "WKT record");
  ExpectOnly(Patched(dir, good12, "badkeys.las",
                     [](auto* b) {
                       // GeoKeyDirectory is the first VLR: claim 40 keys.
                       lf::PutU16(&(*b)[lf::kHeaderSize12 + lf::kVlrHeaderSize + 6], 40);
                     }),
             "CRS", "40 keys");
}

}  // namespace
}  // namespace sacfuse

namespace sacfuse {
namespace {

// LAZ is checked on its decoded points: our own LAZ passes for LAS 1.4 and 1.2; a corrupted chunk is a finding.
TEST(LasValidateLazTest, ChecksLazOnItsDecodedPoints) {
  TempDir dir;
  for (const int minor : {4, 2}) {
    FileSpec spec;
    spec.minor = minor;
    spec.crs = minor == 4 ? "EPSG:25832" : "EPSG:32632";
    spec.edit_options = [](LasWriterOptions* o) { o->compressed = true; };
    const std::string laz = MakeFile(dir, "ok1" + std::to_string(minor) + ".laz", spec);
    const std::vector<std::string> findings = ValidateLasFile(laz);
    EXPECT_TRUE(findings.empty()) << minor << ": " << (findings.empty() ? "" : findings[0]);
  }
  FileSpec spec;
  spec.edit_options = [](LasWriterOptions* o) { o->compressed = true; };
  const std::string laz = MakeFile(dir, "good.laz", spec);
  LasReader reader(laz);
  const uint64_t data = reader.header().offset_to_point_data;
  const std::string bad = Patched(dir, laz, "bad.laz", [&](std::vector<uint8_t>* b) {
    for (uint64_t i = data + 8 + 40; i < data + 8 + 400 && i < b->size(); ++i) (*b)[i] ^= 0x5a;  // inside chunk 0
  });
  const std::vector<std::string> findings = ValidateLasFile(bad);
  ASSERT_FALSE(findings.empty());
  bool named = false;
  for (const std::string& f : findings) named = named || f.rfind("LAZ", 0) == 0 || f.rfind("bounds", 0) == 0 ||
                                                f.rfind("return numbers", 0) == 0 || f.rfind("points by return", 0) == 0;
  EXPECT_TRUE(named) << findings[0];
}

// Issue 50: a LAZ file missing the last bytes of its chunk table decoded (the coder's final bytes are zeros, which a
// decoder supplies past the end, as LASzip's does) and validated "ok".
TEST(LasValidateLazTest, ChunkTableCutShortIsAFinding) {
  TempDir dir;
  FileSpec spec;
  spec.minor = 2;  // no EVLRs: the chunk table ends the file
  spec.crs = "EPSG:32632";
  spec.edit_options = [](LasWriterOptions* o) { o->compressed = true; };
  const std::string laz = MakeFile(dir, "whole.laz", spec);
  ASSERT_TRUE(ValidateLasFile(laz).empty());
  const uint64_t size = std::filesystem::file_size(laz);
  EXPECT_EQ(LasReader(laz).laz_chunk_table_end(), size);
  for (const uint64_t cut : {1, 2, 3}) {
    const std::string shorter = Patched(dir, laz, "cut" + std::to_string(cut) + ".laz",
                                        [&](std::vector<uint8_t>* b) { b->resize(b->size() - cut); });
    const std::vector<std::string> findings = ValidateLasFile(shorter);
    ASSERT_FALSE(findings.empty()) << cut << " bytes cut: validated ok";
    EXPECT_EQ(findings[0], "LAZ: the chunk table's coded entries end at byte " + std::to_string(size) +
                               ", but the file ends at " + std::to_string(size - cut) + ": its last " +
                               std::to_string(cut) + " bytes are missing (truncated)");
  }
}

}  // namespace
}  // namespace sacfuse
