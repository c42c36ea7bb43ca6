// wang-bezier: Wang, Lewis & Hung's pipelined ray/Bezier-patch intersection machine (seed 002):
// a host that culls (ray, patch) pairs by the patch's box and issues them to an 11-stage
// pipeline of TMS320C6701 DSPs and a Culler ASIC, reading back the centre of the nearest
// surviving subpatch.
#include <algorithm>
#include <cmath>
#include <optional>
#include <systemc>

#include "firmware/shading/camera.hpp"
#include "modules/module_params.hpp"
#include "modules/stat_directory.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_support.hpp"
#include "platform/machines/wang_bezier/bezier_host.hpp"
#include "platform/machines/wang_bezier/bezier_pipeline.hpp"

namespace rtsim::platform {

class WangBezier final : public Machine {
 public:
  using Machine::Machine;
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
};

namespace {
const modules::FlagParam kAccuracyCheck(
    {.name = "accuracy.check",
     .default_value = "false",
     .description = "Check every answer of the pipeline against the double-precision reference "
                    "solver on the same job: hit/miss disagreement and hit-point error in patch "
                    "sizes, per job and per primary ray, in stats.json wang.accuracy. Costs wall "
                    "time (on the teapot a run takes about 1.5 times as long); changes neither "
                    "the image nor the timing",
     .source = "study setting: the paper compared with Bezier clipping and printed no number (seed "
               "002 L264-L266); the trade-off of stage count against accuracy"});
/// The module tree: the host and the pipeline (their names and their parameters' paths).
constexpr const char* kHost = "host";
constexpr const char* kPipeline = "pipeline";
}  // namespace

void WangBezier::declare_params(params::ParamRegistry& r) const {
  // Its twin is the functional renderer's brute-force search (every pair the host does not cull
  // goes through the pipeline) with Wang's kernel for patches and the host's kernel for the rest.
  declare_common_params(r,
                        {.accel = false, .shells = false, .polygon_kernel = true, .bezier = true});
  wang_bezier::BezierHost::declare_params(modules::ParamDecls(r, kHost));
  wang_bezier::BezierPipeline::declare_params(modules::ParamDecls(r, kPipeline));
  modules::ParamDecls(r, "", false).add(kAccuracyCheck);
}

FunctionalTwin WangBezier::make_twin(scenes::Scene& scene, const params::ParamRegistry& r) const {
  auto settings = functional::read_render_settings(r);
  settings.accel = functional::AccelKind::None;
  return make_functional_twin(scene, settings);
}

RunResult WangBezier::run(scenes::Scene& scene, FunctionalTwin& twin,
                          const params::ParamRegistry& r, const RunOptions& opts) const {
  using wang_bezier::BezierHost;
  using wang_bezier::BezierPipeline;
  MachineRun run(name(), scene, twin, r, opts);
  BezierPipeline pipeline(kPipeline, r, twin.settings.bezier_iterations,
                          twin.settings.bezier_culler_key_bits, twin.settings.bezier_arithmetic);
  std::optional<wang_bezier::ReferenceCheck> check;
  if (modules::ModuleParams(r, "").get(kAccuracyCheck)) {
    // The angle between the primary rays of two neighbouring pixels at the image's centre.
    const int w = run.frame().width(), h = run.frame().height();
    const shading::PinholeCamera camera(scene.camera, w, h);
    const Vec3 a = camera.primary(0.5 * w, 0.5 * h).direction;
    const Vec3 b = camera.primary(0.5 * w + 1.0, 0.5 * h).direction;
    const double pixel_angle = 2.0 * std::asin(std::min(1.0, 0.5 * glm::length(b - a)));
    check.emplace(*twin.geometry, twin.settings.bezier_iterations, pixel_angle);
  }
  BezierHost host(kHost, run, pipeline.input.fifo, check ? &*check : nullptr);
  host.job_out.bind(pipeline.input.socket);
  // Faults in flight on the pipeline's input, then those of the host's memory at rest.
  std::vector<MemoryFault> at_rest = opts.faults;
  pipeline.set_faults(wang_bezier::job_faults(kPipeline, pipeline.loop_stages(), at_rest));
  inject_faults(name(), at_rest, {&host.patch_memory});
  pipeline.result_out.bind(host.results.socket);
  run.simulate();

  const sc_core::sc_time frame_time = host.frame_time();
  run.stats_over(sc_core::SC_ZERO_TIME, frame_time);
  // The pipeline's own count of jobs taken.
  const std::uint64_t taken = modules::StatDirectory::instance().count_over(kPipeline, "jobs");
  const double jobs = static_cast<double>(taken);
  // Each substage's pool and time, from the modules (stage 0's, and loop stage 1's: the loop
  // stages are alike).
  const auto pools = [](const wang_bezier::PipelineStage& stage) {
    nlohmann::ordered_json out = nlohmann::ordered_json::object();
    for (const auto& s : stage.substages())
      out[s->basename()] = {{"dsps", s->pool().dsps},
                            {"units", s->pool().units},
                            {"cycles", s->pool().cycles},
                            {"time_s", s->timing().work.to_seconds()}};
    return out;
  };
  unsigned dsps = 0;
  for (const auto* s : pipeline.substages()) dsps += s->pool().dsps;
  const double frame = frame_time.to_seconds();
  nlohmann::ordered_json& res = run.machine_stats();
  nlohmann::ordered_json& w = res["wang"];
  w["loop_stages"] = pipeline.loop_stages();
  w["jobs"] = taken;
  if (pipeline.kept_full() > 0) {
    // Measured: the time between jobs leaving while it was kept full.
    const double cycle =
        pipeline.kept_full_time().to_seconds() / static_cast<double>(pipeline.kept_full());
    w["cycle_s"] = cycle;
    w["throughput_rpi_per_s"] = 1.0 / cycle;
    w["kept_full_jobs"] = pipeline.kept_full();
  }
  if (taken > 0) {
    w["latency_s"] = pipeline.shortest_transit().to_seconds();
    w["measured_rpi_per_s"] = frame > 0 ? jobs / frame : 0.0;
    if (w.contains("cycle_s"))
      w["pipeline_utilization"] =
          w["measured_rpi_per_s"].get<double>() * w["cycle_s"].get<double>();
    if (pipeline.kept_full() == 0)
      w["note"] =
          "the host never kept the pipeline full: no steady-state throughput measured "
          "(a faster host: -p host.clock=\"100 GHz\")";
  } else {
    // A scene with no patch a ray could reach gives the pipeline nothing to do: it has no
    // throughput to report.
    w["note"] = "no jobs: no ray reached a Bezier patch, so the pipeline did not run";
  }
  w["dsps"] = dsps;
  w["stage0"] = pools(pipeline.stage0());
  w["substages"] = pools(pipeline.first_loop());
  if (check) res["wang"]["accuracy"] = check->to_json();
  for (const auto& f : pipeline.faults())
    res["wang"]["faults_in_flight"].push_back({{"at", f.at(kPipeline)},
                                               {"word", f.word},
                                               {"xor_mask", f.xor_mask},
                                               {"applied", f.applied}});
  using modules::StatUnit;
  run.machine_units() = {{"wang.*_per_s", StatUnit::rate},
                         {"wang.pipeline_utilization", StatUnit::fraction},
                         // The reference check's shares of the jobs compared and of the hits.
                         {"wang.accuracy.disagreement*", StatUnit::fraction},
                         {"wang.accuracy.wrong_of_hits", StatUnit::fraction},
                         // Its errors, in scene units and pixels.
                         {"wang.accuracy.*_error.*", StatUnit::ratio},
                         {"wang.*_s", StatUnit::seconds},
                         // Stages, jobs, DSPs, units, cycles, the fault's words.
                         {"wang.*", StatUnit::count}};
  return run.finish(host.latency(), {&host.patch_memory});
}

namespace {

const RegisterMachine<WangBezier> kRegistered(
    {.name = "wang-bezier",
     .description =
         "Wang, Lewis & Hung's ray/Bezier-patch pipeline: a host culling and issuing jobs to "
         "stage 0 and 10 loop stages of DSPs with a Culler ASIC (seed 002)",
     .sample_scene = "builtin:default",
     .test_runs = {"--scene builtin:teapot",
                   "--scene builtin:default -p pipeline.culler.kind=software"},
     .benchmark_runs = {"--scene builtin:teapot --width 64 --height 64",
                        "--scene builtin:teapot --width 96 --height 96", "--scene builtin:teapot"},
     .report_plots = {
         {.object = "wang",
          .key = "substages",
          .script = "wang_substages.py",
          .title = "the Bezier pipeline's substages",
          .caption = "Each substage's time per job against the pipeline cycle (the "
                     "slowest sets it), and the busy fraction of its DSP pool over the "
                     "frame beside the host's (stats.json wang.stage0, wang.substages; "
                     "analysis/wang_substages.py)"}}});

}  // namespace
}  // namespace rtsim::platform
