#pragma once
// Time-weighted occupancy of a queue, computed after the run from the timestamps of its +1/-1
// changes (threads may record them out of time order when temporally decoupled).
#include <algorithm>
#include <cstdint>
#include <systemc>
#include <vector>

namespace rtsim::modules {

class Occupancy {
 public:
  void record(const sc_core::sc_time& t, int delta) {
    changes_.push_back({t.value(), delta});
  }

  struct Summary {
    double mean = 0.0;  ///< time-weighted over [0, end]
    int max = 0;
  };

  /// Occupancy over [0, end].
  Summary summarize(const sc_core::sc_time& end) const {
    std::vector<Change> c = changes_;
    // Same time: removals first, so a slot handed over at one instant is not counted twice.
    std::stable_sort(c.begin(), c.end(), [](const Change& a, const Change& b) {
      return a.t != b.t ? a.t < b.t : a.delta < b.delta;
    });
    Summary s;
    const std::uint64_t e = end.value();
    if (e == 0) return s;
    long level = 0;
    std::uint64_t last = 0;
    long double area = 0;
    for (const Change& ch : c) {
      const std::uint64_t t = std::min(ch.t, e);
      area += static_cast<long double>(level) * static_cast<long double>(t - last);
      last = t;
      level += ch.delta;
      s.max = std::max(s.max, static_cast<int>(level));
    }
    area += static_cast<long double>(level) * static_cast<long double>(e - last);
    s.mean = static_cast<double>(area / static_cast<long double>(e));
    return s;
  }

 private:
  struct Change {
    std::uint64_t t;
    int delta;
  };
  std::vector<Change> changes_;
};

}  // namespace rtsim::modules
