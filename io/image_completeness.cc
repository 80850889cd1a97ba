#include "io/image_completeness.h"

namespace sacfuse {
namespace {

bool StartsWith(const std::string& bytes, const char* magic, size_t n) { return bytes.compare(0, n, magic, n) == 0; }

}  // namespace

std::string IncompleteImageProblem(const std::string& bytes) {
  if (StartsWith(bytes, "\xFF\xD8\xFF", 3)) {
    // Entropy-coded data stuffs every 0xFF with 0x00, so the last start-of-scan (FF DA) is a real marker and a
    // complete file has its end-of-image marker (FF D9) after it (trailing bytes after the EOI are tolerated).
    const size_t sos = bytes.rfind("\xFF\xDA", std::string::npos, 2);
    if (sos == std::string::npos) return "JPEG file without a start of scan (SOS) marker: no image data";
    if (bytes.find("\xFF\xD9", sos + 2, 2) == std::string::npos) {
      return "JPEG file without an end of image marker (EOI) after its last scan: truncated (libjpeg: \"Premature "
             "end of JPEG file\"); the missing part of the image decodes as grey";
    }
    return "";
  }
  if (StartsWith(bytes, "\x89PNG\r\n\x1a\n", 8)) {
    // The IEND chunk: length 0, type "IEND", CRC AE 42 60 82.
    if (bytes.find(std::string("\0\0\0\0IEND\xAE\x42\x60\x82", 12)) == std::string::npos) {
      return "PNG file without its IEND chunk: truncated; the missing part of the image decodes as black or fails";
    }
  }
  return "";
}

}  // namespace sacfuse
