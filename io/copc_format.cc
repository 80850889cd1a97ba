#include "io/copc_format.h"

#include <array>
#include <cmath>

#include "io/las_format.h"

namespace sacfuse::copc {
namespace lf = las_format;

std::vector<uint8_t> EncodeInfo(const Info& info) {
  std::vector<uint8_t> b(kInfoSize, 0);  // the 11 reserved words stay 0
  for (int a = 0; a < 3; ++a) lf::PutF64(&b[8 * a], info.center[a]);
  lf::PutF64(&b[24], info.halfsize);
  lf::PutF64(&b[32], info.spacing);
  lf::PutU64(&b[40], info.root_hier_offset);
  lf::PutU64(&b[48], info.root_hier_size);
  lf::PutF64(&b[56], info.gpstime_minimum);
  lf::PutF64(&b[64], info.gpstime_maximum);
  return b;
}

std::string DecodeInfo(const std::vector<uint8_t>& payload, Info* info) {
  if (payload.size() != kInfoSize) {
    return "info VLR has " + std::to_string(payload.size()) + " bytes, COPC 1.0 has " + std::to_string(kInfoSize);
  }
  const uint8_t* b = payload.data();
  for (int a = 0; a < 3; ++a) info->center[a] = lf::GetF64(b + 8 * a);
  info->halfsize = lf::GetF64(b + 24);
  info->spacing = lf::GetF64(b + 32);
  info->root_hier_offset = lf::GetU64(b + 40);
  info->root_hier_size = lf::GetU64(b + 48);
  info->gpstime_minimum = lf::GetF64(b + 56);
  info->gpstime_maximum = lf::GetF64(b + 64);
  for (size_t at = 72; at < kInfoSize; at += 8) {
    if (lf::GetU64(b + at) != 0) return "info VLR reserved word at byte " + std::to_string(at) + " is not 0";
  }
  if (!info->center.allFinite() || !std::isfinite(info->halfsize) || !(info->halfsize > 0.0)) {
    return "info VLR cube is not finite or has no size (halfsize " + std::to_string(info->halfsize) + ")";
  }
  if (!std::isfinite(info->spacing) || !(info->spacing > 0.0)) {
    return "info VLR spacing " + std::to_string(info->spacing) + " is not > 0";
  }
  return "";
}

bool VoxelKey::Valid() const {
  if (level < 0 || level > 30) return false;
  const int64_t n = int64_t{1} << level;
  return x >= 0 && y >= 0 && z >= 0 && x < n && y < n && z < n;
}

std::string VoxelKey::ToString() const {
  return std::to_string(level) + "-" + std::to_string(x) + "-" + std::to_string(y) + "-" + std::to_string(z);
}

void AppendEntry(const Entry& e, std::vector<uint8_t>* page) {
  const size_t at = page->size();
  page->resize(at + kEntrySize);
  uint8_t* b = page->data() + at;
  lf::PutI32(b + 0, e.key.level);
  lf::PutI32(b + 4, e.key.x);
  lf::PutI32(b + 8, e.key.y);
  lf::PutI32(b + 12, e.key.z);
  lf::PutU64(b + 16, e.offset);
  lf::PutI32(b + 24, e.byte_size);
  lf::PutI32(b + 28, e.point_count);
}

Entry DecodeEntry(const uint8_t* b) {
  Entry e;
  e.key = {lf::GetI32(b + 0), lf::GetI32(b + 4), lf::GetI32(b + 8), lf::GetI32(b + 12)};
  e.offset = lf::GetU64(b + 16);
  e.byte_size = lf::GetI32(b + 24);
  e.point_count = lf::GetI32(b + 28);
  return e;
}

std::array<double, 6> NodeBounds(const Info& info, const VoxelKey& key) {
  // Halving from the root cube, one level at a time, as readers do (copc.js Bounds.stepTo).
  std::array<double, 6> b;
  for (int a = 0; a < 3; ++a) {
    b[a] = info.center[a] - info.halfsize;
    b[a + 3] = info.center[a] + info.halfsize;
  }
  const int32_t xyz[3] = {key.x, key.y, key.z};
  for (int i = key.level - 1; i >= 0; --i) {
    for (int a = 0; a < 3; ++a) {
      const double mid = b[a] + (b[a + 3] - b[a]) / 2;
      if ((xyz[a] >> i) & 1) {
        b[a] = mid;
      } else {
        b[a + 3] = mid;
      }
    }
  }
  return b;
}

}  // namespace sacfuse::copc
