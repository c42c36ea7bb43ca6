#pragma once
// The one error type for bad input (scene files, config files, -p overrides, sweep files).
// The command catches it, prints what() and exits with status 2 before writing any output.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace rtsim {

class InputError : public std::runtime_error {
 public:
  /// `file` may be empty (e.g. a -p override); `line` 0 means "no line".
  InputError(std::string file, std::size_t line, const std::string& message)
      : std::runtime_error(format(file, line, message)),
        file_(std::move(file)),
        line_(line),
        message_(message) {}

  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }
  const std::string& message() const { return message_; }

 private:
  static std::string format(const std::string& file, std::size_t line, const std::string& msg) {
    std::string out;
    if (!file.empty()) {
      out += file;
      if (line > 0) {
        // Two appends, not `":" + std::to_string(line)`: GCC 12 -O2 reports a false
        // -Wrestrict on `literal + std::string&&` (GCC bug 105651), fatal under -Werror.
        out += ':';
        out += std::to_string(line);
      }
      out += ": ";
    }
    return out + msg;
  }
  std::string file_;
  std::size_t line_;
  std::string message_;
};

}  // namespace rtsim
