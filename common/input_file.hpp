#pragma once
// Reading a user's input file (a scene, a config, a sweep) with the same rules everywhere: it
// must exist, be a regular file (not a FIFO, a device such as /dev/zero, or a folder: opening or
// reading those can block or never end) and be no larger than a limit; else an InputError
// "cannot open WHAT: why" naming the file, before anything is read.
#include <cstdint>
#include <string>

namespace rtsim {

/// Hand-written configuration (TOML config and sweep files): far more than any real one (the
/// largest in configs/ is a few KiB), and the length the fuzz targets run up to
/// (scripts/fuzz.sh), so no accepted file is longer than what was fuzzed.
inline constexpr std::uintmax_t kMaxConfigFileBytes = std::uintmax_t{1} << 20;

/// The whole file. `what`: "scene file", "config file", "sweep file".
std::string read_input_file(const std::string& path, const std::string& what,
                            std::uintmax_t max_bytes, const std::string& limit_name);

}  // namespace rtsim
