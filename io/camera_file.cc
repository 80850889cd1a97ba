#include "io/camera_file.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/photogrammetric_orientation.h"
#include "io/camera_file_format.h"
#include "io/input_file.h"
#include "io/yaml_keys.h"

namespace sacfuse {
namespace {

const std::set<std::string>& InteriorKeys() {
  static const std::set<std::string> keys = {"width_px", "height_px", "focal_px",      "fx_px",  "fy_px", "cx_px",
                                             "cy_px",    "focal_mm",  "pixel_size_um", "ppx_mm", "ppy_mm"};
  return keys;
}

const std::set<std::string>& ViewKeys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = InteriorKeys();
    for (const char* name : {"image", "depth", "image_path", "x_m", "y_m", "z_m", "lat_deg", "lon_deg", "h_m",
                             "omega_deg", "phi_deg", "kappa_deg", "attitude_frame"}) {
      k.insert(name);
    }
    for (const char* r : kRotationKeys) k.insert(r);
    return k;
  }();
  return keys;
}

std::string KeyList(const std::set<std::string>& keys) {
  std::string out;
  for (const std::string& k : keys) out += (out.empty() ? "" : ", ") + k;
  return out;
}

// One view's fields as text, each with its line; `line` is the view's first line.
struct Record {
  std::map<std::string, std::pair<std::string, int>> fields;
  int line = 0;
};

// Turns one record into a view; every message names the file, line, view and field.
class RecordParser {
 public:
  RecordParser(const std::string& file, const Record& record, size_t index, AttitudeFrame* default_frame)
      : file_(file), record_(record), index_(index), default_frame_(default_frame) {}

  CameraFileView Parse() {
    CameraFileView v;
    v.line = record_.line;
    v.image = Text("image", true);
    who_ = "view " + std::to_string(index_ + 1) + " (\"" + v.image + "\")";
    v.depth = Text("depth", true);
    v.image_path = Text("image_path", false);
    v.camera = Interior();
    ExteriorPosition(&v);
    v.rotation = Attitude();
    const std::string frame = Text("attitude_frame", false);
    if (frame.empty()) {
      v.attitude_frame =
          default_frame_ != nullptr ? *default_frame_ : (v.geodetic ? AttitudeFrame::kLocalEnu : AttitudeFrame::kGrid);
    } else if (frame == "grid") {
      v.attitude_frame = AttitudeFrame::kGrid;
    } else if (frame == "local_enu") {
      v.attitude_frame = AttitudeFrame::kLocalEnu;
    } else {
      Fail("attitude_frame", "\"" + frame + "\" is neither grid nor local_enu");
    }
    return v;
  }

 private:
  [[noreturn]] void Fail(const std::string& key, const std::string& problem) const {
    const auto it = record_.fields.find(key);
    const int line = it != record_.fields.end() ? it->second.second : record_.line;
    throw InputError(file_, "line " + std::to_string(line) + ": " +
                                (who_.empty() ? "view " + std::to_string(index_ + 1) : who_) + ": " + key + ": " +
                                problem);
  }
  bool Has(const std::string& key) const { return record_.fields.count(key) != 0; }

  std::string Text(const std::string& key, bool required) const {
    const auto it = record_.fields.find(key);
    if (it == record_.fields.end()) {
      if (required) Fail(key, "missing (required)");
      return "";
    }
    return it->second.first;
  }

  double Number(const std::string& key) const {
    const std::string text = Text(key, true);
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v)) {
      Fail(key, "\"" + text + "\" is not a finite number");
    }
    return v;
  }
  double Positive(const std::string& key) const {
    const double v = Number(key);
    if (!(v > 0)) Fail(key, std::to_string(v) + " must be > 0");
    return v;
  }
  int PositiveInt(const std::string& key) const {
    const double v = Number(key);
    if (!(v >= 1) || v != std::floor(v) || v > 1e9) Fail(key, "\"" + Text(key, true) + "\" must be a positive integer");
    return static_cast<int>(v);
  }
  // All of `keys` or none; returns whether all are present.
  bool AllOrNone(std::initializer_list<const char*> keys, const char* what) const {
    size_t n = 0;
    std::string missing;
    for (const char* k : keys) {
      if (Has(k)) {
        ++n;
      } else {
        missing += (missing.empty() ? "" : ", ") + std::string(k);
      }
    }
    if (n != 0 && n != keys.size()) Fail(missing, std::string("missing: ") + what + " needs all of them");
    return n == keys.size();
  }

  PinholeCamera Interior() const {
    PinholeCamera cam;
    cam.width = PositiveInt("width_px");
    cam.height = PositiveInt("height_px");
    const bool px = Has("focal_px") || Has("fx_px") || Has("fy_px") || Has("cx_px") || Has("cy_px");
    const bool mm = Has("focal_mm") || Has("pixel_size_um") || Has("ppx_mm") || Has("ppy_mm");
    if (px && mm) {
      Fail(Has("focal_mm")        ? "focal_mm"
           : Has("pixel_size_um") ? "pixel_size_um"
           : Has("ppx_mm")        ? "ppx_mm"
                                  : "ppy_mm",
           "mixes the millimetre interior (focal_mm, pixel_size_um, ppx_mm, ppy_mm) with the pixel one "
           "(focal_px or fx_px/fy_px, cx_px, cy_px); give one");
    }
    if (mm) {
      const double focal_mm = Positive("focal_mm");
      const double pitch_mm = Positive("pixel_size_um") / 1000.0;
      const double ppx_mm = Has("ppx_mm") ? Number("ppx_mm") : 0.0;
      const double ppy_mm = Has("ppy_mm") ? Number("ppy_mm") : 0.0;
      cam.fx = cam.fy = focal_mm / pitch_mm;
      cam.cx = 0.5 * cam.width + ppx_mm / pitch_mm;
      cam.cy = 0.5 * cam.height - ppy_mm / pitch_mm;  // photogrammetric y is up, pixel v is down
      return cam;
    }
    if (Has("focal_px")) {
      if (Has("fx_px") || Has("fy_px")) Fail("focal_px", "give either focal_px or fx_px and fy_px, not both");
      cam.fx = cam.fy = Positive("focal_px");
    } else if (Has("fx_px") || Has("fy_px")) {
      cam.fx = Positive("fx_px");
      cam.fy = Positive("fy_px");
    } else {
      Fail("focal_px", "missing: the interior needs focal_px (or fx_px and fy_px) or focal_mm with pixel_size_um");
    }
    cam.cx = Has("cx_px") ? Number("cx_px") : 0.5 * cam.width;
    cam.cy = Has("cy_px") ? Number("cy_px") : 0.5 * cam.height;
    return cam;
  }

  void ExteriorPosition(CameraFileView* v) const {
    const bool project = AllOrNone({"x_m", "y_m", "z_m"}, "a position in the project CRS");
    const bool geodetic = AllOrNone({"lat_deg", "lon_deg", "h_m"}, "a geodetic position");
    if (project && geodetic) Fail("lat_deg", "give the position either as x_m, y_m, z_m or as lat_deg, lon_deg, h_m");
    if (!project && !geodetic) Fail("x_m", "missing: the position needs x_m, y_m, z_m or lat_deg, lon_deg, h_m");
    v->geodetic = geodetic;
    if (geodetic) {
      v->position = {Number("lat_deg"), Number("lon_deg"), Number("h_m")};
      if (std::abs(v->position.x()) > 90.0) Fail("lat_deg", std::to_string(v->position.x()) + " is outside [-90, 90]");
      if (std::abs(v->position.y()) > 360.0)
        Fail("lon_deg", std::to_string(v->position.y()) + " is outside [-360, 360]");
    } else {
      v->position = {Number("x_m"), Number("y_m"), Number("z_m")};
    }
  }

  Eigen::Matrix3d Attitude() const {
    const bool opk = AllOrNone({"omega_deg", "phi_deg", "kappa_deg"}, "an attitude in angles");
    bool matrix = false;
    for (const char* r : kRotationKeys) matrix = matrix || Has(r);
    if (opk && matrix) Fail("r11", "give the attitude either as omega_deg, phi_deg, kappa_deg or as r11..r33");
    if (opk) return ObjectFromPhotoCameraRotation({Number("omega_deg"), Number("phi_deg"), Number("kappa_deg")});
    if (!matrix) Fail("omega_deg", "missing: the attitude needs omega_deg, phi_deg, kappa_deg or r11..r33");
    Eigen::Matrix3d r;
    for (int i = 0; i < 9; ++i) r(i / 3, i % 3) = Number(kRotationKeys[i]);
    if (!IsRotationMatrix(r, 1e-6)) {
      std::ostringstream m;
      m << "r11..r33 are not a rotation matrix (orthonormal within 1e-6, determinant +1): determinant "
        << r.determinant() << ", max |R^T R - I| "
        << (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
      Fail("r11", m.str());
    }
    return r;
  }

  const std::string& file_;
  const Record& record_;
  size_t index_;
  AttitudeFrame* default_frame_;
  std::string who_;
};

std::vector<CameraFileView> ParseRecords(const std::string& path, const std::vector<Record>& records,
                                         AttitudeFrame* default_frame) {
  if (records.empty()) throw InputError(path, "the camera file lists no views");
  std::vector<CameraFileView> views;
  std::map<std::string, int> lines;
  for (size_t i = 0; i < records.size(); ++i) {
    for (const auto& [key, value] : records[i].fields) {
      if (ViewKeys().count(key) == 0) {
        throw InputError(path, "line " + std::to_string(value.second) + ": view " + std::to_string(i + 1) +
                                   ": unknown field \"" + key + "\"; allowed: " + KeyList(ViewKeys()));
      }
    }
    views.push_back(RecordParser(path, records[i], i, default_frame).Parse());
    const auto [it, fresh] = lines.emplace(views.back().image, records[i].line);
    if (!fresh) {
      throw InputError(path, "line " + std::to_string(records[i].line) + ": image \"" + views.back().image +
                                 "\" is listed twice (first on line " + std::to_string(it->second) + ")");
    }
  }
  return views;
}

// ---- reading YAML ----

int LineOf(const YAML::Node& node) { return node.Mark().line + 1; }

std::string ScalarText(const std::string& path, const YAML::Node& node, const std::string& key) {
  if (!node.IsScalar()) {
    throw InputError(path, "line " + std::to_string(LineOf(node)) + ": " + key + ": expected a single value");
  }
  return node.Scalar();
}

// Throws for the first repeated key of a mapping (`where` prefixes the key, e.g. "cameras.c1.").
void RefuseRepeatedKeys(const std::string& path, const YAML::Node& map, const std::string& where) {
  const std::vector<YamlRepeatedKey> repeats = RepeatedYamlKeys(map);
  if (!repeats.empty()) {
    throw InputError(path, "line " + std::to_string(repeats[0].line) + ": " + where + repeats[0].key + ": " +
                               RepeatedYamlKeyProblem(repeats[0]));
  }
}

CameraFile ReadYaml(const std::string& path) {
  YAML::Node root;
  int second_document_line = 0;
  try {
    std::ostringstream text;
    text << OpenInputStream(path, "camera file").rdbuf();
    root = LoadOneYamlDocument(text.str(), &second_document_line);
  } catch (const YAML::ParserException& e) {
    throw InputError(path, "line " + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw InputError(path, std::string("cannot read: ") + e.what());
  }
  if (second_document_line > 0) {
    throw InputError(path, "line " + std::to_string(second_document_line) + ": " +
                               YamlSecondDocumentProblem("a camera file"));
  }
  if (!root.IsMap()) throw InputError(path, "expected a YAML map with a `views:` list");
  RefuseRepeatedKeys(path, root, "");
  std::map<std::string, YAML::Node> cameras;
  std::optional<AttitudeFrame> default_frame;
  std::vector<double> scene_heights;
  YAML::Node views_node;
  for (const auto& entry : root) {
    const std::string key = entry.first.Scalar();
    const int line = LineOf(entry.first);
    if (key == "version") {
      if (ScalarText(path, entry.second, key) != "1") {
        throw InputError(path, "line " + std::to_string(line) + ": version: only version 1 is known");
      }
    } else if (key == "attitude_frame") {
      const std::string f = ScalarText(path, entry.second, key);
      if (f != "grid" && f != "local_enu") {
        throw InputError(
            path, "line " + std::to_string(line) + ": attitude_frame: \"" + f + "\" is neither grid nor local_enu");
      }
      default_frame = f == "grid" ? AttitudeFrame::kGrid : AttitudeFrame::kLocalEnu;
    } else if (key == "cameras") {
      if (!entry.second.IsMap())
        throw InputError(path, "line " + std::to_string(line) + ": cameras: expected a map id -> interior");
      RefuseRepeatedKeys(path, entry.second, "cameras.");
      for (const auto& cam : entry.second) {
        const std::string id = cam.first.Scalar();
        if (!cam.second.IsMap()) {
          throw InputError(path, "line " + std::to_string(LineOf(cam.first)) + ": cameras." + id + ": expected a map");
        }
        RefuseRepeatedKeys(path, cam.second, "cameras." + id + ".");
        for (const auto& field : cam.second) {
          if (InteriorKeys().count(field.first.Scalar()) == 0) {
            throw InputError(path, "line " + std::to_string(LineOf(field.first)) + ": cameras." + id +
                                       ": unknown field \"" + field.first.Scalar() +
                                       "\"; allowed: " + KeyList(InteriorKeys()));
          }
        }
        cameras[id] = cam.second;
      }
    } else if (key == "views") {
      views_node = entry.second;
    } else if (key == "scene_heights_m") {
      if (!entry.second.IsSequence()) {
        throw InputError(path, "line " + std::to_string(line) + ": scene_heights_m: expected a list of heights");
      }
      for (const YAML::Node& z : entry.second) {
        const std::string text = ScalarText(path, z, key);
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v)) {
          throw InputError(
              path, "line " + std::to_string(LineOf(z)) + ": scene_heights_m: \"" + text + "\" is not a finite number");
        }
        scene_heights.push_back(v);
      }
    } else {
      throw InputError(path, "line " + std::to_string(line) + ": unknown top-level key \"" + key +
                                 "\"; allowed: version, attitude_frame, cameras, views, scene_heights_m");
    }
  }
  if (!views_node || !views_node.IsSequence()) throw InputError(path, "missing `views:` list");
  std::vector<Record> records;
  for (const YAML::Node& view : views_node) {
    Record rec;
    rec.line = LineOf(view);
    if (!view.IsMap())
      throw InputError(path, "line " + std::to_string(rec.line) + ": each view must be a map of fields");
    RefuseRepeatedKeys(path, view, "view " + std::to_string(records.size() + 1) + ": ");
    // The named interior first; the view's own fields override it.
    if (const YAML::Node cam = view["camera"]) {
      const std::string id = ScalarText(path, cam, "camera");
      const auto it = cameras.find(id);
      if (it == cameras.end()) {
        throw InputError(path,
                         "line " + std::to_string(LineOf(cam)) + ": camera: \"" + id + "\" is not under `cameras:`");
      }
      for (const auto& field : it->second) {
        rec.fields[field.first.Scalar()] = {ScalarText(path, field.second, field.first.Scalar()), LineOf(field.first)};
      }
    }
    for (const auto& field : view) {
      const std::string key = field.first.Scalar();
      if (key == "camera") continue;
      if (key == "rotation") {
        const YAML::Node& m = field.second;
        if (!m.IsSequence() || m.size() != 3) {
          throw InputError(path, "line " + std::to_string(LineOf(m)) + ": rotation: expected 3 rows of 3 numbers");
        }
        for (size_t i = 0; i < 3; ++i) {
          if (!m[i].IsSequence() || m[i].size() != 3) {
            throw InputError(path, "line " + std::to_string(LineOf(m)) + ": rotation: expected 3 rows of 3 numbers");
          }
          for (size_t j = 0; j < 3; ++j) {
            rec.fields[kRotationKeys[3 * i + j]] = {ScalarText(path, m[i][j], "rotation"), LineOf(m[i][j])};
          }
        }
        continue;
      }
      rec.fields[key] = {ScalarText(path, field.second, key), LineOf(field.first)};
    }
    records.push_back(std::move(rec));
  }
  return {ParseRecords(path, records, default_frame ? &*default_frame : nullptr), std::move(scene_heights)};
}

// ---- reading CSV ----

// Splits one CSV line (RFC 4180 quoting within a line); unquoted cells are trimmed (spaces after commas are
// common), quoted ones kept as they are. Throws on an unterminated quote.
std::vector<std::string> SplitCsv(const std::string& path, const std::string& line, int line_number) {
  std::vector<std::string> cells;
  std::string cell;
  bool quoted = false, was_quoted = false;
  const auto finish = [&] {
    if (!was_quoted) {
      const size_t b = cell.find_first_not_of(" \t");
      const size_t e = cell.find_last_not_of(" \t");
      cell = b == std::string::npos ? "" : cell.substr(b, e - b + 1);
    }
    cells.push_back(cell);
    cell.clear();
    was_quoted = false;
  };
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        cell += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        cell += c;
      }
    } else if (c == '"') {
      if (!was_quoted) cell.clear();  // blanks before the opening quote
      quoted = was_quoted = true;
    } else if (c == ',') {
      finish();
    } else if (!was_quoted) {
      cell += c;  // (text after a closing quote other than blanks is dropped)
    }
  }
  if (quoted) throw InputError(path, "line " + std::to_string(line_number) + ": unterminated quoted cell");
  finish();
  return cells;
}

CameraFile ReadCsv(const std::string& path) {
  std::ifstream in = OpenInputStream(path, "camera file");
  std::vector<std::string> columns;
  std::vector<Record> records;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line_number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // UTF-8 BOM
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    std::vector<std::string> cells = SplitCsv(path, line, line_number);
    if (columns.empty()) {
      std::set<std::string> seen;
      for (const std::string& name : cells) {
        if (ViewKeys().count(name) == 0) {
          throw InputError(path, "line " + std::to_string(line_number) + ": unknown column \"" + name +
                                     "\"; allowed: " + KeyList(ViewKeys()));
        }
        if (!seen.insert(name).second) {
          throw InputError(path, "line " + std::to_string(line_number) + ": column \"" + name + "\" appears twice");
        }
      }
      columns = std::move(cells);
      continue;
    }
    if (cells.size() != columns.size()) {
      throw InputError(path, "line " + std::to_string(line_number) + ": " + std::to_string(cells.size()) +
                                 " cells, but the header names " + std::to_string(columns.size()) + " columns");
    }
    Record rec;
    rec.line = line_number;
    for (size_t i = 0; i < cells.size(); ++i) {
      if (!cells[i].empty()) rec.fields[columns[i]] = {cells[i], line_number};
    }
    records.push_back(std::move(rec));
  }
  if (in.bad()) throw InputError(path, "read error");
  if (columns.empty()) throw InputError(path, "no header line naming the columns");
  return {ParseRecords(path, records, nullptr), {}};
}

}  // namespace

CameraFileFormat CameraFileFormatOf(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".yaml" || ext == ".yml") return CameraFileFormat::kYaml;
  if (ext == ".csv") return CameraFileFormat::kCsv;
  throw InputError(path, "camera file extension \"" + ext + "\" is neither .yaml/.yml nor .csv");
}

CameraFile ReadCameraFile(const std::string& path) {
  const CameraFileFormat format = CameraFileFormatOf(path);
  CheckInputFile(path, "camera file");
  return format == CameraFileFormat::kYaml ? ReadYaml(path) : ReadCsv(path);
}

std::string CameraFileViewText(const CameraFileView& v) {
  return (v.line > 0 ? "line " + std::to_string(v.line) + ": " : std::string()) + "view \"" + v.image + "\"";
}

}  // namespace sacfuse
