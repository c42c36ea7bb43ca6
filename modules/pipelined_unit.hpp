#pragma once
// A pipelined arithmetic unit (Ullner's intersection pipeline, an inner-product unit): items
// enter one per issue interval and leave `stages` stage times later. Time advances by
// arithmetic, never by one event per item (DESIGN.md "Timing rules"). It is the statistics group
// of its name: busy one issue interval per item, the items issued (named by its owner:
// "intersections") and its stage count.
// Used by ullner-peripheral (the intersection pipeline, the lighting unit); the ray-tracing
// pipeline and Wang's Bezier pipeline next.
#include <algorithm>
#include <cstdint>
#include <string>
#include <systemc>

#include "modules/sim_time.hpp"
#include "modules/statistics.hpp"

namespace rtsim::modules {

class PipelinedUnit : public StatGroup {
 public:
  /// `name`: its statistics group ("peripheral.pipeline"); `interval`: time between successive
  /// issues (also the stage time); `stages`: depth; `items`: what it counts as issued
  /// ("intersections", "inner_products").
  PipelinedUnit(std::string name, sc_core::sc_time interval, unsigned stages,
                std::string items = "issued")
      : StatGroup(std::move(name)),
        interval_(interval),
        stages_(stages),
        issued_(*this, std::move(items), "items issued") {}

  struct Batch {
    sc_core::sc_time first_issue;  ///< when the first item entered
    sc_core::sc_time next_free;    ///< when the unit can accept the next item
    sc_core::sc_time done;         ///< when the last item's result leaves the pipe
  };

  /// Issue `n` items back to back, the first no earlier than `earliest`. An empty batch still
  /// costs nothing but reports `done` = the time it would have started.
  Batch issue(std::uint64_t n, const sc_core::sc_time& earliest) {
    Batch b;
    b.first_issue = std::max(earliest, next_free_);
    if (n == 0) {
      b.next_free = b.first_issue;
      b.done = b.first_issue;
      return b;
    }
    b.next_free = b.first_issue + times(interval_, n);
    b.done = b.next_free - interval_ + latency();
    next_free_ = b.next_free;
    issued_ += n;
    busy_.record(b.first_issue, b.next_free - b.first_issue);
    return b;
  }

  /// Time from an item's issue to its result: stages x stage time.
  sc_core::sc_time latency() const { return times(interval_, stages_); }
  sc_core::sc_time interval() const { return interval_; }
  unsigned stages() const { return stages_; }
  std::uint64_t issued() const { return issued_.value(); }
  /// Busy time: one issue interval per item.
  sc_core::sc_time busy() const { return busy_.total(); }
  /// When it was busy: its issue slots, batch by batch.
  const BusyTimeline& timeline() const { return busy_.timeline(); }

 private:
  sc_core::sc_time interval_ = sc_core::SC_ZERO_TIME;
  unsigned stages_ = 1;
  sc_core::sc_time next_free_ = sc_core::SC_ZERO_TIME;
  Busy busy_{*this, "issue slots used: one interval an item (its utilisation)"};
  Counter issued_;
  Computed stage_count_{*this, "stages", StatUnit::count, "its depth in stages",
                        [this] { return stages_; }};
};

}  // namespace rtsim::modules
