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

uint64_t Fnv1a64FileEdges(const std::string& path, uint64_t size, size_t edge_bytes) {
  unsigned char size_bytes[8];
  for (int i = 0; i < 8; ++i) size_bytes[i] = static_cast<unsigned char>(size >> (8 * i));
  uint64_t h = Update(kFnvOffset, size_bytes, sizeof(size_bytes));
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw InputError(path, "cannot open for fingerprinting");
  std::vector<unsigned char> buffer(edge_bytes);
  const auto read_at = [&](uint64_t offset, size_t n) {
    if (std::fseek(file.get(), static_cast<long>(offset), SEEK_SET) != 0 ||
        std::fread(buffer.data(), 1, n, file.get()) != n) {
      throw InputError(path, "read error while fingerprinting (file shorter than " + std::to_string(size) +
                                 " bytes?)");
    }
    h = Update(h, buffer.data(), n);
  };
  if (size <= 2 * static_cast<uint64_t>(edge_bytes)) {
    buffer.resize(static_cast<size_t>(size));
    if (size > 0) read_at(0, static_cast<size_t>(size));
  } else {
    read_at(0, edge_bytes);
    read_at(size - edge_bytes, edge_bytes);
  }
  return h;
}

std::string HexDigest(uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(value));
  return text;
}

}  // namespace sacfuse
