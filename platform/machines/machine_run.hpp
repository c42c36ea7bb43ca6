#pragma once
// The run skeleton every machine shares (DESIGN.md "The three layers": written once): the frame
// buffer, the traces, the latency probe, the simulation, the statistics and the image. A
// machine's run() is then only what is its own:
//
//   MachineRun run(name(), scene, twin, registry, opts);     // frame, traces, quantum, probe
//   ... build the module tree: each module takes `run` (frame, trace, probe, options,
//       registry, scene, twin) and reads its own parameters ...
//   inject_faults(name(), opts.faults, memories);
//   run.simulate();                                         // sc_start
//   run.stats_over(frame_begin, frame_time);                 // the frame of the statistics
//   ... the machine's own keys into run.machine_stats() ...
//   return run.finish(ray_latency, memories);               // modules, latency, trace, image
//
// The modules report themselves: stats.json's `modules` is every statistics group alive
// (modules/stat_directory.hpp), written by finish().
// Used by every machine.
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "modules/latency_probe.hpp"
#include "modules/latency_recorder.hpp"
#include "modules/memory.hpp"
#include "modules/statistics.hpp"
#include "platform/functional/frame_state.hpp"
#include "platform/machine.hpp"
#include "platform/machines/frame_sample.hpp"
#include "platform/machines/machine_trace.hpp"

namespace rtsim::platform {

class MachineRun {
 public:
  /// Starts the wall clock, sizes the frame (RunOptions, else the scene's camera), sets the TLM
  /// quantum and opens the traces: before any module is built.
  /// With --sample, windows of rows (`rows_sampled`), else the machine names its own work units
  /// (sample_units).
  MachineRun(std::string machine, const scenes::Scene& scene, const FunctionalTwin& twin,
             const params::ParamRegistry& registry, const RunOptions& opts,
             bool rows_sampled = true);

  /// With --sample on a machine whose work is not rows (FrameSample::of_units): `units` units of
  /// work called `unit_name`; the machine simulates those detailed_unit() names, says when each
  /// is done (unit_done) and renders the rest itself; `workers` processors take the units side
  /// by side. Nothing without --sample.
  FrameSample* sample_units(int units, const std::string& unit_name, int workers = 1);

  int width() const { return width_; }
  int height() const { return height_; }
  functional::FrameState& frame() { return frame_; }
  MachineTrace& trace() { return trace_; }
  /// --latency-probe (disabled unless asked for): one journey per ray, stages named as modules.
  modules::LatencyProbe& probe() { return probe_; }
  const RunOptions& options() const { return opts_; }
  /// The run's context, for a module's constructor: its parameters (ModuleParams over this),
  /// the scene and the functional twin (tracer, render settings).
  const params::ParamRegistry& registry() const { return registry_; }
  const scenes::Scene& scene() const { return scene_; }
  const FunctionalTwin& twin() const { return twin_; }

  /// Runs the simulation until nothing is left to happen (a machine ends its frame with
  /// sc_stop(), which is no news).
  void simulate();

  /// After simulate(): the modules' statistics are taken over the frame
  /// [begin, begin + frame_time] (the time before `begin` is the scene load).
  void stats_over(const sc_core::sc_time& begin, const sc_core::sc_time& frame_time);

  /// What the machine adds to stats.json besides its modules (its headline keys).
  nlohmann::ordered_json& machine_stats() { return result_.stats; }
  /// The units of those keys, declared beside the code that writes them (modules/stat_unit.hpp:
  /// "array.messages_sent_by_type.*" counts); tests/stats_units_test.cpp finds any key without.
  modules::UnitSchema& machine_units() { return result_.units; }

  /// The rest of stats.json — `modules`, `ray_latency_s`, `latency_probe`, `faults`, `trace` —
  /// and the image, with the wall time of the whole run.
  RunResult finish(const modules::LatencyRecorder& ray_latency,
                   const std::vector<modules::Memory*>& fault_memories);

 private:
  std::chrono::steady_clock::time_point wall_start_;
  std::string machine_;
  const scenes::Scene& scene_;
  const FunctionalTwin& twin_;
  const params::ParamRegistry& registry_;
  const RunOptions& opts_;
  int width_, height_;
  functional::FrameState frame_;
  MachineTrace trace_;
  modules::LatencyProbe probe_;
  std::optional<modules::StatWindow> window_;
  sc_core::sc_time frame_time_ = sc_core::SC_ZERO_TIME;
  RunResult result_;
  std::optional<FrameSample> sample_;  ///< --sample
  nlohmann::ordered_json sample_json_;
};

}  // namespace rtsim::platform
