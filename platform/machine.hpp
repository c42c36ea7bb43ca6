#pragma once
// A machine: the modules it is wired from, the firmware that runs where, its preset parameters,
// and its functional twin (its own geometry conversion with no timing, whose image the timed
// model must reproduce bit for bit).
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "firmware/scene.hpp"
#include "firmware/tracer.hpp"
#include "modules/stat_unit.hpp"
#include "modules/trace/trace_filter.hpp"
#include "params/registry.hpp"
#include "platform/functional/functional_renderer.hpp"
#include "platform/functional/render_params.hpp"
#include "platform/functional/scene_geometry.hpp"

namespace rtsim::platform {

/// The geometry a machine stores and the tracer its firmware uses, without timing.
struct FunctionalTwin {
  /// Held by pointer: the tracer refers to it, and twins are moved around.
  std::unique_ptr<functional::SceneGeometry> geometry;
  std::unique_ptr<Tracer> tracer;
  functional::RenderSettings settings;
  /// The twin's image where it is not one traced pixel at a time (pxpl5-raytrace's sampled
  /// screen); empty: functional::render. Call render_twin.
  std::function<functional::RenderResult(const scenes::Scene&, const Tracer&,
                                         const functional::RenderOptions&)>
      render;
};

/// The twin's image: its own render, or the functional renderer's with its tracer.
inline functional::RenderResult render_twin(const FunctionalTwin& twin, const scenes::Scene& scene,
                                            const functional::RenderOptions& opts) {
  return twin.render ? twin.render(scene, *twin.tracer, opts)
                     : functional::render(scene, *twin.tracer, opts);
}

/// A word corrupted on its way into one of a machine's memories (`rtsim run --fault
/// MEMORY:WORD:XOR`): the memory by its hierarchical name, the word's index, the bits flipped.
struct MemoryFault {
  std::string memory;
  std::uint64_t word = 0;
  std::uint32_t xor_mask = 0;
};

struct RunOptions {
  int width = 0;  ///< 0: the scene's
  int height = 0;
  bool aov_id = false;
  bool aov_depth = false;
  /// The image is wanted (rtsim run --image all|png). False (--image none): what only the picture
  /// needs is skipped, the functional rows of a sampled run.
  bool image = true;
  std::filesystem::path vcd_path;       ///< empty: no VCD trace
  std::filesystem::path perfetto_path;  ///< empty: no Perfetto trace
  /// At most this many events in each trace file (Perfetto events, VCD value changes); 0: every
  /// event. What a cap drops is counted in stats.json `trace` and printed.
  std::size_t trace_max_events = 0;
  /// --trace-window, --trace-modules: what the traces keep (default: everything).
  modules::TraceFilter trace_filter{};
  /// Told once, while the run goes on, when the Perfetto trace it streams has passed
  /// modules::kTraceWarnBytes (its file name, its bytes so far, the simulated time it reached),
  /// and before the VCD is written when its estimated size is over it (its file name, the bytes
  /// estimated, -1): the user may stop the run and keep less. Empty: nobody is told.
  std::function<void(const std::string&, std::uint64_t, double)> trace_too_large;
  bool latency_probe = false;
  std::vector<MemoryFault> faults;
  std::function<void(long, long)> progress;  ///< (rays finished, rays expected so far)
  /// Sampled simulation (platform/machines/frame_sample.hpp): every `sample_every`-th window of
  /// `sample_window_rows` rows in detail, the rest functionally; 0: the whole frame in detail.
  int sample_every = 0;
  int sample_window_rows = 1;
  /// Windows after window 0 simulated in detail as a warm-up (FrameSample).
  int sample_warmup = 0;
  /// The work-weighted estimate's subsample of columns (functional::window_work): every
  /// `sample_work_stride`-th pixel of each row not simulated in detail is traced functionally to
  /// count its work; 0: no work counted, the systematic estimate.
  int sample_work_stride = 2;
  /// A pilot of --sample-error: only the estimate is wanted, the rest is not rendered.
  bool sample_pilot = false;
};

struct RunResult {
  functional::RenderResult image;  ///< rgb, AOVs and counters (wall_time_s: the simulation)
  double simulated_time_s = 0.0;   ///< the frame time on the modelled machine
  nlohmann::ordered_json stats;    ///< machine-specific keys merged into stats.json
  /// The unit of every number of `stats` (modules/stat_unit.hpp): the machine declares its own
  /// section's, MachineRun adds the modules' and the run's.
  modules::UnitSchema units;
};

/// What a machine's registration says of it (RegisterMachine, platform/machine_registry.hpp):
/// how it is listed, and what the generic tests and the benchmarks run it on.
/// A plot `rtsim run --report` draws of the machine's own stats.json object, with an analysis/
/// script run on stats.json.
struct ReportPlot {
  std::string object{};  ///< the machine's stats.json object ("pipeline", "array", ...)
  std::string key{};     ///< drawn only when the object has this key
  std::string script{};  ///< analysis/SCRIPT
  std::string title{};
  std::string caption{};
};

struct MachineInfo {
  std::string name;         ///< `--machine NAME`
  std::string description;  ///< one line, citing its seed ("seed 004")
  /// A small scene it can hold, which `rtsim describe` builds the module tree for.
  std::string sample_scene;
  /// The runs the generic tests make of it: a scene and parameters, no size, no output
  /// (`--scene builtin:ullner-cubes -p array.rows=4`). The first is its small run, which every
  /// generic test uses; the others vary its structure and trace agreement runs them too.
  std::vector<std::string> test_runs;
  /// The runs bench/pareto.py times it on, in the same form (three scenes it holds).
  std::vector<std::string> benchmark_runs;
  /// `rtsim run` without --machine runs this one (exactly one machine says so).
  bool default_machine = false;
  /// The plots of its own figures a run's report draws.
  std::vector<ReportPlot> report_plots{};
  /// It takes --sample and --sample-error (platform/machines/frame_sample.hpp). A machine that
  /// does not says why (`sampling_refusal`), and `rtsim run` refuses those options before
  /// anything runs.
  bool samples = true;
  std::string sampling_refusal{};
};

class Machine {
 public:
  explicit Machine(MachineInfo info) : info_(std::move(info)) {}
  virtual ~Machine() = default;
  const MachineInfo& info() const { return info_; }
  const std::string& name() const { return info_.name; }
  const std::string& description() const { return info_.description; }
  const std::string& sample_scene() const { return info_.sample_scene; }
  virtual void declare_params(params::ParamRegistry& registry) const = 0;
  /// Converts the scene as the machine would store it; throws InputError for scenes the
  /// machine cannot hold (with what and why).
  virtual FunctionalTwin make_twin(scenes::Scene& scene,
                                   const params::ParamRegistry& registry) const = 0;
  /// Sampled simulation (`rtsim run --sample`, FrameSample): the rows (or units, below) of a
  /// window that keeps every parallel part of it busy (gaudet-pert's PERTs take scanlines in
  /// turn). A machine whose rays come from VisionRayTask skips the rows not simulated in detail.
  virtual int sample_window_rows(const params::ParamRegistry&) const { return 1; }
  /// The vision rays a sampled run simulates in detail after window 0 before it samples (its
  /// warm-up, FrameSample::default_warmup): the machine's queues fill meanwhile, and until they
  /// have its windows run faster than they will. 512: ullner-pipeline's fill on a scene of
  /// alike rows, at 64, 128 and 256 pixels a row (docs/sampling.md). 0: no warm-up.
  virtual int sample_warmup_rays(const params::ParamRegistry&) const { return 512; }
  /// The units of work a sampled run's windows are made of in a `width` x `height` frame: its
  /// rows, or what the machine hands out instead (pxpl5-raytrace: screen regions).
  virtual int sample_units(const params::ParamRegistry&, int /*width*/, int height) const {
    return height;
  }
  /// Builds the SystemC model, simulates one frame and returns the image and statistics.
  /// SystemC allows one simulation per process: call at most once.
  virtual RunResult run(scenes::Scene& scene, FunctionalTwin& twin,
                        const params::ParamRegistry& registry, const RunOptions& opts) const = 0;

 private:
  MachineInfo info_;
};

/// Declares `quantum` (global TLM quantum) and the render/shade parameters of `use`: those the
/// machine's functional twin reads.
void declare_common_params(params::ParamRegistry& registry, const functional::RenderParamUse& use);

/// Declares the parameters `machine` reads (nullptr: the functional renderer's, `rtsim render`
/// without --machine) and tells the registry the names only others read, so that setting one of
/// those says it is not used instead of being accepted and ignored.
void declare_params_of(const Machine* machine, params::ParamRegistry& registry);

}  // namespace rtsim::platform
