#include "platform/machines/machine_run.hpp"

#include "common/input_error.hpp"
#include "modules/activations.hpp"
#include "modules/sim_time.hpp"
#include "modules/stat_classes.hpp"
#include "modules/stat_directory.hpp"
#include "platform/functional/window_work.hpp"
#include "platform/machines/machine_support.hpp"

namespace rtsim::platform {

namespace {
int or_default(int asked, int scene) { return asked > 0 ? asked : scene; }
/// Top-level keys stats.json may have, with room to spare (about 40 today).
constexpr std::size_t kStatsKeys = 96;
}  // namespace

MachineRun::MachineRun(std::string machine, const scenes::Scene& scene, const FunctionalTwin& twin,
                       const params::ParamRegistry& registry, const RunOptions& opts,
                       bool rows_sampled)
    : wall_start_(std::chrono::steady_clock::now()),
      machine_(std::move(machine)),
      scene_(scene),
      twin_(twin),
      registry_(registry),
      opts_(opts),
      width_(or_default(opts.width, scene.camera.width)),
      height_(or_default(opts.height, scene.camera.height)),
      frame_(width_, height_, twin.settings.spp, opts.aov_id, opts.aov_depth),
      // The quantum is set before anything is built (the trace is the first member to be).
      trace_((begin_simulation(registry), opts)),
      probe_(opts.latency_probe) {
  if (opts.sample_every > 1 && rows_sampled) {
    sample_.emplace(width_, height_, opts.sample_every, opts.sample_window_rows,
                    opts.sample_warmup);
    frame_.set_detailed_rows(sample_->detailed_rows());
    // A window is done when its last contribution lands in the frame buffer.
    frame_.fb().set_observer([this](std::uint32_t pixel, std::optional<std::uint64_t> at) {
      sample_->contribution(pixel, at ? *at : modules::sim_now().value());
    });
  }
}

FrameSample* MachineRun::sample_units(int units, const std::string& unit_name, int workers) {
  if (opts_.sample_every <= 1) return nullptr;
  if (opts_.sample_warmup > 0)
    throw InputError("--sample-warmup", 0,
                     machine_ + "'s windows are " + unit_name +
                         " its processors share, timed by their busy time: a warm-up does not "
                         "apply; leave it out");
  sample_.emplace(FrameSample::of_units(units, opts_.sample_every, opts_.sample_window_rows,
                                        unit_name, workers));
  return &*sample_;
}

void MachineRun::simulate() {
  sc_core::sc_report_handler::set_actions("/OSCI/SystemC", sc_core::SC_INFO,
                                          sc_core::SC_DO_NOTHING);
  try {
    sc_core::sc_start();
  } catch (...) {
    // SystemC hands an exception from a process back as its own report: the flag says whether
    // it was simulated time running out (the parameters' doing: bad input, not a fault).
    if (modules::time_overflowed())
      throw InputError(machine_, 0,
                       std::string(modules::TimeOverflow().what()) +
                           ": the frame these parameters describe is longer than the simulator "
                           "can count; shorten the times, the scene or the image");
    throw;
  }
}

void MachineRun::stats_over(const sc_core::sc_time& begin, const sc_core::sc_time& frame_time) {
  frame_time_ = frame_time;
  result_.simulated_time_s = frame_time.to_seconds();
  // The work of every window, for the work-weighted estimate (a --sample-error pilot's too: its
  // residuals choose K).
  if (sample_ && sample_->rows_sampled() && opts_.sample_work_stride > 0)
    sample_->set_window_work(functional::window_work(
        scene_, *twin_.tracer, twin_.settings.shade, width_, height_, twin_.settings.spp,
        sample_->window_rows(), opts_.sample_work_stride, sample_->detailed_rows()));
  if (sample_)
    sample_json_ = sample_->estimate(begin, begin + frame_time, result_.simulated_time_s);
  window_ = modules::StatWindow{begin, begin + frame_time};
}

RunResult MachineRun::finish(const modules::LatencyRecorder& ray_latency,
                             const std::vector<modules::Memory*>& fault_memories) {
  if (!window_) throw std::logic_error(machine_ + ": finish() before stats_over()");
  // The machine's keys first were added by the machine; the common ones lead.
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  // Room for every key, the command's own included: an ordered_json object is a vector of
  // (const key, value) pairs, which copies every value when it grows: `modules` whole, thousands
  // of modules, once each time.
  out.get_ref<nlohmann::ordered_json::object_t&>().reserve(kStatsKeys);
  // The unit of each number (modules/stat_unit.hpp), declared beside what writes it.
  using modules::StatUnit;
  modules::UnitSchema units{{"module_classes.*.instances", StatUnit::count},
                            {"module_classes.*.instances_reporting", StatUnit::count},
                            {"simulation.delta_cycles", StatUnit::count},
                            {"simulation.process_activations", StatUnit::count},
                            {"simulation.activations.*", StatUnit::count}};
  units.add(modules::LatencyRecorder::units(), "ray_latency_s.");
  // The options' keys are declared whether or not they are there: the options change no other
  // key of stats.json, `units` included.
  units.add(modules::LatencyProbe::units(), "latency_probe.");
  units.add(faults_units(), "faults.");
  units.add(MachineTrace::units(), "trace.");
  units.add(FrameSample::units(), "sample.");
  // Every statistics group alive is one of this run's modules (one simulation a process).
  out["modules"] = modules::StatDirectory::instance().to_json(*window_, &units);
  out["module_classes"] = modules::class_aggregates(out["modules"]);
  out["ray_latency_s"] = ray_latency.to_json();
  // What the simulation cost in events: an idle module should cost none (modules/activations.hpp).
  out["simulation"] = modules::activations_json();
  for (auto& [key, value] : result_.stats.items()) out[key] = std::move(value);
  if (probe_.enabled()) {
    // A machine that follows none of its rays would print "0 rays" as if it had measured them.
    if (probe_.rays() == 0)
      throw std::logic_error(machine_ + ": --latency-probe followed no " + probe_.unit() +
                             ": the machine does not report its " + probe_.unit() + "s' journeys");
    out["latency_probe"] = probe_.to_json();
  }
  if (!opts_.faults.empty()) out["faults"] = faults_json(fault_memories);
  if (trace_.on()) out["trace"] = trace_.finish(*window_);
  if (sample_) {
    out["sample"] = std::move(sample_json_);
    // The rows not simulated in detail, functionally: the image is whole.
    frame_.fb().set_observer({});
    if (!opts_.sample_pilot && opts_.image && !sample_->functional_rows().empty())
      functional::render_rows(scene_, *twin_.tracer, twin_.settings.shade, frame_,
                              sample_->functional_rows());
  }
  result_.stats = std::move(out);
  units.add(result_.units);
  result_.units = std::move(units);
  result_.image = frame_.finish(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count());
  return std::move(result_);
}

}  // namespace rtsim::platform
