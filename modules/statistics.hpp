#pragma once
// Statistics a module owns (DESIGN.md "The three layers"; after gem5's stat groups and SST's
// registerStatistic): a module declares each figure it reports as a member, named once, and the
// member registers itself with the module's group when it is built:
//
//   class Host : public modules::Processor {        // a Processor is a StatGroup
//     modules::Counter jobs_issued_{*this, "jobs_issued", "jobs handed to the pipeline"};
//     ...  ++jobs_issued_;
//
// A group is named by its hierarchical (SystemC) name; an object that is not an sc_module (a
// link, a queue, a pipelined unit) is a group of its own under a name its owner gives it, or a
// child of its owner's group ("peripheral" -> "peripheral.pipeline"). Every group alive is in the
// StatDirectory (modules/stat_directory.hpp), which writes stats.json's `modules` tree and hands
// the traces their busy and depth signals: nobody copies a counter out by hand.
//
// The kinds: Counter (events), CounterArray (events by kind), Scalar (a figure), Peak (the largest
// level seen), Duration (time spent), Busy (a busy timeline: busy_s, utilization,
// utilization_windows, the busy signal), Level (a queue's time-weighted depth: queue.{capacity,
// mean_occupancy, max_occupancy}, the depth signal), Distribution (per-item latencies), Computed (a
// figure worked out at the end from the module's parameters) and LevelSignal (a trace signal only).
// Used by every machine's modules and the kit's (Processor, Link, TimedFifo, MessageQueue,
// PipelinedUnit, Memory, TokenRing).
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <systemc>
#include <utility>
#include <vector>

#include "modules/busy_timeline.hpp"
#include "modules/latency_recorder.hpp"
#include "modules/level_steps.hpp"
#include "modules/occupancy.hpp"
#include "modules/stat_unit.hpp"

namespace rtsim::modules {

/// The frame the statistics are taken over: means and windows over [begin, end].
struct StatWindow {
  sc_core::sc_time begin = sc_core::SC_ZERO_TIME;
  sc_core::sc_time end = sc_core::SC_ZERO_TIME;
};

/// A level signal for the traces: `kind` is its suffix ("busy", "depth", "holder").
struct TraceSignal {
  std::string kind;
  std::vector<LevelChange> changes;
};

/// What one group's statistics write, gathered before it becomes JSON (the order of stats.json
/// is fixed: busy_s, utilization, the values by name, queue, utilization_windows).
struct StatReport {
  bool busy_reported = false;
  sc_core::sc_time busy = sc_core::SC_ZERO_TIME;
  std::map<std::string, nlohmann::ordered_json> values;
  nlohmann::ordered_json queue;    ///< null unless a Level reported
  nlohmann::ordered_json windows;  ///< null unless a Busy recorded windows
  /// The unit of each key written, relative to the group ("bits", "queue.mean_occupancy").
  std::vector<std::pair<std::string, StatUnit>> units;
};

class Statistic;

/// A named set of statistics: a module, or an object a module owns. Registered in the
/// StatDirectory while it lives; neither copied nor moved (its statistics point at it).
class StatGroup {
 public:
  /// A group named `path` (an sc_module's name(): "pert0.shell").
  explicit StatGroup(std::string path);
  /// A child of `parent`'s group: "peripheral" + "pipeline" -> "peripheral.pipeline".
  StatGroup(const StatGroup& parent, std::string_view child);
  virtual ~StatGroup();
  StatGroup(const StatGroup&) = delete;
  StatGroup& operator=(const StatGroup&) = delete;

  const std::string& stat_path() const { return path_; }
  const std::vector<const Statistic*>& statistics() const { return statistics_; }

 private:
  friend class Statistic;
  std::string path_;
  std::vector<const Statistic*> statistics_;
};

/// One figure of a group, named relative to it ("jobs_issued"; a time ends in "_s"), in its unit
/// (modules/stat_unit.hpp: a count unless it says otherwise).
class Statistic {
 public:
  Statistic(StatGroup& group, std::string name, std::string description,
            StatUnit unit = StatUnit::count);
  virtual ~Statistic() = default;
  Statistic(const Statistic&) = delete;
  Statistic& operator=(const Statistic&) = delete;

  const std::string& name() const { return label_->name; }
  const std::string& description() const { return label_->description; }
  StatUnit unit() const { return label_->unit; }
  /// Adds itself to its group's report over `window`.
  virtual void report(StatReport& out, const StatWindow& window) const = 0;
  /// Its trace signals (Busy, Level, LevelSignal); none by default.
  virtual void signals(std::vector<TraceSignal>& /*out*/) const {}

 protected:
  /// Records in `out` that key `key` (relative to the group) is in this statistic's unit.
  void declare_unit(StatReport& out, std::string key) const {
    out.units.emplace_back(std::move(key), label_->unit);
  }

 private:
  /// Its name, description and unit, kept once for every statistic that has them (a thousand
  /// processors' counters share one): a counter is its value and a pointer, so a module's
  /// counters lie a few to a cache line, where two strings each spread them over kilobytes that
  /// every message handled touched.
  struct Label {
    std::string name;
    std::string description;
    StatUnit unit;
  };
  static const Label& intern(std::string name, std::string description, StatUnit unit);
  const Label* label_;
};

/// A count of events.
class Counter final : public Statistic {
 public:
  using Statistic::Statistic;
  Counter& operator++() {
    ++value_;
    return *this;
  }
  Counter& operator+=(std::uint64_t n) {
    value_ += n;
    return *this;
  }
  std::uint64_t value() const { return value_; }
  void report(StatReport& out, const StatWindow& window) const override;

 private:
  std::uint64_t value_ = 0;
};

/// Counts by kind, each written as `prefix + kind` ("received_" + "vision" -> received_vision):
/// a processor's messages by type, a ring's bytes by traffic class.
class CounterArray final : public Statistic {
 public:
  CounterArray(StatGroup& group, std::string prefix, std::vector<std::string> kinds,
               std::string description, StatUnit unit = StatUnit::count)
      : Statistic(group, std::move(prefix), std::move(description), unit),
        more_(kinds.size() > kInline ? kinds.size() : 0, 0),
        values_(kinds.size() > kInline ? more_.data() : inline_.data()),
        kinds_(std::move(kinds)) {}
  void add(std::size_t kind, std::uint64_t n = 1) { values_[kind] += n; }
  std::uint64_t operator[](std::size_t kind) const { return values_[kind]; }
  std::size_t size() const { return kinds_.size(); }
  void report(StatReport& out, const StatWindow& window) const override;

 private:
  /// A few kinds' counts are kept in the object itself, beside the pointer add() reads (not in
  /// a block of their own elsewhere: one cache line less for every message counted).
  static constexpr std::size_t kInline = 8;
  std::array<std::uint64_t, kInline> inline_{};
  std::vector<std::uint64_t> more_;  ///< the counts when there are more kinds
  std::uint64_t* values_;
  std::vector<std::string> kinds_;
};

/// The largest value of a level seen (rays in flight, registers in use).
class Peak final : public Statistic {
 public:
  using Statistic::Statistic;
  void note(std::uint64_t level) {
    if (level > value_) value_ = level;
  }
  std::uint64_t value() const { return value_; }
  void report(StatReport& out, const StatWindow& window) const override;

 private:
  std::uint64_t value_ = 0;
};

/// A figure that is not a count (a ratio, a size in words), in the unit it is declared with.
class Scalar final : public Statistic {
 public:
  Scalar(StatGroup& group, std::string name, std::string description, StatUnit unit)
      : Statistic(group, std::move(name), std::move(description), unit) {}
  Scalar& operator=(double v) {
    value_ = v;
    return *this;
  }
  Scalar& operator+=(double v) {
    value_ += v;
    return *this;
  }
  double value() const { return value_; }
  void report(StatReport& out, const StatWindow& window) const override;

 private:
  double value_ = 0.0;
};

/// Time spent (waiting, blocked); written in seconds.
class Duration final : public Statistic {
 public:
  Duration(StatGroup& group, std::string name, std::string description)
      : Statistic(group, std::move(name), std::move(description), StatUnit::seconds) {}
  Duration& operator+=(const sc_core::sc_time& t) {
    value_ += t;
    return *this;
  }
  const sc_core::sc_time& value() const { return value_; }
  void report(StatReport& out, const StatWindow& window) const override;

 private:
  sc_core::sc_time value_ = sc_core::SC_ZERO_TIME;
};

/// When the group was busy: busy_s (the total recorded), utilization (busy_s over the frame),
/// utilization_windows and the traces' busy signal. A group has at most one.
class Busy final : public Statistic {
 public:
  Busy(StatGroup& group, std::string description = "time busy (its utilisation)")
      : Statistic(group, "busy_s", std::move(description), StatUnit::seconds) {}
  /// Busy over [start, start + duration).
  void record(const sc_core::sc_time& start, const sc_core::sc_time& duration) {
    timeline_.add(start, duration);
    total_ += duration;
  }
  const sc_core::sc_time& total() const { return total_; }
  const BusyTimeline& timeline() const { return timeline_; }
  /// With its utilisation windows (most of a large machine's report: thousands of timelines,
  /// reported on two threads, StatDirectory::to_json).
  void report(StatReport& out, const StatWindow& window) const override;
  void signals(std::vector<TraceSignal>& out) const override;

 private:
  // What record() touches first, together: the total, then the timeline's head.
  sc_core::sc_time total_ = sc_core::SC_ZERO_TIME;
  BusyTimeline timeline_;
};

/// A queue's depth over time: queue.{capacity, mean_occupancy, max_occupancy} (time-weighted
/// over the frame) and the traces' depth signal. Capacity kUnbounded is written as null.
class Level final : public Statistic {
 public:
  static constexpr std::size_t kUnbounded = std::numeric_limits<std::size_t>::max();
  Level(StatGroup& group, std::size_t capacity,
        std::string description = "entries waiting (time-weighted)")
      : Statistic(group, "queue", std::move(description)), capacity_(capacity) {}
  void put(const sc_core::sc_time& t) { occupancy_.put(t); }
  void got(const sc_core::sc_time& t) { occupancy_.got(t); }
  std::size_t capacity() const { return capacity_; }
  const Occupancy& occupancy() const { return occupancy_; }
  void report(StatReport& out, const StatWindow& window) const override;
  void signals(std::vector<TraceSignal>& out) const override;

 private:
  std::size_t capacity_;
  Occupancy occupancy_;
};

/// Per-item times (a job's latency): {count, mean, p50, p99, max, histogram}; seconds but the
/// counts.
class Distribution final : public Statistic {
 public:
  Distribution(StatGroup& group, std::string name, std::string description)
      : Statistic(group, std::move(name), std::move(description), StatUnit::seconds) {}
  void add(const sc_core::sc_time& t) { recorder_.add(t); }
  const LatencyRecorder& recorder() const { return recorder_; }
  void report(StatReport& out, const StatWindow& window) const override;

 private:
  LatencyRecorder recorder_;
};

/// A figure worked out when the statistics are written (from the module's parameters or
/// other figures), in `unit` (each number of it, when it is an array or an object): `value` is
/// called then.
class Computed final : public Statistic {
 public:
  Computed(StatGroup& group, std::string name, StatUnit unit, std::string description,
           std::function<nlohmann::ordered_json()> value)
      : Statistic(group, std::move(name), std::move(description), unit), value_(std::move(value)) {}
  void report(StatReport& out, const StatWindow& window) const override;

 private:
  std::function<nlohmann::ordered_json()> value_;
};

/// A level over time for the traces only (a token ring's transmitting node): NAME.kind.
class LevelSignal final : public Statistic {
 public:
  LevelSignal(StatGroup& group, std::string kind, std::string description)
      : Statistic(group, std::move(kind), std::move(description)) {}
  void change(std::uint64_t t, long level) { changes_.push_back({t, level}); }
  std::vector<LevelChange>& changes() { return changes_; }
  const std::vector<LevelChange>& changes() const { return changes_; }
  void report(StatReport& /*out*/, const StatWindow& /*window*/) const override {}
  void signals(std::vector<TraceSignal>& out) const override;

 private:
  std::vector<LevelChange> changes_;
};

}  // namespace rtsim::modules
