#pragma once
// `rtsim run --latency-probe`: where a ray spends its time on its way through the machine.
//
// Each probed ray carries a journey: the time it spends at each stage of the machine (a module
// or a bus), split into three parts:
//   queueing — waiting for the stage: in its input queue, or for a bus slot / the wanted ID;
//   service  — the stage working on the ray (a processor's task, a pipeline's intersections);
//   transfer — moving the ray's data: words on a bus, a message over a link.
// When the ray ends its journey is folded into per-stage sums and the end-to-end latency into a
// LatencyRecorder. What the parts do not cover (end-to-end minus their sum) is reported as
// `unattributed_s`, so a stage a machine forgot to report shows up instead of hiding.
//
// Disabled (the default) every call is one branch: a machine calls the probe unconditionally.
// Used by every machine.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <systemc>
#include <vector>

#include "modules/latency_recorder.hpp"

namespace rtsim::modules {

enum class LatencyPart : std::uint8_t { kQueueing = 0, kService = 1, kTransfer = 2 };
inline constexpr int kLatencyParts = 3;

class LatencyProbe {
 public:
  /// Handle of one ray's journey; kNoJourney when the probe is disabled.
  using Journey = std::uint32_t;
  static constexpr Journey kNoJourney = ~Journey{0};

  explicit LatencyProbe(bool enabled = false) : enabled_(enabled) {}
  bool enabled() const { return enabled_; }

  /// Index of stage `name` (created on first call). Stages are reported in the order they were
  /// first named: name them in the order a ray meets them.
  int stage(const std::string& name);

  /// Starts a ray's journey at `now`.
  Journey begin(const sc_core::sc_time& now);
  /// Adds `dt` of `part` at `stage` to the journey (no-op for kNoJourney).
  void add(Journey j, int stage, LatencyPart part, const sc_core::sc_time& dt);
  /// Ends the journey at `now` and folds it into the totals; `j` may then be reused.
  void end(Journey j, const sc_core::sc_time& now);
  /// A copy of journey `j` so far, for a ray it spawns whose latency counts from the same
  /// start (ullner-array: a result and the shadow rays of one hit); kNoJourney for kNoJourney.
  Journey fork(Journey j);
  /// Forgets journey `j` without counting it: its ray ended with nothing to deliver (an
  /// occluded shadow ray contributes nothing).
  void drop(Journey j);

  /// What a journey follows when it is not a ray ("sample": pxpl5-raytrace's), and where its
  /// journey starts and ends when that is not the machine's ray latency window: stats.json
  /// `unit` and `scope`, shown with the figures.
  void describe(std::string unit, std::string scope) {
    unit_ = std::move(unit);
    scope_ = std::move(scope);
  }
  const std::string& unit() const { return unit_; }

  std::uint64_t rays() const { return rays_; }
  /// Journeys begun and not ended (a machine that loses rays shows them here).
  std::size_t in_flight() const { return slots_.size() - free_.size(); }

  /// stats.json `latency_probe`: {rays, unit, [scope], end_to_end_s: {count, mean, p50, p99, max,
  /// histogram}, unattributed_s, stages: {NAME: {queueing_s, service_s, transfer_s, total_s, p99_s,
  /// share}}} — per-stage figures are means per ray (a ray that never met a stage counts 0 there);
  /// p99_s is the 99th percentile of the stage's total; share = total_s / end-to-end mean.
  nlohmann::ordered_json to_json() const;
  /// The units of to_json's keys (modules/stat_unit.hpp).
  static UnitSchema units();

 private:
  struct Slot {
    /// Kept as an sc_time (integer picoseconds) so that end-to-end = (now - begin) is exact and
    /// equals a machine's own `ray_latency_s` sample for the same window bit for bit.
    sc_core::sc_time begin;
    std::vector<double> parts;  ///< [stage * kLatencyParts + part], seconds
  };
  struct StageTotals {
    std::string name;
    long double parts[kLatencyParts] = {0, 0, 0};
    LatencyRecorder total;
  };

  bool enabled_;
  std::string unit_ = "ray";
  std::string scope_;
  std::vector<StageTotals> stages_;
  std::vector<Slot> slots_;
  std::vector<Journey> free_;
  LatencyRecorder end_to_end_;
  long double unattributed_ = 0;
  std::uint64_t rays_ = 0;
};

}  // namespace rtsim::modules
