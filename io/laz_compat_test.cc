// Our LAZ reader on the LAZ files of ../shared/research-data (written by LAStools/LASzip, PDAL/laz-perf, laspy/
// laz-rs): every file that has an uncompressed twin (same name .las beside it, or the twin named in kTwins)
// decodes to exactly its points, every attribute; the other supported files decode with the header's count and
// within its bounds; unsupported ones (LASzip v1 items, waveform packets) are refused naming the file and the
// compressor/item version. Skips with a message when the shared data are absent. Never copies those files.
#include <algorithm>
#include <cmath>
#include <tuple>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/las_reader.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;

std::optional<fs::path> ResearchData() {
  const auto shared = testing::SharedDir();
  if (!shared || !fs::exists(*shared / "research-data")) return std::nullopt;
  return *shared / "research-data";
}

// LAZ files whose uncompressed twin has another name (relative to research-data). COPC files reorder points into
// an octree, so their twin is compared as a set of points.
const std::map<std::string, std::string>& Twins() {
  static const std::map<std::string, std::string> twins = {
      {"las_compat/pdal/laz__autzen_trim.laz", "lidar/pdal_autzen/autzen_trim.las"},
      {"las_compat/pdal/laz__simple.laz", "las_compat/pdal/las__simple.las"},
      {"las_compat/liblas/1.2-with-color.laz", "las_compat/pdal/las__1.2-with-color.las"},
      {"las_compat/laspy/simple.copc.laz", "las_compat/pdal/las__1.2-with-color.las"},
      {"las_compat/pdal/copc__1.2-with-color.copc.laz", "las_compat/pdal/las__1.2-with-color.las"},
      {"las_compat/laspy/extra.laz", "las_compat/pdal/las__extrabytes.las"},
  };
  return twins;
}

// LAZ files we refuse, and a word the message must contain.
const std::map<std::string, std::string>& Refused() {
  static const std::map<std::string, std::string> refused = {
      {"lidar/lastools/TO_core_last_zoom.laz", "compressor 1 (point-wise, not chunked) (LASzip 1.0r0)"},
      {"las_compat/laspy/fullwave.laz", "WAVEPACKET"},
  };
  return refused;
}

std::string Describe(const LasPoint& p) {
  char text[256];
  std::snprintf(text, sizeof(text), "(%.6f %.6f %.6f) i%u r%u/%u c%u f%u ch%u sd%d e%d a%.3f u%u s%u t%.9f rgb%u,%u,%u nir%u",
                p.xyz.x(), p.xyz.y(), p.xyz.z(), p.intensity, p.return_number, p.number_of_returns, p.classification,
                p.flags, p.scanner_channel, p.scan_direction, p.edge_of_flight_line, p.scan_angle_deg, p.user_data,
                p.point_source_id, p.gps_time, p.rgb[0], p.rgb[1], p.rgb[2], p.nir);
  return text;
}

// The COPC files converted point format 3 to 7 (scan angle rank -> 0.006 degree steps) with another offset
// (coordinates equal to rounding).
bool Same(const LasPoint& a, const LasPoint& b, bool converted) {
  const bool angle = converted ? std::abs(a.scan_angle_deg - b.scan_angle_deg) <= 0.006f
                               : a.scan_angle_deg == b.scan_angle_deg;
  const bool xyz = converted ? (a.xyz - b.xyz).cwiseAbs().maxCoeff() < 1e-6 : a.xyz == b.xyz;
  return angle && xyz && a.intensity == b.intensity && a.return_number == b.return_number &&
         a.number_of_returns == b.number_of_returns && a.classification == b.classification && a.flags == b.flags &&
         a.scanner_channel == b.scanner_channel && a.scan_direction == b.scan_direction &&
         a.edge_of_flight_line == b.edge_of_flight_line &&
         a.user_data == b.user_data && a.point_source_id == b.point_source_id &&
         (a.gps_time == b.gps_time || (a.gps_time != a.gps_time && b.gps_time != b.gps_time)) && a.rgb == b.rgb &&
         a.nir == b.nir;
}

std::vector<fs::path> LazFiles(const fs::path& root) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (e.is_regular_file() && e.path().extension() == ".laz") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(LazCompatTest, SharedLazFilesDecodeToTheirUncompressedTwins) {
  const auto root = ResearchData();
  if (!root) GTEST_SKIP() << "../shared/research-data not found (set SACFUSE_SHARED)";
  const std::vector<fs::path> files = LazFiles(*root);
  ASSERT_GE(files.size(), 15u);
  size_t twins = 0;
  size_t decoded = 0;
  size_t refused = 0;
  for (const fs::path& file : files) {
    const std::string name = fs::relative(file, *root).string();
    SCOPED_TRACE(name);
    if (const auto it = Refused().find(name); it != Refused().end()) {
      try {
        LasReader reader(file.string());
        ADD_FAILURE() << "an unsupported LAZ file was accepted";
      } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(file.string()), std::string::npos) << what;
        EXPECT_NE(what.find(it->second), std::string::npos) << what;
        std::printf("[ laz      ] %s refused: %s\n", name.c_str(), what.c_str() + file.string().size() + 2);
      }
      ++refused;
      continue;
    }
    LasHeader h;
    std::vector<LasPoint> points;
    ASSERT_NO_THROW(points = ReadAllLasPoints(file.string(), &h));
    ASSERT_EQ(points.size(), h.point_count);
    ++decoded;
    fs::path twin = fs::path(file).replace_extension(".las");
    if (const auto it = Twins().find(name); it != Twins().end()) twin = *root / it->second;
    if (!fs::exists(twin)) {
      for (const LasPoint& p : points) {
        for (int a = 0; a < 3; ++a) {
          ASSERT_GE(p.xyz[a], h.min[a] - h.scale[a]) << Describe(p);
          ASSERT_LE(p.xyz[a], h.max[a] + h.scale[a]) << Describe(p);
        }
      }
      std::printf("[ laz      ] %s: %zu points (format %d, LAS 1.%d), no uncompressed twin\n", name.c_str(),
                  points.size(), h.point_format, h.version_minor);
      continue;
    }
    LasHeader th;
    std::vector<LasPoint> expected = ReadAllLasPoints(twin.string(), &th);
    ASSERT_EQ(points.size(), expected.size()) << twin;
    const bool copc = name.find("copc") != std::string::npos;
    if (!copc) EXPECT_EQ(h.point_format, th.point_format);
    EXPECT_EQ(h.scale, th.scale);
    if (!copc) EXPECT_EQ(h.offset, th.offset);
    if (copc) {
      const auto order = [](const LasPoint& a, const LasPoint& b) {
        return std::tie(a.gps_time, a.xyz[0], a.xyz[1], a.xyz[2]) < std::tie(b.gps_time, b.xyz[0], b.xyz[1], b.xyz[2]);
      };
      std::sort(points.begin(), points.end(), order);
      std::sort(expected.begin(), expected.end(), order);
    }
    size_t bad = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      if (!Same(points[i], expected[i], copc) && bad++ < 3) {
        ADD_FAILURE() << "point " << i << ": " << Describe(points[i]) << " vs " << Describe(expected[i]);
      }
    }
    EXPECT_EQ(bad, 0u);
    ++twins;
    std::printf("[ laz      ] %s: %zu points (format %d, LAS 1.%d) identical to %s%s\n", name.c_str(), points.size(),
                h.point_format, h.version_minor, fs::relative(twin, *root).c_str(), copc ? " (as a set)" : "");
  }
  EXPECT_GE(twins, 12u);
  EXPECT_EQ(refused, Refused().size());
  std::printf("[ laz      ] %zu LAZ files: %zu decoded (%zu against a twin), %zu refused\n", files.size(), decoded,
              twins, refused);
}

}  // namespace
}  // namespace sacfuse
