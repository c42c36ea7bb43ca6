#pragma once
// The level of a counted quantity (entries in a queue, busy intervals in progress) over time,
// from the times it went up and the times it went down. One walk serves both the statistics
// (Occupancy's time-weighted mean and maximum) and the traces (VCD and Perfetto depth and busy
// signals), so a trace can never tell another story than stats.json.
//
// At equal times the downs go first: a slot handed over at one instant is not counted twice, and
// back-to-back busy intervals do not show a level of 2 where one ends and the next begins.
// Used by the traces and statistics of every machine.
#include <algorithm>
#include <cstdint>
#include <vector>

namespace rtsim::modules {

/// One value change of a level signal: from `t` (sc_time ticks) on, the level is `level`.
struct LevelChange {
  std::uint64_t t = 0;
  long level = 0;
};

/// Calls step(t, delta) for every up (+1) and down (-1), in time order, downs first at equal
/// times. Both lists must be sorted.
template <class Step>
void walk_level_steps(const std::vector<std::uint64_t>& ups,
                      const std::vector<std::uint64_t>& downs, Step&& step) {
  std::size_t u = 0, d = 0;
  while (u < ups.size() || d < downs.size()) {
    if (d < downs.size() && (u == ups.size() || downs[d] <= ups[u]))
      step(downs[d++], -1);
    else
      step(ups[u++], +1);
  }
}

/// The value changes of the level that starts at 0: one change per distinct time at which the
/// level differs from the one before (the net of all steps at that time). Both lists sorted.
inline std::vector<LevelChange> level_changes(const std::vector<std::uint64_t>& ups,
                                              const std::vector<std::uint64_t>& downs) {
  std::vector<LevelChange> out;
  long level = 0;
  long last_written = 0;
  bool pending = false;
  std::uint64_t pending_t = 0;
  const auto flush = [&] {
    if (pending && level != last_written) {
      out.push_back({pending_t, level});
      last_written = level;
    }
    pending = false;
  };
  walk_level_steps(ups, downs, [&](std::uint64_t t, int delta) {
    if (pending && t != pending_t) flush();
    pending = true;
    pending_t = t;
    level += delta;
  });
  flush();
  return out;
}

}  // namespace rtsim::modules
