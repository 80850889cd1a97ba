// Writing camera files (YAML and CSV), the inverse of the readers in io/camera_file.cc: numbers with 17
// significant digits, so a written block reads back exactly.
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/photogrammetric_orientation.h"
#include "io/atomic_file.h"
#include "io/camera_file.h"
#include "io/camera_file_format.h"

namespace sacfuse {
namespace {

std::string Num(double v) {
  if (v == 0.0) v = 0.0;  // no "-0"
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

std::string YamlString(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string CsvCell(const std::string& s) {
  const bool plain = s.find_first_of(",\"\n#") == std::string::npos &&
                     (s.empty() || (s.front() != ' ' && s.back() != ' ' && s.front() != '\t' && s.back() != '\t'));
  if (plain) return s;
  std::string out = "\"";
  for (const char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// The fields of one view, in writing order (name, text).
std::vector<std::pair<std::string, std::string>> InteriorFields(const PinholeCamera& c,
                                                                const CameraFileWriteOptions& o) {
  std::vector<std::pair<std::string, std::string>> f = {{"width_px", std::to_string(c.width)},
                                                        {"height_px", std::to_string(c.height)}};
  if (o.pixel_size_um > 0 && c.fx == c.fy) {
    const double pitch_mm = o.pixel_size_um / 1000.0;
    f.insert(f.end(), {{"focal_mm", Num(c.fx * pitch_mm)},
                       {"pixel_size_um", Num(o.pixel_size_um)},
                       {"ppx_mm", Num((c.cx - 0.5 * c.width) * pitch_mm)},
                       {"ppy_mm", Num(-(c.cy - 0.5 * c.height) * pitch_mm)}});
  } else if (c.fx == c.fy) {
    f.insert(f.end(), {{"focal_px", Num(c.fx)}, {"cx_px", Num(c.cx)}, {"cy_px", Num(c.cy)}});
  } else {
    f.insert(f.end(), {{"fx_px", Num(c.fx)}, {"fy_px", Num(c.fy)}, {"cx_px", Num(c.cx)}, {"cy_px", Num(c.cy)}});
  }
  return f;
}

std::vector<std::pair<std::string, std::string>> ExteriorFields(const CameraFileView& v,
                                                                const CameraFileWriteOptions& o) {
  std::vector<std::pair<std::string, std::string>> f;
  if (v.geodetic) {
    f = {{"lat_deg", Num(v.position.x())}, {"lon_deg", Num(v.position.y())}, {"h_m", Num(v.position.z())}};
  } else {
    f = {{"x_m", Num(v.position.x())}, {"y_m", Num(v.position.y())}, {"z_m", Num(v.position.z())}};
  }
  if (o.rotation_matrix) {
    for (int i = 0; i < 9; ++i) f.emplace_back(kRotationKeys[i], Num(v.rotation(i / 3, i % 3)));
  } else {
    const OmegaPhiKappa a = OmegaPhiKappaFromRotation(v.rotation);
    f.insert(f.end(), {{"omega_deg", Num(a.omega_deg)}, {"phi_deg", Num(a.phi_deg)}, {"kappa_deg", Num(a.kappa_deg)}});
  }
  f.emplace_back("attitude_frame", v.attitude_frame == AttitudeFrame::kGrid ? "grid" : "local_enu");
  return f;
}

std::string FlowMap(const std::vector<std::pair<std::string, std::string>>& fields) {
  std::string out = "{";
  for (size_t i = 0; i < fields.size(); ++i) out += (i ? ", " : "") + fields[i].first + ": " + fields[i].second;
  return out + "}";
}

std::string YamlText(const CameraFile& file, const CameraFileWriteOptions& o) {
  const std::vector<CameraFileView>& views = file.views;
  std::vector<std::string> interiors;  // distinct interiors, as text
  std::map<std::string, size_t> ids;
  std::vector<size_t> view_camera;
  for (const CameraFileView& v : views) {
    const std::string text = FlowMap(InteriorFields(v.camera, o));
    const auto [it, fresh] = ids.emplace(text, interiors.size());
    if (fresh) interiors.push_back(text);
    view_camera.push_back(it->second);
  }
  std::string out =
      "# sacfuse camera file (io/camera_file.h). R = R_x(omega) R_y(phi) R_z(kappa) maps the photogrammetric camera\n"
      "# frame (x right, y up, z toward the viewer) into the attitude frame; positions are projection centres.\n"
      "version: 1\ncameras:\n";
  for (size_t i = 0; i < interiors.size(); ++i) out += "  cam" + std::to_string(i) + ": " + interiors[i] + "\n";
  out += "views:\n";
  for (size_t i = 0; i < views.size(); ++i) {
    const CameraFileView& v = views[i];
    std::vector<std::pair<std::string, std::string>> f = {{"image", YamlString(v.image)},
                                                          {"depth", YamlString(v.depth)}};
    if (!v.image_path.empty()) f.emplace_back("image_path", YamlString(v.image_path));
    f.emplace_back("camera", "cam" + std::to_string(view_camera[i]));
    const auto ext = ExteriorFields(v, o);
    f.insert(f.end(), ext.begin(), ext.end());
    out += "  - " + FlowMap(f) + "\n";
  }
  if (!file.scene_heights_m.empty()) {
    out +=
        "# heights of known scene points (tie points), metres: they bound the tile-planning height range\n"
        "scene_heights_m: [";
    for (size_t i = 0; i < file.scene_heights_m.size(); ++i) out += (i ? ", " : "") + Num(file.scene_heights_m[i]);
    out += "]\n";
  }
  return out;
}

std::string CsvText(const std::vector<CameraFileView>& views, const CameraFileWriteOptions& o) {
  std::vector<std::string> columns;  // union of every view's fields, in first-seen order
  std::vector<std::map<std::string, std::string>> rows;
  for (const CameraFileView& v : views) {
    std::vector<std::pair<std::string, std::string>> f = {{"image", v.image}, {"depth", v.depth}};
    if (!v.image_path.empty()) f.emplace_back("image_path", v.image_path);
    for (const auto& part : {InteriorFields(v.camera, o), ExteriorFields(v, o)})
      f.insert(f.end(), part.begin(), part.end());
    std::map<std::string, std::string> row;
    for (const auto& [k, text] : f) {
      if (std::find(columns.begin(), columns.end(), k) == columns.end()) columns.push_back(k);
      row[k] = text;
    }
    rows.push_back(std::move(row));
  }
  std::string out =
      "# sacfuse camera file (io/camera_file.h): one view per line; R (r11..r33, row-major, or omega/phi/kappa) maps\n"
      "# the photogrammetric camera frame (x right, y up, z toward the viewer) into the attitude frame.\n";
  for (size_t i = 0; i < columns.size(); ++i) out += (i ? "," : "") + columns[i];
  out += "\n";
  for (const auto& row : rows) {
    for (size_t i = 0; i < columns.size(); ++i) {
      const auto it = row.find(columns[i]);
      out += (i ? "," : "") + (it == row.end() ? std::string() : CsvCell(it->second));
    }
    out += "\n";
  }
  return out;
}

}  // namespace

void WriteCameraFile(const std::string& path, const CameraFile& file, const CameraFileWriteOptions& options) {
  CameraFileFormat format;
  try {
    format = CameraFileFormatOf(path);
  } catch (const InputError& e) {
    throw Error(e.what());
  }
  if (format == CameraFileFormat::kCsv && !file.scene_heights_m.empty()) {
    throw Error(path + ": a CSV camera file cannot hold scene heights (write YAML)");
  }
  WriteFileAtomically(path, format == CameraFileFormat::kYaml ? YamlText(file, options) : CsvText(file.views, options));
}

}  // namespace sacfuse
