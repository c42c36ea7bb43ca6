#pragma once
// When a module was busy, coarsely: busy intervals are summed into fixed-width time bins whose
// width doubles (pairs of bins merge) whenever the recorded span outgrows kMaxBins, so memory
// stays bounded however long the frame and however many intervals. At the end the bins are
// resampled into N equal windows of the frame: the busy fraction per window, for utilisation
// over time (stats.json `modules.NAME.utilization_windows`, analysis/utilisation_timeline.py).
//
// Exact while a window boundary falls on a bin boundary; otherwise a bin cut by a window
// boundary is shared out in proportion to the overlap (as if its busy time were spread evenly
// over the part of the bin between the first start and the last end recorded), an error of at
// most one bin width per boundary. The span is at least kMaxBins / 2 bins wide once it has
// grown, so with 100 windows that is < 1.3% of a window.
//
// While a trace is written (a KeepIntervals object is alive when the timeline is made) it also
// keeps every interval as recorded, so the traces' busy signals are these very intervals, the
// ones busy_s and the windows are summed from (16 bytes an interval; an interval that starts
// where the previous one ended extends it). Timelines are members deep inside the modules, and a
// run has one trace setting: a scoped switch reaches them without threading a flag through
// every constructor.
//
// A timeline starts sparse: its first kSparseIntervals intervals are kept as they are, and
// windows and totals come from them exactly. Only a timeline that records more turns to bins,
// sized then for the span so far. Most of a large machine's modules (a link used now and then, a
// processor of one of 64 PERTs) never need bins, and a timeline that does skips the doublings
// from one tick up to its span (each a pass over the bins; they were a fifth of a 64-PERT run).
// The bins are 32-bit counts of ticks while every bin fits (half the memory: a binned timeline
// reserves 64 KiB, not 128 KiB, and a large machine has hundreds; on this virtual machine each
// megabyte touched for the first time costs about a millisecond). A bin that would outgrow 32
// bits (a bin wider than 2^32 ticks fully busy, or overlapping intervals) turns all of them to
// 64 bits first, so the sums are the same integers either way (tests/systemc_busy_timeline_test.cpp
// holds the two to each other on random intervals).
// Used by every machine (each busy module: processors, pipelines, buses, links).
#include <cstdint>
#include <systemc>
#include <vector>

#include "modules/level_steps.hpp"

namespace rtsim::modules {

/// Busy fraction per window of a frame.
struct UtilizationWindows {
  double begin_s = 0.0;          ///< absolute simulated time of the first window's start
  double window_s = 0.0;         ///< width of every window
  std::vector<double> values{};  ///< busy time / window_s, in [0, 1]; empty: not recorded
};

class BusyTimeline {
 public:
  /// Bins kept at most; 16384 x 4 bytes = 64 KiB a module at most (128 KiB once widened).
  static constexpr std::size_t kMaxBins = 16384;
  /// Intervals kept exactly before the timeline turns to bins (16 KiB).
  static constexpr std::size_t kSparseIntervals = 1024;

  /// While one is alive, timelines made keep their intervals (for traces). Not nestable
  /// across threads; SystemC runs one simulation per process anyway.
  class KeepIntervals {
   public:
    KeepIntervals() { ++keeping_; }
    ~KeepIntervals() { --keeping_; }
    KeepIntervals(const KeepIntervals&) = delete;
    KeepIntervals& operator=(const KeepIntervals&) = delete;
  };

  /// While one is alive, timelines made keep 64-bit bins from the start (tests compare them
  /// with the 32-bit bins that widen when they must).
  class WideBins {
   public:
    WideBins() { ++wide_from_start_; }
    ~WideBins() { --wide_from_start_; }
    WideBins(const WideBins&) = delete;
    WideBins& operator=(const WideBins&) = delete;
  };

  BusyTimeline() : keep_(keeping_ > 0), wide_(wide_from_start_ > 0) {}

  /// The module was busy over [start, start + duration). Intervals may come in any order;
  /// overlapping intervals add (a pipelined unit records its issue slots, which never overlap).
  void add(const sc_core::sc_time& start, const sc_core::sc_time& duration);

  /// Busy fraction in `n` equal windows of [begin, end]. Empty if n == 0 or end <= begin.
  UtilizationWindows windows(const sc_core::sc_time& begin, const sc_core::sc_time& end,
                             std::size_t n) const;

  /// Total busy time recorded (exact: the bins hold integer ticks).
  sc_core::sc_time total() const;
  std::uint64_t bin_width_ticks() const {
    settle();
    return std::uint64_t{1} << shift_;
  }
  std::size_t bins() const {
    settle();
    return bin_count();
  }
  /// Whether the bins are 64-bit (one outgrew 32 bits, or made while a WideBins was alive).
  bool wide_bins() const { return wide_; }

  /// Whether the intervals are kept (made while a KeepIntervals was alive).
  bool keeps_intervals() const { return keep_; }
  /// The number of intervals in progress over time (0 and 1 unless intervals overlap), from
  /// the kept intervals; empty if they were not kept.
  std::vector<LevelChange> level_changes() const;

 private:
  struct Interval {
    std::uint64_t start;
    std::uint64_t end;
  };
  inline static int keeping_ = 0;
  inline static int wide_from_start_ = 0;
  std::size_t bin_count() const { return wide_ ? wide_bins_.size() : bins_.size(); }
  /// Calls f with the bins in use (either vector).
  template <class F>
  decltype(auto) with_bins(F&& f) {
    return wide_ ? f(wide_bins_) : f(bins_);
  }
  template <class F>
  decltype(auto) with_bins(F&& f) const {
    return wide_ ? f(wide_bins_) : f(bins_);
  }
  /// The bins to 64 bits, values kept.
  void widen();
  void merge_pairs();
  /// The bins take the pending interval, if any.
  void settle_pending();
  void settle() const;
  void add_to_bins(std::uint64_t s, std::uint64_t e);
  void to_bins();
  /// ceil(ticks / the bin width): the bins `ticks` of time take.
  std::uint64_t bins_for(std::uint64_t ticks) const {
    return (ticks >> shift_) + ((ticks & ((std::uint64_t{1} << shift_) - 1)) != 0 ? 1 : 0);
  }
  // What add() reads first, together (a large machine's every busy interval comes here).
  bool keep_ = false;
  bool recorded_ = false;  ///< anything added yet
  bool binned_ = false;    ///< bins in use (else sparse_ and open_ hold everything)
  bool wide_ = false;      ///< the bins are wide_bins_ (else bins_)
  /// Ticks per bin: 1 << shift_. A power of two (merge_pairs doubles it), so the hot path of
  /// every busy interval shifts instead of dividing.
  unsigned shift_ = 0;
  std::uint64_t origin_ = 0;  ///< ticks (sc_time values) at the start of bin 0
  std::uint64_t first_ = 0;   ///< earliest start recorded
  std::uint64_t last_ = 0;    ///< latest end recorded
  /// Sparse: the interval recorded last (while recorded_), kept here rather than at the end of
  /// sparse_ so that extending it, the common case, reads no line but this object's.
  Interval open_{0, 0};
  /// Binned: the interval recorded last, not yet in the bins (empty: start == end). Most of a
  /// processor's intervals start where the one before ended; they extend it here instead of
  /// each visiting the bins.
  Interval pending_{0, 0};
  std::vector<std::uint32_t> bins_;       ///< busy ticks a bin, while each fits in 32 bits
  std::vector<std::uint64_t> wide_bins_;  ///< the same, once one has not
  std::vector<Interval> sparse_;          ///< the intervals before open_, until it turns to bins
  std::vector<Interval> intervals_;
};

}  // namespace rtsim::modules
