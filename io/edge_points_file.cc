#include "io/edge_points_file.h"

#include <cstdint>
#include <cstring>
#include <iterator>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/input_file.h"

namespace sacfuse {
namespace {

constexpr char kMagic[17] = "sacfuse-edge-v1\n";
constexpr size_t kMagicSize = 16;
constexpr size_t kRecordSize = 3 * sizeof(double);

static_assert(sizeof(double) == 8, "edge point files store float64");

}  // namespace

void WriteEdgePointsFile(const std::string& path, const std::vector<Eigen::Vector3d>& points) {
  std::string bytes(kMagic, kMagicSize);
  const uint64_t count = points.size();
  bytes.append(reinterpret_cast<const char*>(&count), sizeof(count));
  bytes.reserve(bytes.size() + points.size() * kRecordSize);
  for (const Eigen::Vector3d& p : points) {
    for (int i = 0; i < 3; ++i) {
      const double v = p[i];
      bytes.append(reinterpret_cast<const char*>(&v), sizeof(v));
    }
  }
  WriteFileAtomically(path, bytes);
}

std::vector<Eigen::Vector3d> ReadEdgePointsFile(const std::string& path) {
  std::ifstream in = OpenInputStream(path, "tile edge point file");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < kMagicSize + sizeof(uint64_t) || bytes.compare(0, kMagicSize, kMagic) != 0) {
    throw InputError(path, "not a sacfuse edge point file (bad header)");
  }
  uint64_t count = 0;
  std::memcpy(&count, bytes.data() + kMagicSize, sizeof(count));
  const size_t body = bytes.size() - kMagicSize - sizeof(uint64_t);
  if (body % kRecordSize != 0 || body / kRecordSize != count) {
    throw InputError(path, "truncated or corrupt: " + std::to_string(body) + " bytes of records for " +
                               std::to_string(count) + " points");
  }
  std::vector<Eigen::Vector3d> points(count);
  const char* p = bytes.data() + kMagicSize + sizeof(uint64_t);
  for (uint64_t i = 0; i < count; ++i) {
    double v[3];
    std::memcpy(v, p + i * kRecordSize, kRecordSize);
    points[i] = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  return points;
}

}  // namespace sacfuse
