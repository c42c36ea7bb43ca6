#pragma once
// The points of a sweep: the cartesian product of its axes (the last axis varies fastest), each
// turned into the arguments of one `rtsim run`.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "platform/sweep/sweep_file.hpp"

namespace rtsim::sweep {

/// A name (run option or parameter) and its value at one point.
struct Setting {
  std::string name{};
  Value value{};
  bool swept = false;         ///< from an axis (a column of the results table), not fixed
  std::size_t name_line = 0;  ///< where the name is given (for an unknown name)
};

struct Point {
  std::size_t index = 0;  ///< position in the product: the row of the results table
  std::string key{};      ///< its folder under points/: the index, zero-padded ("0007")
  /// Every run option and parameter: the fixed ones in file order, then the swept ones in axis
  /// order.
  std::vector<Setting> settings{};
  /// Arguments of `rtsim run` after the program name, without --out:
  /// run --machine M --scene S [--width W] [--height H] -q [--config F]... [-p NAME=VALUE]...
  std::vector<std::string> args{};
  /// The point whose image files this one's folder gets (share_images, image_sharing.hpp): it
  /// runs timing-only (`--image none`). Empty: it renders its own, or writes none.
  std::optional<std::size_t> image_from{};

  /// The setting called `name`, or null.
  const Setting* find(std::string_view name) const;
  const std::string& machine() const;  ///< as written in the sweep file
  const std::string& scene() const;    ///< as written (relative paths unresolved)
  /// The swept settings as NAME=VALUE, in axis order, joined by `separator` ("" for none).
  std::string swept_text(std::string_view separator) const;
  /// "rtsim run ..." with arguments shell-quoted where needed.
  std::string command_line() const;
  /// FNV-1a 64-bit hash of command_line(), 16 hex digits: the point's identity for resuming.
  std::string hash() const;
};

/// Every point, in product order (index 0, 1, ...).
std::vector<Point> expand_points(const SweepFile& file);

/// The --scene argument for a scene as written: builtin:NAME unchanged, a relative file path
/// resolved against the sweep file's folder.
std::string scene_argument(const SweepFile& file, const std::string& scene);

/// FNV-1a, 64 bits, as 16 lower-case hex digits.
std::string fnv1a64_hex(std::string_view text);

}  // namespace rtsim::sweep
