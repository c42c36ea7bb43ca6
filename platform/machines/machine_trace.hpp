#pragma once
// The traces of one run: Perfetto (Chrome JSON) and VCD, either or both or neither.
//
// Two kinds of content, both named by the module names of stats.json:
//  * transactions: Perfetto slices a module emits as it works (slice(): a ray in the pipeline, a
//    packet on a bus), streamed to the file during the simulation;
//  * signals: each module's busy level and each queue's depth, written by finish() after the
//    simulation from the very objects stats.json was summarised from (the Busy and Level
//    statistics of the StatDirectory's groups): VCD variables NAME.busy / NAME.depth, and Perfetto
//    counters of the same names. Their time-weighted means over the frame are stats.json's
//    utilisation and mean occupancy (tests/trace_agreement_test.cpp).
//
// Every event is written unless the run narrows the traces (RunOptions::trace_filter: a window of
// simulated time, module name patterns) or caps them (RunOptions::trace_max_events, per file).
// What a cap dropped is counted in the files, in the `trace` object finish() returns for
// stats.json, and printed by `rtsim run`.
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <systemc>
#include <unordered_set>

#include "modules/busy_timeline.hpp"
#include "modules/slice_sink.hpp"
#include "modules/statistics.hpp"
#include "modules/trace/perfetto_trace.hpp"
#include "modules/trace/trace_filter.hpp"
#include "modules/trace/vcd_trace.hpp"
#include "platform/machine.hpp"

namespace rtsim::platform {

class MachineTrace final : public modules::SliceSink {
 public:
  /// Opens the traces RunOptions asks for. Make it before the modules: while it lives, their
  /// busy timelines keep the intervals the busy signals are drawn from.
  explicit MachineTrace(const RunOptions& opts);
  /// A trace that was not finished (the run failed) leaves no file.
  ~MachineTrace() override;
  MachineTrace(const MachineTrace&) = delete;
  MachineTrace& operator=(const MachineTrace&) = delete;

  bool on() const { return perfetto_ != nullptr || vcd_ != nullptr; }
  bool perfetto_on() const { return perfetto_ != nullptr; }

  /// A Perfetto slice on the track of `module` (a stats.json module name; tracks are created on
  /// first use), unless the filter leaves it out.
  void slice(std::string_view module, std::string_view name, const sc_core::sc_time& start,
             const sc_core::sc_time& duration,
             std::initializer_list<modules::PerfettoTrace::Arg> args = {}) override {
    if (perfetto_ && keeps(module, start, duration))
      perfetto_->slice(perfetto_->track(module), name, start, duration, args);
  }

  void flow(std::string_view module, std::string_view name, std::uint64_t id,
            modules::PerfettoTrace::FlowPhase phase, const sc_core::sc_time& t) override {
    if (perfetto_ && keeps(module, t, sc_core::SC_ZERO_TIME))
      perfetto_->flow(perfetto_->track(module), name, id, phase, t);
  }
  /// A step of a ray's (or job's) flow: the first step of `id` under `flow` starts it.
  void hop(std::string_view module, std::string_view flow, std::uint64_t id,
           const sc_core::sc_time& t) override;
  bool records() const override { return perfetto_ != nullptr; }

  /// After the simulation: writes the busy and depth signals of every statistics group alive
  /// that the filter keeps, closes the files and returns stats.json's `trace` object (null when
  /// no trace was asked for); `window` is the frame the statistics cover. Call once.
  nlohmann::ordered_json finish(const modules::StatWindow& window);
  /// The units of finish()'s keys (modules/stat_unit.hpp; stats.json `trace`).
  static modules::UnitSchema units();

 private:
  bool keeps(std::string_view module, const sc_core::sc_time& start,
             const sc_core::sc_time& duration);

  modules::TraceFilter filter_;
  std::size_t max_events_ = 0;
  std::optional<modules::BusyTimeline::KeepIntervals> keep_intervals_;
  std::unique_ptr<modules::PerfettoTrace> perfetto_;
  std::unique_ptr<modules::VcdTrace> vcd_;
  std::map<std::string, bool, std::less<>> module_kept_;  ///< the filter's answer, per name
  std::function<void(const std::string&, std::uint64_t, double)> too_large_;  ///< RunOptions'
  /// A VCD value change's bytes, about (its estimated size before it is written).
  static constexpr std::uint64_t kVcdBytesPerChange = 16;
  /// The items whose flow has started, by flow name ("ray", "job").
  std::map<std::string, std::unordered_set<std::uint64_t>, std::less<>> flows_started_;
};

}  // namespace rtsim::platform
