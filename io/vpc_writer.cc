#include "io/vpc_writer.h"

#include <algorithm>
#include <ctime>
#include <exception>
#include <tuple>
#include <filesystem>
#include <optional>
#include <regex>
#include <utility>

#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/las_crs.h"
#include "io/las_reader.h"

namespace sacfuse {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

// Dimensions of a point format as PDAL names and types them (what `pdal_wrench build_vpc` lists).
Json Schemas(int pdrf) {
  std::vector<std::tuple<const char*, const char*, int>> dims = {
      {"X", "floating", 8},          {"Y", "floating", 8},           {"Z", "floating", 8},
      {"Intensity", "unsigned", 2},  {"ReturnNumber", "unsigned", 1}, {"NumberOfReturns", "unsigned", 1},
      {"ScanDirectionFlag", "unsigned", 1}, {"EdgeOfFlightLine", "unsigned", 1}, {"Classification", "unsigned", 1},
      {"ScanAngleRank", "floating", 4}, {"UserData", "unsigned", 1}, {"PointSourceId", "unsigned", 2}};
  const bool gps = pdrf == 1 || pdrf >= 3;
  const bool rgb = pdrf == 2 || pdrf == 3 || pdrf == 5 || pdrf == 7 || pdrf == 8 || pdrf == 10;
  if (gps) dims.emplace_back("GpsTime", "floating", 8);
  if (pdrf >= 6) {
    dims.emplace_back("ScanChannel", "unsigned", 1);
    dims.emplace_back("ClassFlags", "unsigned", 1);
  }
  if (rgb) {
    for (const char* c : {"Red", "Green", "Blue"}) dims.emplace_back(c, "unsigned", 2);
  }
  if (pdrf == 8 || pdrf == 10) dims.emplace_back("Infrared", "unsigned", 2);
  Json out = Json::array();
  for (const auto& [name, type, size] : dims) out.push_back({{"name", name}, {"type", type}, {"size", size}});
  return out;
}

// proj:epsg of a file: the EPSG code PROJ gives its whole CRS ("EPSG:5698"); none for a compound named by two codes
// ("EPSG:2154+5720"), whose horizontal code alone would drop the heights' CRS; else the horizontal code (a
// projected CRS with ellipsoidal heights, written as PROJCS + an ellipsoidal VERT_CS: its 2D code, as PDAL states it).
std::optional<int> WholeEpsgCode(const LasCrsInfo& crs) {
  static const std::regex single(R"(EPSG:([0-9]+))");
  std::smatch m;
  if (std::regex_match(crs.code, m, single)) return std::stoi(m[1].str());
  if (crs.code.find('+') != std::string::npos || crs.epsg <= 0) return std::nullopt;
  return crs.epsg;
}

// RFC 3339 date of a LAS creation day of year.
std::string CreationDate(int year, int day_of_year) {
  if (year <= 0 || day_of_year <= 0) return "1970-01-01T00:00:00Z";
  std::tm tm{};
  tm.tm_year = year - 1900;
  tm.tm_mday = day_of_year;  // timegm normalises day n of January into its month
  const std::time_t t = timegm(&tm);
  std::tm utc{};
  gmtime_r(&t, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

// The header's XY box as a GeoJSON polygon, its corners through `to` (x, y -> position).
template <typename To>
Json BoxPolygon(const LasHeader& h, const To& to) {
  const double x0 = h.min.x(), y0 = h.min.y(), x1 = h.max.x(), y1 = h.max.y();
  const std::pair<double, double> corners[5] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}};
  Json ring = Json::array();
  for (const auto& [x, y] : corners) ring.push_back(to(x, y));
  return {{"type", "Polygon"}, {"coordinates", Json::array({ring})}};
}

// The STAC item of one file.
Json FileFeature(const std::string& file, const fs::path& base, const Crs& crs) {
  LasHeader h;
  {
    LasReader reader(file);
    h = reader.header();
  }
  const LasCrsInfo file_crs = ReadLasCrs(h);
  const double z_mid = (h.min.z() + h.max.z()) / 2;
  // Geometry and bbox: WGS 84 longitude / latitude when the CRS converts there, else the file's coordinates.
  Json geometry, bbox;
  const auto native = [](double x, double y) { return Json::array({x, y}); };
  if (crs.georeferenced()) {
    double lon_min = 180, lon_max = -180, lat_min = 90, lat_max = -90;
    const auto wgs84 = [&](double x, double y) {
      const Eigen::Vector2d llh = LatLonFromProject(crs, Eigen::Vector3d(x, y, z_mid));  // no geoid grid needed
      lat_min = std::min(lat_min, llh[0]);
      lat_max = std::max(lat_max, llh[0]);
      lon_min = std::min(lon_min, llh[1]);
      lon_max = std::max(lon_max, llh[1]);
      return Json::array({llh[1], llh[0]});
    };
    geometry = BoxPolygon(h, wgs84);
    bbox = Json::array({lon_min, lat_min, lon_max, lat_max});
  } else {
    geometry = BoxPolygon(h, native);
    bbox = Json::array({h.min.x(), h.min.y(), h.max.x(), h.max.y()});
  }
  Json properties = {
      {"datetime", CreationDate(h.creation_year, h.creation_day)},
      {"pc:count", h.point_count},
      {"pc:type", "eopc"},  // electro-optical (photogrammetric) point cloud
      {"pc:encoding", "laszip"},
      {"pc:schemas", Schemas(h.point_format)},
      {"proj:wkt2", file_crs.wkt},
      {"proj:geometry", BoxPolygon(h, native)},
      {"proj:bbox", Json::array({h.min.x(), h.min.y(), h.min.z(), h.max.x(), h.max.y(), h.max.z()})},
  };
  if (const std::optional<int> code = WholeEpsgCode(file_crs)) properties["proj:epsg"] = *code;
  const std::string href = "./" + fs::relative(fs::absolute(file), base).generic_string();
  std::string id = fs::path(file).filename().string();
  id = id.substr(0, id.find('.'));  // "3_4" of 3_4.laz and 3_4.copc.laz
  return Json{{"type", "Feature"},
              {"stac_version", "1.0.0"},
              {"stac_extensions",
               Json::array({"https://stac-extensions.github.io/pointcloud/v1.0.0/schema.json",
                            "https://stac-extensions.github.io/projection/v1.1.0/schema.json"})},
              {"id", id},
              {"geometry", geometry},
              {"bbox", bbox},
              {"properties", properties},
              {"links", Json::array()},
              {"assets", {{"data", {{"href", href}, {"roles", Json::array({"data"})}}}}}};
}

}  // namespace

void WriteVirtualPointCloud(const std::string& vpc_path, const std::vector<std::string>& files, const Crs& crs) {
  const fs::path base = fs::absolute(vpc_path).parent_path();
  // One feature per file, made in parallel (opening a LAZ file reads its chunk table; a merge indexes hundreds of
  // tiles), kept in the order given; the first file in that order that fails is the one reported.
  std::vector<Json> items(files.size());
  std::vector<std::exception_ptr> errors(files.size());
  tbb::parallel_for(size_t{0}, files.size(), [&](size_t i) {
    try {
      items[i] = FileFeature(files[i], base, crs);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  Json features = Json::array();
  for (size_t i = 0; i < files.size(); ++i) {
    if (errors[i]) std::rethrow_exception(errors[i]);
    features.push_back(std::move(items[i]));
  }
  const Json vpc = {{"type", "FeatureCollection"}, {"features", features}};
  WriteFileAtomically(vpc_path, vpc.dump(2) + "\n");
}

}  // namespace sacfuse
