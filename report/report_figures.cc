#include "report/report_figures.h"
#include "io/json_text.h"

#include <nlohmann/json.hpp>

namespace sacfuse {
namespace {

nlohmann::json MapJson(const MapFigure& m) {
  return {{"present", m.present}, {"file", m.file}, {"width_px", m.width_px}, {"height_px", m.height_px},
          {"x_min", m.x_min}, {"y_max", m.y_max}, {"metres_per_px", m.metres_per_px}, {"cell_m", m.cell_m},
          {"points_scanned", m.points_scanned}, {"cells_filled", m.cells_filled}, {"cells_total", m.cells_total}};
}

MapFigure MapFromJson(const nlohmann::json& m) {
  MapFigure f;
  f.present = m.at("present").get<bool>();
  f.file = m.at("file").get<std::string>();
  f.width_px = m.at("width_px").get<int>();
  f.height_px = m.at("height_px").get<int>();
  f.x_min = m.at("x_min").get<double>();
  f.y_max = m.at("y_max").get<double>();
  f.metres_per_px = m.at("metres_per_px").get<double>();
  f.cell_m = m.at("cell_m").get<double>();
  f.points_scanned = m.at("points_scanned").get<uint64_t>();
  f.cells_filled = m.at("cells_filled").get<uint64_t>();
  f.cells_total = m.at("cells_total").get<uint64_t>();
  return f;
}

}  // namespace

std::string ReportFiguresToJson(const ReportFigures& f) {
  const ProfileFigure& p = f.profile;
  const ProfileStrip& s = p.strip;
  nlohmann::json j;
  j["map"] = MapJson(f.map);
  if (f.dsm.present) j["dsm"] = MapJson(f.dsm);
  if (f.ortho.present) j["ortho"] = MapJson(f.ortho);
  j["profile"] = {
      {"present", p.present}, {"reason", p.reason}, {"before_file", p.before_file}, {"after_file", p.after_file},
      {"strip", {{"start", {s.start_xy.x(), s.start_xy.y()}}, {"end", {s.end_xy.x(), s.end_xy.y()}},
                 {"half_width_m", s.half_width_m}, {"z_range_m", {s.z_min_m, s.z_max_m}}, {"relief_m", s.relief_m},
                 {"peak", {s.peak_xy.x(), s.peak_xy.y()}}}},
      {"frame", {{"s", {p.frame.s_min, p.frame.s_max}}, {"z", {p.frame.z_min, p.frame.z_max}},
                 {"width_px", p.frame.width_px}, {"height_px", p.frame.height_px}}},
      {"gsd_m", p.gsd_m}, {"gsd_source", p.gsd_source},
      {"before_in_strip", p.before_in_strip}, {"after_in_strip", p.after_in_strip},
      {"reference_in_strip", p.reference_in_strip}, {"before_drawn", p.before_drawn},
      {"after_drawn", p.after_drawn}, {"reference_drawn", p.reference_drawn}, {"before_views", p.before_views}, {"before_reason", p.before_reason},
      {"before_window_pixels", p.before_window_pixels}, {"has_reference", p.has_reference},
      {"after_source", p.after_source}};
  j["seconds"] = f.seconds;
  j["map_seconds"] = f.map_seconds;
  j["profile_seconds"] = f.profile_seconds;
  j["peak_rss_mib"] = f.peak_rss_mib;
  return JsonText(j, 2) + "\n";
}

ReportFigures ReportFiguresFromJson(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text);
  ReportFigures f;
  f.map = MapFromJson(j.at("map"));
  if (j.contains("dsm")) f.dsm = MapFromJson(j.at("dsm"));
  if (j.contains("ortho")) f.ortho = MapFromJson(j.at("ortho"));
  const auto& p = j.at("profile");
  ProfileFigure& q = f.profile;
  q.present = p.at("present").get<bool>();
  q.reason = p.at("reason").get<std::string>();
  q.before_file = p.at("before_file").get<std::string>();
  q.after_file = p.at("after_file").get<std::string>();
  const auto& s = p.at("strip");
  q.strip.start_xy = {s.at("start").at(0).get<double>(), s.at("start").at(1).get<double>()};
  q.strip.end_xy = {s.at("end").at(0).get<double>(), s.at("end").at(1).get<double>()};
  q.strip.half_width_m = s.at("half_width_m").get<double>();
  q.strip.z_min_m = s.at("z_range_m").at(0).get<double>();
  q.strip.z_max_m = s.at("z_range_m").at(1).get<double>();
  q.strip.relief_m = s.at("relief_m").get<double>();
  q.strip.peak_xy = {s.at("peak").at(0).get<double>(), s.at("peak").at(1).get<double>()};
  const auto& fr = p.at("frame");
  q.frame.s_min = fr.at("s").at(0).get<double>();
  q.frame.s_max = fr.at("s").at(1).get<double>();
  q.frame.z_min = fr.at("z").at(0).get<double>();
  q.frame.z_max = fr.at("z").at(1).get<double>();
  q.frame.width_px = fr.at("width_px").get<int>();
  q.frame.height_px = fr.at("height_px").get<int>();
  q.gsd_m = p.at("gsd_m").get<double>();
  q.gsd_source = p.at("gsd_source").get<std::string>();
  q.before_in_strip = p.at("before_in_strip").get<uint64_t>();
  q.after_in_strip = p.at("after_in_strip").get<uint64_t>();
  q.reference_in_strip = p.at("reference_in_strip").get<uint64_t>();
  q.before_drawn = p.at("before_drawn").get<uint64_t>();
  q.after_drawn = p.at("after_drawn").get<uint64_t>();
  q.reference_drawn = p.at("reference_drawn").get<uint64_t>();
  q.before_views = p.at("before_views").get<size_t>();
  q.before_reason = p.value("before_reason", "");
  q.before_window_pixels = p.at("before_window_pixels").get<uint64_t>();
  q.has_reference = p.at("has_reference").get<bool>();
  q.after_source = p.at("after_source").get<std::string>();
  f.seconds = j.at("seconds").get<double>();
  f.map_seconds = j.value("map_seconds", 0.0);
  f.profile_seconds = j.value("profile_seconds", 0.0);
  f.peak_rss_mib = j.at("peak_rss_mib").get<double>();
  return f;
}

}  // namespace sacfuse
