#include "io/colmap_model.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string_view>
#include <type_traits>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/input_file.h"

namespace sacfuse {
namespace {

struct ModelInfo {
  int id;
  const char* name;
  int num_params;
};
constexpr ModelInfo kModels[] = {
    {0, "SIMPLE_PINHOLE", 3},        {1, "PINHOLE", 4},         {2, "SIMPLE_RADIAL", 4},
    {3, "RADIAL", 5},                {4, "OPENCV", 8},          {5, "OPENCV_FISHEYE", 8},
    {6, "FULL_OPENCV", 12},          {7, "FOV", 5},             {8, "SIMPLE_RADIAL_FISHEYE", 4},
    {9, "RADIAL_FISHEYE", 5},        {10, "THIN_PRISM_FISHEYE", 12}, {11, "RAD_TAN_THIN_PRISM_FISHEYE", 16},
};
const ModelInfo* FindModel(const std::string& name) {
  for (const ModelInfo& m : kModels) {
    if (name == m.name) return &m;
  }
  return nullptr;
}
constexpr uint64_t kInvalidPoint3DId = std::numeric_limits<uint64_t>::max();

std::string Join(const std::string& dir, const char* file) { return (std::filesystem::path(dir) / file).string(); }

std::string ParamCountError(const std::string& model, size_t got) {
  return "camera model " + model + " takes " + std::to_string(ColmapCameraModelNumParams(model)) +
         " parameters, got " + std::to_string(got);
}

// Unit quaternion from the file's (w, x, y, z); COLMAP normalises on read too.
Eigen::Quaterniond NormalisedQuaternion(double w, double x, double y, double z, const std::string& path,
                                        const std::string& where) {
  Eigen::Quaterniond q(w, x, y, z);
  const double norm = q.norm();
  if (!std::isfinite(norm) || norm < 1e-12) {
    throw InputError(path, where + ": quaternion (" + std::to_string(w) + ", " + std::to_string(x) + ", " +
                               std::to_string(y) + ", " + std::to_string(z) + ") cannot be normalised");
  }
  q.coeffs() /= norm;
  return q;
}

// ---------------------------------------------------------------------------------------------------------------
// Binary: explicit little-endian decoding, with the record being read named in every truncation error.

class BinaryReader {
 public:
  explicit BinaryReader(const std::string& path) : path_(path), in_(OpenInputStream(path, "COLMAP model file")) {
    in_.seekg(0, std::ios::end);
    size_ = static_cast<uint64_t>(in_.tellg());
    in_.seekg(0);
  }
  void SetRecord(std::string record) { record_ = std::move(record); }
  uint64_t remaining() const { return size_ - pos_; }

  uint64_t U64() { return Uint(8); }
  uint32_t U32() { return static_cast<uint32_t>(Uint(4)); }
  int32_t I32() { return static_cast<int32_t>(static_cast<uint32_t>(Uint(4))); }
  uint8_t U8() { return static_cast<uint8_t>(Uint(1)); }
  double F64() {
    const uint64_t bits = Uint(8);
    double value;
    std::memcpy(&value, &bits, sizeof(value));
    return value;
  }
  std::string CString() {
    std::string s;
    for (;;) {
      const char c = static_cast<char>(U8());
      if (c == '\0') return s;
      s += c;
    }
  }
  // Fails early when `count` items of at least `min_bytes` each cannot fit (no huge allocations on garbage).
  void Expect(uint64_t count, uint64_t min_bytes, const std::string& what) {
    if (count > remaining() / min_bytes) {
      throw InputError(path_, "truncated" + (record_ == "the header" ? std::string() : " in " + record_) + ": " +
                                  what + " = " + std::to_string(count) +
                                  " needs at least " + std::to_string(min_bytes) + " bytes each but only " +
                                  std::to_string(remaining()) + " bytes remain");
    }
  }
  void ExpectEnd() {
    if (remaining() != 0) {
      throw InputError(path_, std::to_string(remaining()) + " unexpected trailing bytes after the last record");
    }
  }

 private:
  uint64_t Uint(int bytes) {
    uint8_t b[8];
    if (remaining() < static_cast<uint64_t>(bytes) || !in_.read(reinterpret_cast<char*>(b), bytes)) {
      throw InputError(path_, "truncated in " + record_ + " (at byte " + std::to_string(pos_) + " of " +
                                  std::to_string(size_) + ")");
    }
    pos_ += bytes;
    uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | b[i];
    return v;
  }

  std::string path_;
  std::ifstream in_;
  uint64_t size_ = 0;
  uint64_t pos_ = 0;
  std::string record_ = "the header";
};

// Little-endian appends: Put(&out, value) writes sizeof(value) bytes.
template <typename T>
void Put(std::string* out, T value) {
  uint64_t bits = 0;
  if constexpr (std::is_floating_point_v<T>) {
    std::memcpy(&bits, &value, sizeof(value));
  } else {
    bits = static_cast<uint64_t>(value);
  }
  for (size_t i = 0; i < sizeof(T); ++i) *out += static_cast<char>((bits >> (8 * i)) & 0xff);
}

std::string RecordName(const char* kind, uint64_t i, uint64_t n) {
  return std::string(kind) + " record " + std::to_string(i + 1) + " of " + std::to_string(n);
}

void ReadCamerasBinary(const std::string& path, ColmapModel* model) {
  BinaryReader r(path);
  const uint64_t n = r.U64();
  r.Expect(n, 4 + 4 + 8 + 8, "number of cameras");
  for (uint64_t i = 0; i < n; ++i) {
    r.SetRecord(RecordName("camera", i, n));
    ColmapCamera cam;
    cam.camera_id = r.U32();
    const int32_t model_id = r.I32();
    const std::string where = RecordName("camera", i, n) + " (camera_id " + std::to_string(cam.camera_id) + ")";
    r.SetRecord(where);
    cam.model = ColmapCameraModelName(model_id);
    if (cam.model.empty()) throw InputError(path, where + ": unknown camera model id " + std::to_string(model_id));
    cam.width = r.U64();
    cam.height = r.U64();
    cam.params.resize(ColmapCameraModelNumParams(cam.model));
    for (double& p : cam.params) p = r.F64();
    if (!model->cameras.emplace(cam.camera_id, cam).second) {
      throw InputError(path, where + ": duplicated camera_id " + std::to_string(cam.camera_id));
    }
  }
  r.ExpectEnd();
}

void ReadImagesBinary(const std::string& path, ColmapModel* model) {
  BinaryReader r(path);
  const uint64_t n = r.U64();
  r.Expect(n, 4 + 7 * 8 + 4 + 1 + 8, "number of images");
  model->images.reserve(n);
  for (uint64_t i = 0; i < n; ++i) {
    r.SetRecord(RecordName("image", i, n));
    ColmapImage img;
    img.image_id = r.U32();
    std::string where = RecordName("image", i, n) + " (image_id " + std::to_string(img.image_id) + ")";
    r.SetRecord(where);
    double q[4];
    for (double& v : q) v = r.F64();
    for (int k = 0; k < 3; ++k) img.cam_from_world_translation[k] = r.F64();
    img.camera_id = r.U32();
    img.name = r.CString();
    where = RecordName("image", i, n) + " (image_id " + std::to_string(img.image_id) + ", \"" + img.name + "\")";
    r.SetRecord(where);
    img.cam_from_world_rotation = NormalisedQuaternion(q[0], q[1], q[2], q[3], path, where);
    const uint64_t num_points = r.U64();
    r.Expect(num_points, 24, "num_points2D");
    img.points2D.resize(num_points);
    for (ColmapPoint2D& p : img.points2D) {
      p.xy.x() = r.F64();
      p.xy.y() = r.F64();
      p.point3D_id = r.U64();
    }
    model->images.push_back(std::move(img));
  }
  r.ExpectEnd();
}

void ReadPoints3DBinary(const std::string& path, ColmapModel* model) {
  BinaryReader r(path);
  const uint64_t n = r.U64();
  r.Expect(n, 8 + 24 + 3 + 8 + 8, "number of points");
  for (uint64_t i = 0; i < n; ++i) {
    r.SetRecord(RecordName("point3D", i, n));
    ColmapPoint3D pt;
    pt.point3D_id = r.U64();
    const std::string where = RecordName("point3D", i, n) + " (point3D_id " + std::to_string(pt.point3D_id) + ")";
    r.SetRecord(where);
    for (int k = 0; k < 3; ++k) pt.xyz[k] = r.F64();
    for (uint8_t& c : pt.rgb) c = r.U8();
    pt.error = r.F64();
    const uint64_t track_length = r.U64();
    r.Expect(track_length, 8, "track_length");
    pt.track.resize(track_length);
    for (ColmapTrackElement& el : pt.track) {
      el.image_id = r.U32();
      el.point2D_idx = r.U32();
    }
    const uint64_t id = pt.point3D_id;
    if (!model->points3D.emplace(id, std::move(pt)).second) {
      throw InputError(path, where + ": duplicated point3D_id " + std::to_string(id));
    }
  }
  r.ExpectEnd();
}

// ---------------------------------------------------------------------------------------------------------------
// Text: '#' comment lines, whitespace-separated fields; images take two lines each (the second may be empty).

class TextReader {
 public:
  explicit TextReader(const std::string& path) : path_(path), in_(OpenInputStream(path, "COLMAP model file")) {}
  // Next line with trailing CR/whitespace removed; false at end of file.
  bool NextLine(std::string* line) {
    if (!std::getline(in_, *line)) return false;
    ++line_number_;
    const size_t end = line->find_last_not_of(" \t\r\n");
    line->erase(end == std::string::npos ? 0 : end + 1);
    const size_t begin = line->find_first_not_of(" \t");
    line->erase(0, begin == std::string::npos ? line->size() : begin);
    return true;
  }
  // Next line that is neither empty nor a comment.
  bool NextDataLine(std::string* line) {
    while (NextLine(line)) {
      if (!line->empty() && (*line)[0] != '#') return true;
    }
    return false;
  }
  [[noreturn]] void Fail(const std::string& message) const {
    throw InputError(path_, "line " + std::to_string(line_number_) + ": " + message);
  }
  const std::string& path() const { return path_; }
  int line_number() const { return line_number_; }

 private:
  std::string path_;
  std::ifstream in_;
  int line_number_ = 0;
};

// Splits on spaces/tabs; when `max_tokens` is reached the rest of the line (trimmed) is the last token.
std::vector<std::string_view> Tokenize(std::string_view line, size_t max_tokens = SIZE_MAX) {
  std::vector<std::string_view> tokens;
  size_t pos = 0;
  while (pos < line.size()) {
    pos = line.find_first_not_of(" \t", pos);
    if (pos == std::string_view::npos) break;
    if (tokens.size() + 1 == max_tokens) {
      tokens.push_back(line.substr(pos));
      break;
    }
    const size_t end = std::min(line.find_first_of(" \t", pos), line.size());
    tokens.push_back(line.substr(pos, end - pos));
    pos = end;
  }
  return tokens;
}

template <typename T>
T ParseInt(const TextReader& r, std::string_view token, const char* field) {
  T value{};
  const char* end = token.data() + token.size();
  const auto res = std::from_chars(token.data(), end, value);
  if (res.ec != std::errc() || res.ptr != end) {
    r.Fail(std::string("invalid ") + field + " \"" + std::string(token) + "\"");
  }
  return value;
}

double ParseDouble(const TextReader& r, std::string_view token, const char* field) {
  std::string_view t = token;
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  double value = 0.0;
  const char* end = t.data() + t.size();
  const auto res = std::from_chars(t.data(), end, value);
  if (t.empty() || res.ec != std::errc() || res.ptr != end) {
    r.Fail(std::string("invalid ") + field + " \"" + std::string(token) + "\"");
  }
  return value;
}

uint64_t ParsePoint3DId(const TextReader& r, std::string_view token) {
  if (token == "-1") return kInvalidPoint3DId;
  return ParseInt<uint64_t>(r, token, "POINT3D_ID");
}

void ReadCamerasText(const std::string& path, ColmapModel* model) {
  TextReader r(path);
  std::string line;
  while (r.NextDataLine(&line)) {
    const auto t = Tokenize(line);
    if (t.size() < 4) r.Fail("expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS[], got \"" + line + "\"");
    ColmapCamera cam;
    cam.camera_id = ParseInt<uint32_t>(r, t[0], "CAMERA_ID");
    cam.model = std::string(t[1]);
    const int num_params = ColmapCameraModelNumParams(cam.model);
    if (num_params < 0) r.Fail("unknown camera model \"" + cam.model + "\"");
    cam.width = ParseInt<uint64_t>(r, t[2], "WIDTH");
    cam.height = ParseInt<uint64_t>(r, t[3], "HEIGHT");
    for (size_t k = 4; k < t.size(); ++k) cam.params.push_back(ParseDouble(r, t[k], "camera parameter"));
    if (static_cast<int>(cam.params.size()) != num_params) {
      r.Fail("camera_id " + std::to_string(cam.camera_id) + ": " + ParamCountError(cam.model, cam.params.size()));
    }
    if (!model->cameras.emplace(cam.camera_id, cam).second) {
      r.Fail("duplicated camera_id " + std::to_string(cam.camera_id));
    }
  }
}

void ReadImagesText(const std::string& path, ColmapModel* model) {
  TextReader r(path);
  std::string line;
  while (r.NextDataLine(&line)) {
    const auto t = Tokenize(line, 10);
    if (t.size() < 10) r.Fail("expected IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME, got \"" + line + "\"");
    ColmapImage img;
    img.image_id = ParseInt<uint32_t>(r, t[0], "IMAGE_ID");
    double q[4];
    for (int k = 0; k < 4; ++k) q[k] = ParseDouble(r, t[1 + k], "quaternion component");
    for (int k = 0; k < 3; ++k) img.cam_from_world_translation[k] = ParseDouble(r, t[5 + k], "translation");
    img.camera_id = ParseInt<uint32_t>(r, t[8], "CAMERA_ID");
    img.name = std::string(t[9]);
    const std::string where =
        "line " + std::to_string(r.line_number()) + ": image_id " + std::to_string(img.image_id) + " (\"" + img.name + "\")";
    img.cam_from_world_rotation = NormalisedQuaternion(q[0], q[1], q[2], q[3], path, where);
    // The POINTS2D line always follows, empty when the image has none (a missing last line is accepted).
    if (r.NextLine(&line)) {
      const auto p = Tokenize(line);
      if (p.size() % 3 != 0) {
        r.Fail("POINTS2D of image_id " + std::to_string(img.image_id) + " (\"" + img.name + "\"): " +
               std::to_string(p.size()) + " fields is not a multiple of 3 (X Y POINT3D_ID)");
      }
      img.points2D.resize(p.size() / 3);
      for (size_t k = 0; k < img.points2D.size(); ++k) {
        img.points2D[k].xy = {ParseDouble(r, p[3 * k], "point2D X"), ParseDouble(r, p[3 * k + 1], "point2D Y")};
        img.points2D[k].point3D_id = ParsePoint3DId(r, p[3 * k + 2]);
      }
    }
    model->images.push_back(std::move(img));
  }
}

void ReadPoints3DText(const std::string& path, ColmapModel* model) {
  TextReader r(path);
  std::string line;
  while (r.NextDataLine(&line)) {
    const auto t = Tokenize(line);
    if (t.size() < 8 || (t.size() - 8) % 2 != 0) {
      r.Fail("expected POINT3D_ID X Y Z R G B ERROR followed by (IMAGE_ID POINT2D_IDX) pairs, got " +
             std::to_string(t.size()) + " fields");
    }
    ColmapPoint3D pt;
    pt.point3D_id = ParseInt<uint64_t>(r, t[0], "POINT3D_ID");
    for (int k = 0; k < 3; ++k) pt.xyz[k] = ParseDouble(r, t[1 + k], "coordinate");
    for (int k = 0; k < 3; ++k) {
      const unsigned v = ParseInt<unsigned>(r, t[4 + k], "colour");
      if (v > 255) r.Fail("colour component " + std::to_string(v) + " > 255");
      pt.rgb[k] = static_cast<uint8_t>(v);
    }
    pt.error = ParseDouble(r, t[7], "ERROR");
    pt.track.resize((t.size() - 8) / 2);
    for (size_t k = 0; k < pt.track.size(); ++k) {
      pt.track[k].image_id = ParseInt<uint32_t>(r, t[8 + 2 * k], "track IMAGE_ID");
      pt.track[k].point2D_idx = ParseInt<uint32_t>(r, t[9 + 2 * k], "track POINT2D_IDX");
    }
    const uint64_t id = pt.point3D_id;
    if (!model->points3D.emplace(id, std::move(pt)).second) r.Fail("duplicated point3D_id " + std::to_string(id));
  }
}

// Shortest decimal that reads back to the same double (to_chars round-trip guarantee).
std::string Num(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, res.ptr);
}

void CheckCameraForWriting(const ColmapCamera& cam, const std::string& path) {
  const int num_params = ColmapCameraModelNumParams(cam.model);
  if (num_params < 0) throw Error(path + ": camera_id " + std::to_string(cam.camera_id) + ": unknown model " + cam.model);
  if (static_cast<int>(cam.params.size()) != num_params) {
    throw Error(path + ": camera_id " + std::to_string(cam.camera_id) + ": " + ParamCountError(cam.model, cam.params.size()));
  }
}

void CheckImageNameForWriting(const std::string& name, const std::string& path, bool text) {
  // Binary names are NUL-terminated; text names end at the line break (COLMAP trims surrounding spaces).
  const bool invalid = name.empty() || name.find('\0') != std::string::npos ||
                       (text && (name.find_first_of("\r\n") != std::string::npos ||
                                 name.front() == ' ' || name.back() == ' ' || name.front() == '\t' ||
                                 name.back() == '\t'));
  if (invalid) throw Error(path + ": image name \"" + name + "\" cannot be stored in this format");
}

}  // namespace

int ColmapCameraModelId(const std::string& model_name) {
  const ModelInfo* m = FindModel(model_name);
  return m ? m->id : -1;
}
std::string ColmapCameraModelName(int model_id) {
  for (const ModelInfo& m : kModels) {
    if (model_id == m.id) return m.name;
  }
  return "";
}
int ColmapCameraModelNumParams(const std::string& model_name) {
  const ModelInfo* m = FindModel(model_name);
  return m ? m->num_params : -1;
}

ColmapModel ReadColmapModel(const std::string& dir) {
  ColmapModel model;
  using Reader = void (*)(const std::string&, ColmapModel*);
  struct Part {
    const char* stem;
    Reader binary;
    Reader text;
  };
  const Part parts[] = {{"cameras", ReadCamerasBinary, ReadCamerasText},
                        {"images", ReadImagesBinary, ReadImagesText},
                        {"points3D", ReadPoints3DBinary, ReadPoints3DText}};
  std::string images_path;
  for (const Part& part : parts) {
    const std::string bin = Join(dir, (std::string(part.stem) + ".bin").c_str());
    const std::string txt = Join(dir, (std::string(part.stem) + ".txt").c_str());
    std::error_code ec;
    std::string used;
    // Whatever is there is read through the readers' checks (a FIFO or folder named cameras.bin is refused).
    if (std::filesystem::exists(std::filesystem::symlink_status(bin, ec))) {
      part.binary(used = bin, &model);
    } else if (std::filesystem::exists(std::filesystem::symlink_status(txt, ec))) {
      part.text(used = txt, &model);
    } else {
      throw InputError(bin, std::string("missing COLMAP sparse model file (neither ") + part.stem + ".bin nor " +
                                part.stem + ".txt exists in " + dir + ")");
    }
    if (std::string(part.stem) == "images") images_path = used;
  }
  std::set<uint32_t> image_ids;
  for (const ColmapImage& img : model.images) {
    const std::string what = "image_id " + std::to_string(img.image_id) + " (\"" + img.name + "\")";
    if (!image_ids.insert(img.image_id).second) throw InputError(images_path, "duplicated " + what);
    if (model.cameras.count(img.camera_id) == 0) {
      throw InputError(images_path, what + " refers to camera_id " + std::to_string(img.camera_id) +
                                        ", which is not in the cameras file");
    }
  }
  return model;
}

void WriteColmapModelBinary(const ColmapModel& model, const std::string& dir) {
  const std::string cameras_path = Join(dir, "cameras.bin");
  std::string cams, imgs, pts;
  Put<uint64_t>(&cams, model.cameras.size());
  for (const auto& [id, cam] : model.cameras) {
    CheckCameraForWriting(cam, cameras_path);
    Put<uint32_t>(&cams, cam.camera_id);
    Put<int32_t>(&cams, ColmapCameraModelId(cam.model));
    Put<uint64_t>(&cams, cam.width);
    Put<uint64_t>(&cams, cam.height);
    for (const double p : cam.params) Put(&cams, p);
  }
  const std::string images_path = Join(dir, "images.bin");
  Put<uint64_t>(&imgs, model.images.size());
  for (const ColmapImage& img : model.images) {
    CheckImageNameForWriting(img.name, images_path, false);
    Put<uint32_t>(&imgs, img.image_id);
    const Eigen::Quaterniond& q = img.cam_from_world_rotation;
    for (const double v : {q.w(), q.x(), q.y(), q.z()}) Put(&imgs, v);
    for (int k = 0; k < 3; ++k) Put<double>(&imgs, img.cam_from_world_translation[k]);
    Put<uint32_t>(&imgs, img.camera_id);
    imgs.append(img.name.c_str(), img.name.size() + 1);  // NUL-terminated
    Put<uint64_t>(&imgs, img.points2D.size());
    for (const ColmapPoint2D& p : img.points2D) {
      Put<double>(&imgs, p.xy.x());
      Put<double>(&imgs, p.xy.y());
      Put<uint64_t>(&imgs, p.point3D_id);
    }
  }
  Put<uint64_t>(&pts, model.points3D.size());
  for (const auto& [id, pt] : model.points3D) {
    Put<uint64_t>(&pts, pt.point3D_id);
    for (int k = 0; k < 3; ++k) Put<double>(&pts, pt.xyz[k]);
    for (const uint8_t c : pt.rgb) Put(&pts, c);
    Put<double>(&pts, pt.error);
    Put<uint64_t>(&pts, pt.track.size());
    for (const ColmapTrackElement& el : pt.track) {
      Put<uint32_t>(&pts, el.image_id);
      Put<uint32_t>(&pts, el.point2D_idx);
    }
  }
  WriteFileAtomically(cameras_path, cams);
  WriteFileAtomically(images_path, imgs);
  WriteFileAtomically(Join(dir, "points3D.bin"), pts);
}

void WriteColmapModelText(const ColmapModel& model, const std::string& dir) {
  const std::string cameras_path = Join(dir, "cameras.txt");
  std::string cams =
      "# Camera list with one line of data per camera:\n"
      "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
      "# Number of cameras: " + std::to_string(model.cameras.size()) + "\n";
  for (const auto& [id, cam] : model.cameras) {
    CheckCameraForWriting(cam, cameras_path);
    cams += std::to_string(cam.camera_id) + " " + cam.model + " " + std::to_string(cam.width) + " " +
            std::to_string(cam.height);
    for (const double p : cam.params) cams += " " + Num(p);
    cams += "\n";
  }
  const std::string images_path = Join(dir, "images.txt");
  size_t num_observations = 0;
  for (const ColmapImage& img : model.images) {
    for (const ColmapPoint2D& p : img.points2D) num_observations += p.point3D_id != kInvalidPoint3DId;
  }
  const double mean_obs = model.images.empty() ? 0.0 : static_cast<double>(num_observations) / model.images.size();
  std::string imgs =
      "# Image list with two lines of data per image:\n"
      "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
      "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
      "# Number of images: " + std::to_string(model.images.size()) + ", mean observations per image: " +
      Num(mean_obs) + "\n";
  for (const ColmapImage& img : model.images) {
    CheckImageNameForWriting(img.name, images_path, true);
    const Eigen::Quaterniond& q = img.cam_from_world_rotation;
    const Eigen::Vector3d& t = img.cam_from_world_translation;
    imgs += std::to_string(img.image_id) + " " + Num(q.w()) + " " + Num(q.x()) + " " + Num(q.y()) + " " +
            Num(q.z()) + " " + Num(t.x()) + " " + Num(t.y()) + " " + Num(t.z()) + " " +
            std::to_string(img.camera_id) + " " + img.name + "\n";
    std::string points;
    for (const ColmapPoint2D& p : img.points2D) {
      if (!points.empty()) points += " ";
      points += Num(p.xy.x()) + " " + Num(p.xy.y()) + " " +
                (p.point3D_id == kInvalidPoint3DId ? std::string("-1") : std::to_string(p.point3D_id));
    }
    imgs += points + "\n";
  }
  size_t track_total = 0;
  for (const auto& [id, pt] : model.points3D) track_total += pt.track.size();
  const double mean_track = model.points3D.empty() ? 0.0 : static_cast<double>(track_total) / model.points3D.size();
  std::string pts =
      "# 3D point list with one line of data per point:\n"
      "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
      "# Number of points: " + std::to_string(model.points3D.size()) + ", mean track length: " + Num(mean_track) +
      "\n";
  for (const auto& [id, pt] : model.points3D) {
    pts += std::to_string(pt.point3D_id) + " " + Num(pt.xyz.x()) + " " + Num(pt.xyz.y()) + " " + Num(pt.xyz.z()) +
           " " + std::to_string(pt.rgb[0]) + " " + std::to_string(pt.rgb[1]) + " " + std::to_string(pt.rgb[2]) +
           " " + Num(pt.error);
    for (const ColmapTrackElement& el : pt.track) {
      pts += " " + std::to_string(el.image_id) + " " + std::to_string(el.point2D_idx);
    }
    pts += "\n";
  }
  WriteFileAtomically(cameras_path, cams);
  WriteFileAtomically(images_path, imgs);
  WriteFileAtomically(Join(dir, "points3D.txt"), pts);
}

}  // namespace sacfuse
