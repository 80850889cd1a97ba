#pragma once
// Streaming reader for the vertices of a binary PLY file, as COLMAP's stereo_fusion writes fused.ply
// (binary_little_endian; x y z nx ny nz as float, red green blue as uchar). The header is parsed generally:
// properties may come in any order and with any scalar type (char/int8 ... double/float64), the vertex element
// may sit among other elements of fixed-size properties, binary_big_endian is read too. Not supported (clear
// InputError): ASCII PLY, list properties in or before the vertex element.
#include <array>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sacfuse {

struct PlyVertex {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();  // zero when the file has no nx/ny/nz
  std::array<uint8_t, 3> rgb = {0, 0, 0};             // zero when the file has no red/green/blue
};

class PlyVertexReader {
 public:
  // Opens the file and parses its header; throws InputError naming the file when it is not a PLY this reader
  // handles, lacks x/y/z, or is shorter than its header says.
  explicit PlyVertexReader(const std::string& path);

  uint64_t vertex_count() const { return vertex_count_; }
  bool has_normals() const { return normal_[0] >= 0 && normal_[1] >= 0 && normal_[2] >= 0; }
  bool has_colour() const { return rgb_[0] >= 0 && rgb_[1] >= 0 && rgb_[2] >= 0; }
  // Property names of the vertex element in file order (for messages and tests).
  std::vector<std::string> vertex_properties() const;

  // Reads up to max_count further vertices into *out (resized); returns how many (0 at the end). Throws
  // InputError naming the file when the data end early.
  size_t Read(std::vector<PlyVertex>* out, size_t max_count);

 private:
  enum class Type { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };
  struct Property {
    std::string name;
    Type type;
    size_t offset;  // bytes from the start of the record
  };
  double Value(const char* record, const Property& p) const;

  std::string path_;
  std::ifstream in_;
  bool big_endian_ = false;
  uint64_t vertex_count_ = 0;
  uint64_t vertices_read_ = 0;
  size_t stride_ = 0;  // bytes per vertex record
  std::vector<Property> properties_;
  int xyz_[3] = {-1, -1, -1};  // indices into properties_
  int normal_[3] = {-1, -1, -1};
  int rgb_[3] = {-1, -1, -1};
  std::vector<char> buffer_;
};

}  // namespace sacfuse
