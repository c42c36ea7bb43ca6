#include "common/input_file.hpp"

#include <filesystem>
#include <fstream>

#include "common/input_error.hpp"

namespace rtsim {

std::string read_input_file(const std::string& path, const std::string& what,
                            std::uintmax_t max_bytes, const std::string& limit_name) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw InputError(path, 0, "cannot open " + what + ": no such file");
  if (!std::filesystem::is_regular_file(status))
    throw InputError(path, 0, "cannot open " + what + ": not a regular file");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path, 0, "cannot open " + what + ": " + ec.message());
  if (size > max_bytes)
    throw InputError(path, 0,
                     what + " is " + std::to_string(size) + " bytes, more than the limit of " +
                         std::to_string(max_bytes) + " (" + limit_name + ")");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open " + what + ": permission denied or unreadable");
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (in.bad()) throw InputError(path, 0, "cannot open " + what + ": read error");
  return text;
}

}  // namespace rtsim
