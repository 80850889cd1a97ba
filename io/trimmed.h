#pragma once
// A line or field of a text input without the white space (spaces, tabs, CR, LF, ...) around it.
#include <cctype>
#include <string>

namespace sacfuse {

inline std::string Trimmed(const std::string& s) {
  size_t begin = 0, end = s.size();
  while (begin < end && std::isspace(static_cast<unsigned char>(s[begin]))) ++begin;
  while (end > begin && std::isspace(static_cast<unsigned char>(s[end - 1]))) --end;
  return s.substr(begin, end - begin);
}

}  // namespace sacfuse
