#pragma once
// A stats.json read back from disk (`rtsim diff`, a resumed sweep's points): the file may be
// anyone's, so it is checked before it is walked. JSON nests without bound and the walkers
// (stats_leaves) recurse, so depth is bounded before parsing; the fields every reader uses must
// be there with their types, or a reader's `value()` throws a raw type error.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace rtsim::sweep {

/// The largest stats.json read back: a 32x32 array's with utilisation windows is a few MB.
inline constexpr std::uintmax_t kMaxStatsFileBytes = std::uintmax_t{256} << 20;

/// Most levels of nesting a stats.json may have; rtsim writes at most 6
/// (modules.pert0.shell.queue.depth.max, say).
inline constexpr std::size_t kMaxStatsDepth = 64;

/// Why `text` is not a stats.json rtsim could have written, or "" when it is one: JSON nested at
/// most kMaxStatsDepth deep, an object whose `command` is "run" or "render", whose `machine` and
/// `scene` are strings and whose `width` and `height` are whole numbers from 1.
std::string stats_json_problem(std::string_view text);

/// The parsed stats.json; InputError(origin, 0, "not a stats.json: why") otherwise.
nlohmann::ordered_json read_stats_json(std::string_view text, const std::string& origin);

}  // namespace rtsim::sweep
