#pragma once
// Whether an encoded JPEG or PNG file ends the way its format says it must. OpenCV decodes a truncated JPEG or PNG
// anyway (the missing rows come out grey) and libjpeg/libpng only print an unattributed "Premature end of JPEG
// file" on stderr; sacfuse checks the bytes itself so the warning names the file and reaches the log.
#include <string>

namespace sacfuse {

// "" when `bytes` is complete or not a JPEG/PNG; otherwise what is missing, e.g. "JPEG file without an end of
// image marker (EOI) after its last scan: truncated".
std::string IncompleteImageProblem(const std::string& bytes);

}  // namespace sacfuse
