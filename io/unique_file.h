#pragma once
// A C stdio FILE owned by a std::unique_ptr, closed when it goes out of scope: for the readers and writers of io/
// that seek and read or write raw bytes. Private to io/.
#include <cstdio>
#include <memory>

namespace sacfuse {

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f != nullptr) std::fclose(f);
  }
};
using UniqueFile = std::unique_ptr<std::FILE, FileCloser>;

}  // namespace sacfuse
