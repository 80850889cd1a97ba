// Reads every real LAS file under ../shared/research-data/{las_compat,lidar}, checks counts and bounds, writes
// each back with our writer, re-reads it and compares field by field; validates source and copy
// (io/las_validate.h: the copy may have no problem the source does not have); every LAZ file must be rejected
// with a clear message. All points of every file are used (the largest, zurich.las, has 656,837; the whole
// test takes a few seconds).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/las_crs.h"
#include "io/las_format.h"
#include "io/las_reader.h"
#include "io/las_validate.h"
#include "io/las_writer.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;

// Per-file decisions for files that are odd in some way (paths relative to research-data/). Files not listed
// must read cleanly with every point inside the header bounds (within one scale step).
struct Decision {
  bool readable;                // false: an InputError containing `error` is expected
  const char* error;            // fragment of the expected message
  bool points_inside_bounds;    // false: the header bounds are known to be wrong for this file
  const char* reason;
};
const std::map<std::string, Decision>& Decisions() {
  static const std::map<std::string, Decision> kDecisions = {
      // Rejected.
      {"las_compat/pdal/las__garbage_nVariableLength.las",
       {false, "truncated", true,
        "garbage VLR count (1069128089) and global encoding, and 719 points promised where 718 fit: truncated "
        "(PDAL rejects it too)"}},
      {"las_compat/pdal/las__permutations__1.2-no-points.las",
       {false, "can hold only 0", true,
        "header promises 1065 points but the file ends at the point offset: truncated (PDAL rejects it too)"}},
      // Read, although not quite by the book.
      {"las_compat/pdal/las__bad_vlr_count.las",
       {true, "", true,
        "VLR count 3 but the 2 VLRs end exactly at the point offset: points unambiguous (laspy, LASlib read it; "
        "PDAL rejects)"}},
      {"las_compat/las-rs/long-header.las",
       {true, "", true, "LAS 1.2 header size 229: 1.0-1.3 let applications extend the header; 2 bytes skipped"}},
      {"las_compat/liblas/bad_points_1.1.las",
       {true, "", true, "one all-zero point (return 0 of 0): wrong content, valid layout; we do not judge content"}},
      {"las_compat/liblas/TO_core_last_clip.las",
       {true, "", true, "LAS 1.0 point data start signature (2 bytes) between header and points"}},
      {"las_compat/laspy/simple1_3.las",
       {true, "", false,
        "PDRF 4: waveform packet fields skipped, waveform data after the points ignored; the header bounds hold "
        "the raw stored integers, not coordinates (writer bug)"}},
      {"las_compat/laspy/unregistered_extra_bytes.las",
       {true, "", true, "4 extra bytes per record without an Extra Bytes VLR: skipped"}},
      {"las_compat/ign/las_with_origin_dxmMarker.las",
       {true, "", true, "LAS 1.4 PDRF 3 with legacy count 0 (should be set): the 64-bit count is used"}},
      {"lidar/lastools/zurich.las",
       {true, "", false,
        "header Z range [547.29, 573.87] misses 228 points (data 506.23-573.90); same header in zurich.laz "
        "(lassort output)"}},
      {"las_compat/ign/prio4_bridge_with_probas.las",
       {true, "", true, "LAS 1.4 PDRF 8 with the legacy count set (should be 0): the 64-bit count is used"}},
  };
  return kDecisions;
}

std::vector<fs::path> FilesWithExtension(const fs::path& root, const std::string& ext) {
  std::vector<fs::path> files;
  for (const char* sub : {"las_compat", "lidar"}) {
    const fs::path dir = root / sub;
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
      std::string e = entry.path().extension().string();
      std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
      if (entry.is_regular_file() && e == ext) files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::optional<fs::path> ResearchData() {
  const auto shared = testing::SharedDir();
  if (!shared) return std::nullopt;
  return *shared / "research-data";
}

// Largest valid LAS scale (10^k x {1, 0.5, 0.25}) not above `scale`.
double ValidScaleAtMost(double scale) {
  double best = 0.0;
  for (int k = -12; k <= 3; ++k) {
    for (double m : {1.0, 2.5, 5.0}) {
      const double s = k >= 0 ? m * std::pow(10.0, k) : m / std::pow(10.0, -k);
      if (s <= scale * (1 + 1e-12)) best = std::max(best, s);
    }
  }
  return best;
}

// How a file was written back.
struct RoundTrip {
  bool exact = false;  // same scale and offset: the stored integers must be identical
};

// Writes `points` back with our writer: the same version and point format where the writer has them (LAS 1.0,
// 1.1, 1.3 -> 1.2; waveform formats 4, 5, 9, 10 -> 1, 3, 6, 8, losing their packets), the global-encoding bits our
// writer may set for that version, every VLR (extra-bytes descriptions aside, as extra bytes are not written) and
// -- when the source scale is one our writer accepts (10^k x {1, 0.5, 0.25}) -- the same scale and offset, so the
// stored integers must come back identical; otherwise the closest valid scale (coordinates within half a step).
// Re-reads and compares every standard field of the format and the CRS records.
void ExpectRoundTrip(const LasHeader& source, const std::vector<LasPoint>& points, const fs::path& out_path,
                     RoundTrip* trip) {
  RoundTrip& result = *trip;
  LasWriterOptions options;
  const int pdrf = source.point_format;
  options.version_minor = source.version_minor >= 4 ? 4 : 2;
  static const int kTarget[11] = {0, 1, 2, 3, 1, 3, 6, 7, 8, 6, 8};  // waveform formats lose their packets
  options.point_format = kTarget[pdrf];
  // GPS time (0) for both versions; synthetic returns (3) and WKT (4) in 1.4; the waveform bits (1, 2) go with
  // the waveform packets.
  options.global_encoding_extra_bits =
      static_cast<uint16_t>(source.global_encoding & (options.version_minor == 4 ? 0x19 : 0x1));
  if (las_format::HasGpsTime(kTarget[pdrf]) == false) options.global_encoding_extra_bits &= ~uint16_t{0x1};
  result.exact = true;
  for (int a = 0; a < 3; ++a) {
    double canonical = 0.0;
    result.exact = result.exact && las_format::CanonicalLasScale(source.scale[a], &canonical) &&
                   canonical == source.scale[a];
  }
  Eigen::Vector3d scale, offset;
  for (int a = 0; a < 3; ++a) {
    if (result.exact) {
      scale[a] = source.scale[a];
      offset[a] = source.offset[a];
      continue;
    }
    scale[a] = ValidScaleAtMost(source.scale[a]);
    // Offset at the middle of the data, on the scale grid: the finer scale still fits int32 where the source
    // used the whole int32 range.
    double lo = 0.0, hi = 0.0;
    if (!points.empty()) {
      lo = hi = points[0].xyz[a];
      for (const LasPoint& p : points) {
        lo = std::min(lo, p.xyz[a]);
        hi = std::max(hi, p.xyz[a]);
      }
    }
    offset[a] = std::floor((lo + hi) / 2 / scale[a]) * scale[a];
  }
  options.scale_xyz = scale;
  options.offset = offset;
  for (const LasVlr& vlr : source.vlrs) {
    if (vlr.user_id == "LASF_Spec" && vlr.record_id == 4) continue;  // extra bytes are not written back
    if (vlr.extended && options.version_minor < 4) continue;
    options.vlrs.push_back(vlr);
  }
  {
    LasWriter writer(out_path.string(), options);
    for (size_t i = 0; i < points.size(); i += 10000) {
      writer.WritePoints(&points[i], std::min<size_t>(10000, points.size() - i));
    }
    writer.Close();
  }
  LasHeader header;
  const std::vector<LasPoint> back = ReadAllLasPoints(out_path.string(), &header);
  EXPECT_EQ(back.size(), points.size());
  if (back.size() != points.size()) return;
  EXPECT_EQ(header.version_minor, options.version_minor);
  EXPECT_EQ(header.point_format, kTarget[pdrf]);
  EXPECT_EQ(header.global_encoding, options.global_encoding_extra_bits);
  EXPECT_EQ(header.vlrs.size(), options.vlrs.size());
  // The CRS records are kept byte for byte.
  EXPECT_EQ(header.Wkt(), source.Wkt());
  for (size_t v = 0; v < std::min(header.vlrs.size(), options.vlrs.size()); ++v) {
    EXPECT_EQ(header.vlrs[v].user_id, options.vlrs[v].user_id) << "VLR " << v;
    EXPECT_EQ(header.vlrs[v].record_id, options.vlrs[v].record_id) << "VLR " << v;
    EXPECT_EQ(header.vlrs[v].data, options.vlrs[v].data) << "VLR " << v;
  }
  try {
    EXPECT_EQ(ReadLasCrs(header).epsg, ReadLasCrs(source).epsg);
  } catch (const Error& e) {  // a malformed source CRS record stays malformed; both must say so
    EXPECT_THROW(ReadLasCrs(source), Error) << e.what();
  }
  if (result.exact) {
    EXPECT_EQ(header.scale, source.scale);
    EXPECT_EQ(header.offset, source.offset);
  }
  for (size_t i = 0; i < points.size(); ++i) {
    const LasPoint& a = points[i];
    const LasPoint& b = back[i];
    for (int k = 0; k < 3; ++k) {
      if (result.exact) {
        // Exactly the same stored integer.
        int32_t sa = 0, sb = 0;
        ASSERT_TRUE(las_format::Quantise(a.xyz[k], scale[k], offset[k], &sa));
        ASSERT_TRUE(las_format::Quantise(b.xyz[k], scale[k], offset[k], &sb));
        ASSERT_EQ(sa, sb) << "point " << i << " axis " << k;
        ASSERT_EQ(a.xyz[k], b.xyz[k]) << "point " << i << " axis " << k;
        continue;
      }
      // Half a step of the new scale, plus the double rounding of (x - offset) / scale at this magnitude.
      const double slack = 8 * std::numeric_limits<double>::epsilon() * std::max(std::abs(a.xyz[k]), 1.0);
      ASSERT_LE(std::abs(a.xyz[k] - b.xyz[k]), scale[k] / 2 + slack) << "point " << i << " axis " << k;
    }
    ASSERT_EQ(a.intensity, b.intensity) << i;
    ASSERT_EQ(a.return_number, b.return_number) << i;
    ASSERT_EQ(a.number_of_returns, b.number_of_returns) << i;
    ASSERT_EQ(a.classification, b.classification) << i;
    ASSERT_EQ(a.flags, b.flags) << i;
    ASSERT_EQ(a.scanner_channel, b.scanner_channel) << i;
    ASSERT_EQ(a.scan_direction, b.scan_direction) << i;
    ASSERT_EQ(a.edge_of_flight_line, b.edge_of_flight_line) << i;
    ASSERT_EQ(a.scan_angle_deg, b.scan_angle_deg) << i;
    ASSERT_EQ(a.user_data, b.user_data) << i;
    ASSERT_EQ(a.point_source_id, b.point_source_id) << i;
    ASSERT_EQ(a.gps_time, b.gps_time) << i;
    ASSERT_EQ(a.rgb, b.rgb) << i;
    ASSERT_EQ(a.nir, b.nir) << i;
  }
}

// Rule names ("bounds", "CRS", ...) of ValidateLasFile's findings.
std::set<std::string> FindingRules(const std::vector<std::string>& findings) {
  std::set<std::string> rules;
  for (const std::string& f : findings) rules.insert(f.substr(0, f.find(':')));
  return rules;
}

std::string Join(const std::set<std::string>& items) {
  std::string out;
  for (const auto& i : items) out += (out.empty() ? "" : ", ") + i;
  return out.empty() ? "none" : out;
}

TEST(LasCompatTest, DecisionTableNamesExistingFiles) {
  const auto root = ResearchData();
  if (!root) GTEST_SKIP() << "../shared/research-data not found (set SACFUSE_SHARED)";
  for (const auto& [name, decision] : Decisions()) EXPECT_TRUE(fs::exists(*root / name)) << name;
}

// Reads one file, checks it against its decision, writes it back. Returns true when the file was read.
bool CheckLasFile(const fs::path& root, const fs::path& file, const fs::path& out_path) {
  const std::string name = fs::relative(file, root).string();
  const auto it = Decisions().find(name);
  const Decision decision = it != Decisions().end() ? it->second : Decision{true, "", true, ""};
  LasHeader header;
  std::vector<LasPoint> points;
  try {
    points = ReadAllLasPoints(file.string(), &header);
  } catch (const InputError& e) {
    EXPECT_FALSE(decision.readable) << e.what();
    EXPECT_NE(std::string(e.what()).find(decision.error), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    return false;
  }
  EXPECT_TRUE(decision.readable) << "expected an InputError containing '" << decision.error << "'";
  EXPECT_EQ(points.size(), header.point_count);
  if (decision.points_inside_bounds) {
    for (size_t i = 0; i < points.size(); ++i) {
      for (int a = 0; a < 3; ++a) {
        const double tolerance = header.scale[a] * (1 + 1e-6);
        if (points[i].xyz[a] < header.min[a] - tolerance || points[i].xyz[a] > header.max[a] + tolerance) {
          ADD_FAILURE() << "point " << i << " axis " << a << " = " << points[i].xyz[a] << " outside ["
                        << header.min[a] << ", " << header.max[a] << "]";
          i = points.size();
          break;
        }
      }
    }
  }
  RoundTrip trip;
  try {
    ExpectRoundTrip(header, points, out_path, &trip);
  } catch (const Error& e) {
    ADD_FAILURE() << "round trip failed: " << e.what();
    return true;
  }
  // Our copy has no problem the source does not have (the source's own defects are printed, not judged).
  const std::vector<std::string> source_findings = ValidateLasFile(file.string());
  const std::vector<std::string> copy_findings = ValidateLasFile(out_path.string());
  const std::set<std::string> source_rules = FindingRules(source_findings);
  for (const std::string& f : copy_findings) {
    // The same message: the same defect carried over (same counts, same values), not a new one of that rule.
    EXPECT_NE(std::find(source_findings.begin(), source_findings.end(), f), source_findings.end())
        << "new problem in our copy: " << f;
  }
  std::printf("[ compat   ] %-60s %s; source findings: %s; copy: %s\n", name.c_str(),
              trip.exact ? "exact integers" : "rescaled", Join(source_rules).c_str(),
              Join(FindingRules(copy_findings)).c_str());
  return true;
}

TEST(LasCompatTest, ReadsEveryLasFileAndWritesItBack) {
  const auto root = ResearchData();
  if (!root) GTEST_SKIP() << "../shared/research-data not found (set SACFUSE_SHARED)";
  const std::vector<fs::path> files = FilesWithExtension(*root, ".las");
  ASSERT_GE(files.size(), 40u);
  testing::TempDir out_dir;
  size_t read_ok = 0, rejected = 0;
  for (const fs::path& file : files) {
    SCOPED_TRACE(fs::relative(file, *root).string());
    if (CheckLasFile(*root, file, out_dir / (std::to_string(read_ok + rejected) + ".las"))) {
      ++read_ok;
    } else {
      ++rejected;
    }
  }
  EXPECT_EQ(rejected, 2u);
  std::printf("[ compat   ] %zu LAS files read and written back, %zu rejected as decided\n", read_ok, rejected);
}

// Values PDAL's own tests expect from these files (LasReaderTest test_different_formats), plus VLR and count facts
// of the odd files read above.
TEST(LasCompatTest, MatchesKnownValues) {
  const auto root = ResearchData();
  if (!root) GTEST_SKIP() << "../shared/research-data not found (set SACFUSE_SHARED)";
  struct Expected {
    const char* file;
    int minor, pdrf;
    double gps;
    uint16_t r, g, b;
  };
  for (const Expected& e : std::vector<Expected>{{"las__permutations__1.0_0.las", 0, 0, 0, 0, 0, 0},
                                                  {"las__permutations__1.0_1.las", 0, 1, 1205902800.0, 0, 0, 0},
                                                  {"las__permutations__1.1_0.las", 1, 0, 0, 0, 0, 0},
                                                  {"las__permutations__1.1_1.las", 1, 1, 1205902800.0, 0, 0, 0},
                                                  {"las__permutations__1.2_0.las", 2, 0, 0, 0, 0, 0},
                                                  {"las__permutations__1.2_1.las", 2, 1, 1205902800.0, 0, 0, 0},
                                                  {"las__permutations__1.2_2.las", 2, 2, 0, 255, 12, 234},
                                                  {"las__permutations__1.2_3.las", 2, 3, 1205902800.0, 255, 12, 234}}) {
    SCOPED_TRACE(e.file);
    LasHeader header;
    const auto points = ReadAllLasPoints((*root / "las_compat/pdal" / e.file).string(), &header);
    ASSERT_EQ(points.size(), 1u);
    EXPECT_EQ(header.version_minor, e.minor);
    EXPECT_EQ(header.point_format, e.pdrf);
    EXPECT_NEAR(points[0].xyz.x(), 470692.44, 1e-6);
    EXPECT_NEAR(points[0].xyz.y(), 4602888.90, 1e-6);
    EXPECT_NEAR(points[0].xyz.z(), 16.0, 1e-6);
    EXPECT_EQ(points[0].gps_time, e.gps);
    EXPECT_EQ(points[0].rgb, (std::array<uint16_t, 3>{e.r, e.g, e.b}));
  }
  LasHeader header;
  EXPECT_EQ(ReadAllLasPoints((*root / "las_compat/pdal/las__bad_vlr_count.las").string(), &header).size(), 10u);
  EXPECT_EQ(header.vlrs.size(), 2u);
  ReadAllLasPoints((*root / "las_compat/pdal/las__lots_of_vlr.las").string(), &header);
  EXPECT_EQ(header.vlrs.size(), 390u);
  EXPECT_EQ(ReadAllLasPoints((*root / "las_compat/pdal/las__simple.las").string(), &header).size(), 1065u);
  EXPECT_EQ(header.points_by_return[0], 925u);  // PDAL LasReaderTest.header
  EXPECT_EQ(header.points_by_return[1], 114u);
  EXPECT_DOUBLE_EQ(header.max.x(), 638982.55);
  EXPECT_DOUBLE_EQ(header.min.y(), 848899.70);
  ReadAllLasPoints((*root / "las_compat/laspy/1_4_w_evlr.las").string(), &header);
  ASSERT_FALSE(header.vlrs.empty());
  EXPECT_TRUE(header.vlrs.back().extended);
  EXPECT_NE(header.Wkt().find("PROJCS"), std::string::npos);
  EXPECT_EQ(header.Wkt().back(), ']');
}
}  // namespace
}  // namespace sacfuse
