#include "io/file_checksum.h"

#include <cstdio>
#include <memory>
#include <vector>

#include "core/error.h"

namespace sacfuse {
namespace {
constexpr uint64_t kFnvOffset = 1469598103934665603ull;
constexpr uint64_t kFnvPrime = 1099511628211ull;

uint64_t Update(uint64_t h, const unsigned char* data, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    h ^= data[i];
    h *= kFnvPrime;
  }
  return h;
}
}  // namespace

uint64_t Fnv1a64(const std::string& bytes) {
  return Update(kFnvOffset, reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size());
}

uint64_t Fnv1a64File(const std::string& path) {
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw InputError(path, "cannot open for checksumming");
  std::vector<unsigned char> buffer(1 << 20);
  uint64_t h = kFnvOffset;
  size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), file.get())) > 0) h = Update(h, buffer.data(), n);
  if (std::ferror(file.get())) throw InputError(path, "read error while checksumming");
  return h;
}

std::string HexDigest(uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(value));
  return text;
}

}  // namespace sacfuse
