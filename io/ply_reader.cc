#include "io/ply_reader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "io/trimmed.h"

namespace sacfuse {
namespace {

std::vector<std::string> Words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

template <typename T>
T Load(const char* p, bool swap) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, p, sizeof(T));
  if (swap) std::reverse(bytes, bytes + sizeof(T));
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

bool HostIsBigEndian() {
  const uint16_t one = 1;
  uint8_t first;
  std::memcpy(&first, &one, 1);
  return first == 0;
}

uint8_t ColourByte(double v, bool is_float, size_t size) {
  if (is_float) v *= 255.0;           // float colours are in [0, 1]
  else if (size == 2) v /= 257.0;     // 16-bit colours
  return static_cast<uint8_t>(std::clamp(std::lround(v), 0L, 255L));
}

}  // namespace

PlyVertexReader::PlyVertexReader(const std::string& path) : path_(path), in_(path, std::ios::binary) {
  if (!in_) throw InputError(path, "cannot open PLY file");
  std::string line;
  if (!std::getline(in_, line) || Trimmed(line) != "ply") throw InputError(path, "not a PLY file (no \"ply\" magic)");

  struct Element {
    std::string name;
    uint64_t count = 0;
    size_t stride = 0;
    bool has_list = false;
    std::vector<Property> properties;
  };
  std::vector<Element> elements;
  bool format_seen = false, header_done = false;
  int line_number = 1;
  while (std::getline(in_, line)) {
    ++line_number;
    line = Trimmed(line);
    const auto w = Words(line);
    const std::string where = "header line " + std::to_string(line_number) + " (\"" + line + "\")";
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") {
      header_done = true;
      break;
    }
    if (w[0] == "format") {
      if (w.size() < 2) throw InputError(path, where + ": incomplete format line");
      if (w[1] == "binary_little_endian") big_endian_ = false;
      else if (w[1] == "binary_big_endian") big_endian_ = true;
      else if (w[1] == "ascii") throw InputError(path, "ASCII PLY is not supported (only binary)");
      else throw InputError(path, where + ": unknown format \"" + w[1] + "\"");
      format_seen = true;
    } else if (w[0] == "element") {
      if (w.size() != 3) throw InputError(path, where + ": expected \"element NAME COUNT\"");
      Element e;
      e.name = w[1];
      try {
        size_t used = 0;
        e.count = std::stoull(w[2], &used);
        if (used != w[2].size()) throw std::invalid_argument(w[2]);
      } catch (const std::exception&) {
        throw InputError(path, where + ": invalid element count \"" + w[2] + "\"");
      }
      elements.push_back(e);
    } else if (w[0] == "property") {
      if (elements.empty()) throw InputError(path, where + ": property before any element");
      Element& e = elements.back();
      if (w.size() >= 2 && w[1] == "list") {
        e.has_list = true;
        e.properties.push_back({w.size() > 4 ? w[4] : "?", Type::kUint8, 0});
        continue;
      }
      if (w.size() != 3) throw InputError(path, where + ": expected \"property TYPE NAME\"");
      static const std::pair<const char*, std::pair<Type, size_t>> kTypes[] = {
          {"char", {Type::kInt8, 1}},     {"int8", {Type::kInt8, 1}},       {"uchar", {Type::kUint8, 1}},
          {"uint8", {Type::kUint8, 1}},   {"short", {Type::kInt16, 2}},     {"int16", {Type::kInt16, 2}},
          {"ushort", {Type::kUint16, 2}}, {"uint16", {Type::kUint16, 2}},   {"int", {Type::kInt32, 4}},
          {"int32", {Type::kInt32, 4}},   {"uint", {Type::kUint32, 4}},     {"uint32", {Type::kUint32, 4}},
          {"float", {Type::kFloat32, 4}}, {"float32", {Type::kFloat32, 4}}, {"double", {Type::kFloat64, 8}},
          {"float64", {Type::kFloat64, 8}}};
      bool known = false;
      for (const auto& [name, type_size] : kTypes) {
        if (w[1] == name) {
          e.properties.push_back({w[2], type_size.first, e.stride});
          e.stride += type_size.second;
          known = true;
          break;
        }
      }
      if (!known) throw InputError(path, where + ": unknown property type \"" + w[1] + "\"");
    } else {
      throw InputError(path, where + ": unknown header keyword \"" + w[0] + "\"");
    }
  }
  if (!header_done) throw InputError(path, "PLY header has no end_header line (truncated file?)");
  if (!format_seen) throw InputError(path, "PLY header has no format line");

  // Skip fixed-size elements before "vertex"; lists there would need parsing every record, which we do not need.
  uint64_t skip_bytes = 0;
  const Element* vertex = nullptr;
  for (const Element& e : elements) {
    if (e.name == "vertex") {
      vertex = &e;
      break;
    }
    if (e.has_list) {
      throw InputError(path, "element \"" + e.name + "\" with list properties before the vertex element is not "
                             "supported");
    }
    skip_bytes += e.count * e.stride;
  }
  if (!vertex) throw InputError(path, "PLY file has no vertex element");
  if (vertex->has_list) throw InputError(path, "list properties in the vertex element are not supported");
  properties_ = vertex->properties;
  vertex_count_ = vertex->count;
  stride_ = vertex->stride;

  static const char* const kXyz[3] = {"x", "y", "z"};
  static const char* const kNormal[3] = {"nx", "ny", "nz"};
  static const char* const kRgb[3] = {"red", "green", "blue"};
  static const char* const kDiffuse[3] = {"diffuse_red", "diffuse_green", "diffuse_blue"};
  for (int i = 0; i < static_cast<int>(properties_.size()); ++i) {
    const std::string& n = properties_[i].name;
    for (int k = 0; k < 3; ++k) {
      if (n == kXyz[k]) xyz_[k] = i;
      if (n == kNormal[k]) normal_[k] = i;
      if (n == kRgb[k] || (n == kDiffuse[k] && rgb_[k] < 0)) rgb_[k] = i;
    }
  }
  for (int k = 0; k < 3; ++k) {
    if (xyz_[k] < 0) throw InputError(path, std::string("vertex element has no property \"") + kXyz[k] + "\"");
  }

  const std::streamoff data_start = in_.tellg();
  const uint64_t file_size = std::filesystem::file_size(path);
  const uint64_t needed = static_cast<uint64_t>(data_start) + skip_bytes + vertex_count_ * stride_;
  if (file_size < needed) {
    throw InputError(path, "truncated PLY: the header promises " + std::to_string(vertex_count_) + " vertices of " +
                               std::to_string(stride_) + " bytes (data ending at byte " + std::to_string(needed) +
                               ") but the file has " + std::to_string(file_size) + " bytes");
  }
  in_.seekg(data_start + static_cast<std::streamoff>(skip_bytes));
  big_endian_ = big_endian_ != HostIsBigEndian();  // from here on: "swap bytes"
}

std::vector<std::string> PlyVertexReader::vertex_properties() const {
  std::vector<std::string> names;
  for (const Property& p : properties_) names.push_back(p.name);
  return names;
}

double PlyVertexReader::Value(const char* record, const Property& p) const {
  const char* at = record + p.offset;
  const bool swap = big_endian_;
  switch (p.type) {
    case Type::kInt8: return Load<int8_t>(at, false);
    case Type::kUint8: return Load<uint8_t>(at, false);
    case Type::kInt16: return Load<int16_t>(at, swap);
    case Type::kUint16: return Load<uint16_t>(at, swap);
    case Type::kInt32: return Load<int32_t>(at, swap);
    case Type::kUint32: return Load<uint32_t>(at, swap);
    case Type::kFloat32: return Load<float>(at, swap);
    case Type::kFloat64: return Load<double>(at, swap);
  }
  return 0.0;
}

size_t PlyVertexReader::Read(std::vector<PlyVertex>* out, size_t max_count) {
  const size_t n = static_cast<size_t>(std::min<uint64_t>(max_count, vertex_count_ - vertices_read_));
  out->resize(n);
  if (n == 0) return 0;
  buffer_.resize(n * stride_);
  in_.read(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  if (static_cast<size_t>(in_.gcount()) != buffer_.size()) {
    throw InputError(path_, "truncated PLY: data end after " +
                                std::to_string(vertices_read_ + static_cast<uint64_t>(in_.gcount()) / stride_) +
                                " of " + std::to_string(vertex_count_) + " vertices");
  }
  auto is_float = [](Type t) { return t == Type::kFloat32 || t == Type::kFloat64; };
  auto size_of = [](Type t) -> size_t {
    switch (t) {
      case Type::kInt8: case Type::kUint8: return 1;
      case Type::kInt16: case Type::kUint16: return 2;
      case Type::kFloat64: return 8;
      default: return 4;
    }
  };
  for (size_t i = 0; i < n; ++i) {
    const char* record = buffer_.data() + i * stride_;
    PlyVertex& v = (*out)[i];
    for (int k = 0; k < 3; ++k) v.xyz[k] = Value(record, properties_[xyz_[k]]);
    if (has_normals()) {
      for (int k = 0; k < 3; ++k) v.normal[k] = static_cast<float>(Value(record, properties_[normal_[k]]));
    } else {
      v.normal.setZero();
    }
    if (has_colour()) {
      for (int k = 0; k < 3; ++k) {
        const Property& p = properties_[rgb_[k]];
        v.rgb[k] = ColourByte(Value(record, p), is_float(p.type), size_of(p.type));
      }
    } else {
      v.rgb = {0, 0, 0};
    }
  }
  vertices_read_ += n;
  return n;
}

}  // namespace sacfuse
