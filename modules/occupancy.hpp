#pragma once
// Time-weighted occupancy of a queue from the timestamps of its puts and gets. The two lists
// are sorted and merged at the end: they are usually in time order already, but a producer may
// stamp a put earlier than its previous one (Ullner's peripheral sends the answer of a ray with
// no intersections before the previous ray's leaves the pipe), and the threads may record them
// out of global time order when temporally decoupled. The walk over them (downs first at equal
// times) is modules/level_steps.hpp, shared with the traces' depth signals.
// Used by every queue (TimedFifo) of every machine.
#include <algorithm>
#include <cstdint>
#include <systemc>
#include <vector>

#include "modules/level_steps.hpp"

namespace rtsim::modules {

class Occupancy {
 public:
  void put(const sc_core::sc_time& t) { puts_.push_back(t.value()); }
  void got(const sc_core::sc_time& t) { gets_.push_back(t.value()); }

  struct Summary {
    double mean = 0.0;  ///< time-weighted over [0, end]
    int max = 0;
  };

  /// Occupancy over [begin, end].
  Summary summarize(const sc_core::sc_time& begin, const sc_core::sc_time& end) const {
    Summary s;
    const std::uint64_t b = begin.value();
    const std::uint64_t e = end.value();
    if (e <= b) return s;
    long level = 0;
    std::uint64_t last = b;
    long double area = 0;
    std::vector<std::uint64_t> put_copy, get_copy;
    const std::vector<std::uint64_t>& puts = in_order(puts_, put_copy);
    const std::vector<std::uint64_t>& gets = in_order(gets_, get_copy);
    walk_level_steps(puts, gets, [&](std::uint64_t t, int delta) {
      t = std::clamp(t, b, e);
      area += static_cast<long double>(level) * static_cast<long double>(t - last);
      last = t;
      level += delta;
      s.max = std::max(s.max, static_cast<int>(level));
    });
    area += static_cast<long double>(level) * static_cast<long double>(e - last);
    s.mean = static_cast<double>(area / static_cast<long double>(e - b));
    return s;
  }

  /// The depth over time, for traces: the same steps summarize() integrates.
  std::vector<LevelChange> depth_changes() const {
    std::vector<std::uint64_t> put_copy, get_copy;
    return level_changes(in_order(puts_, put_copy), in_order(gets_, get_copy));
  }

 private:
  /// `v` itself when it is in time order (the usual case: a queue of millions of messages is
  /// not copied), else `copy` filled with it sorted.
  static const std::vector<std::uint64_t>& in_order(const std::vector<std::uint64_t>& v,
                                                    std::vector<std::uint64_t>& copy) {
    if (std::is_sorted(v.begin(), v.end())) return v;
    copy = v;
    std::sort(copy.begin(), copy.end());
    return copy;
  }

  std::vector<std::uint64_t> puts_;
  std::vector<std::uint64_t> gets_;
};

}  // namespace rtsim::modules
