#pragma once
// The one exception type of sacfuse. Messages carry their context (file, view, tile, config key) so that a
// user reading only the last log line knows what to fix.
#include <stdexcept>
#include <string>

namespace sacfuse {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Bad or unreadable input data (corrupt, truncated or mismatched files).
class InputError : public Error {
 public:
  InputError(const std::string& file, const std::string& message)
      : Error(file + ": " + message), file_(file), message_(message) {}
  const std::string& file() const { return file_; }
  // What is wrong, without the file (for a caller that adds context and throws again, or warns).
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  std::string message_;
};

// Invalid configuration or command-line option.
class ConfigError : public Error {
 public:
  using Error::Error;
};

}  // namespace sacfuse
