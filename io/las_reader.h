#pragma once
// Streaming reader for uncompressed LAS 1.0-1.4, point formats 0-10 (LAZ is rejected with a clear message).
// Validates the header against the file (signature, header size, offsets, record length vs format,
// offset + count x length <= file size) and throws sacfuse::InputError naming the file on any inconsistency.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/las_types.h"

namespace sacfuse {

class LasReader {
 public:
  explicit LasReader(const std::string& path);
  ~LasReader();
  LasReader(const LasReader&) = delete;
  LasReader& operator=(const LasReader&) = delete;

  const LasHeader& header() const;
  // Reads up to max_count further points into out (resized); returns how many were read (0 at the end).
  size_t Read(std::vector<LasPoint>* out, size_t max_count);
  // Back to the first point.
  void Rewind();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Convenience for small files and tests: every point of a file.
std::vector<LasPoint> ReadAllLasPoints(const std::string& path, LasHeader* header = nullptr);

}  // namespace sacfuse
