// ullner-pipeline: Ullner's ray-tracing pipeline (seed 000 §2.4, L684-L753). One polygon
// processor per polygon in a linear chain on bit-serial links; rays stream past the fixed
// polygons and each processor overwrites the description's intersection fields when its polygon
// is hit closer. The host at both ends (Fig. 2-23) is the peripheral's host, keeping many rays
// in flight; it loads the polygons by shifting them down the chain, dummies in the spares.
#include <algorithm>
#include <systemc>

#include "common/input_error.hpp"
#include "firmware/tasks/polygon_processor_task.hpp"
#include "modules/stat_directory.hpp"
#include "platform/functional/frame_state.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_support.hpp"
#include "platform/machines/ullner_pipeline/engine_chain.hpp"
#include "platform/machines/ullner_pipeline/pipeline_host.hpp"

namespace rtsim::platform {

class UllnerPipeline final : public Machine {
 public:
  using Machine::Machine;
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
};

namespace {

/// At most this many points along the chain in stats.json (`along_chain`): enough for a plot,
/// small at 100,000 processors (assumption, not a seed figure).
constexpr std::uint64_t kChainProfilePoints = 1000;

/// Windows of the frame in `along_chain.busy_windows` (assumption: enough columns to see a
/// chain of 1000 processors fill, about 5 ms, in a 1.3 s frame).
constexpr std::size_t kBusyWindows = 64;

/// Per-processor counts averaged over runs of neighbouring processors, per description.
nlohmann::ordered_json along_chain(const ullner_pipeline::EngineChain& chain,
                                   std::uint64_t descriptions, double busy_fraction,
                                   const sc_core::sc_time& frame_begin,
                                   const sc_core::sc_time& frame_end) {
  const std::uint64_t n = chain.engines();
  const std::uint64_t points = std::min(n, kChainProfilePoints);
  const double per = static_cast<double>(std::max<std::uint64_t>(descriptions, 1));
  nlohmann::ordered_json first = nlohmann::ordered_json::array(),
                         overwrites = nlohmann::ordered_json::array(),
                         answers = nlohmann::ordered_json::array(),
                         first_accept = nlohmann::ordered_json::array(),
                         last_accept = nlohmann::ordered_json::array(),
                         waited = nlohmann::ordered_json::array();
  for (std::uint64_t p = 0; p < points; ++p) {
    const std::uint64_t lo = p * n / points, hi = (p + 1) * n / points;
    double o = 0.0, a = 0.0;
    for (std::uint64_t k = lo; k < hi; ++k) {
      o += static_cast<double>(chain.overwrites()[k]);
      a += static_cast<double>(chain.answers()[k]);
    }
    const double count = static_cast<double>(hi - lo) * per;
    first.push_back(lo);
    overwrites.push_back(o / count);
    answers.push_back(a / count);
    if (!chain.engine_modules().empty()) {
      const auto& e = *chain.engine_modules()[lo];
      first_accept.push_back(e.first_accept().to_seconds());
      last_accept.push_back(e.last_accept().to_seconds());
      waited.push_back(e.waited().to_seconds() / per);
    }
  }
  nlohmann::ordered_json out = {{"engines", n},
                                {"busy_fraction", busy_fraction},
                                {"first_engine", std::move(first)},
                                {"overwrites_per_description", std::move(overwrites)},
                                {"answers_per_description", std::move(answers)}};
  // pipeline.model = engines: where the chain fills and drains (each point's first processor).
  if (!chain.engine_modules().empty()) {
    out["first_accept_s"] = std::move(first_accept);
    out["last_accept_s"] = std::move(last_accept);
    out["waited_per_description_s"] = std::move(waited);
    // When a few processors along the chain were busy: the fill, a hold, the drain.
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    modules::UtilizationWindows w;
    for (const auto& timeline : chain.watched_busy()) {
      w = timeline.windows(frame_begin, frame_end, kBusyWindows);
      rows.push_back(w.values);
    }
    out["busy_windows"] = {{"engines", chain.watched()},
                           {"begin_s", w.begin_s},
                           {"window_s", w.window_s},
                           {"busy", std::move(rows)}};
  }
  return out;
}

}  // namespace

/// The module tree: the host and the chain (their names and their parameters' paths).
constexpr const char* kHost = "host";
constexpr const char* kPipeline = "pipeline";

void UllnerPipeline::declare_params(params::ParamRegistry& r) const {
  // Its twin searches by brute force with Ullner's quad kernel, as every ray passes every
  // processor: no render.accel, grid, shells, polygon_kernel or bezier parameter is read.
  declare_common_params(
      r, {.accel = false, .shells = false, .polygon_kernel = false, .bezier = false});
  ullner_pipeline::PipelineHost::declare_params(modules::ParamDecls(r, kHost));
  ullner_pipeline::EngineChain::declare_params(modules::ParamDecls(r, kPipeline));
}

FunctionalTwin UllnerPipeline::make_twin(scenes::Scene& scene,
                                         const params::ParamRegistry& r) const {
  // One processor a polygon, each holding a convex quadrilateral (seed 000 L267, L688).
  require_polygons(name(), scene);
  auto settings = functional::read_render_settings(r);
  settings.polygon_kernel = functional::PolygonKernel::UllnerQuad;
  settings.accel = functional::AccelKind::None;
  FunctionalTwin twin = make_functional_twin(scene, settings);
  const modules::ModuleParams pipeline(r, kPipeline);
  const std::size_t engines = ullner_pipeline::EngineChain::engines(pipeline);
  if (twin.geometry->shapes.size() > engines)
    throw InputError(scene.name, 0,
                     "the scene needs " + std::to_string(twin.geometry->shapes.size()) +
                         " quadrilaterals but the pipeline has " + std::to_string(engines) +
                         " processors, one a polygon (set " +
                         ullner_pipeline::EngineChain::engines_name(pipeline) + " to at least " +
                         std::to_string(twin.geometry->shapes.size()) + ")");
  // The processors test t > 0 (seed 000 L275) and hold nothing but their polygon: there is no
  // hither plane to clip vision rays at, so the twin has none either (docs/machines.md).
  scene.camera.hither = 0.0;
  return twin;
}

RunResult UllnerPipeline::run(scenes::Scene& scene, FunctionalTwin& twin,
                              const params::ParamRegistry& r, const RunOptions& opts) const {
  using ullner_pipeline::EngineChain;
  using ullner_pipeline::PipelineHost;
  MachineRun run(name(), scene, twin, r, opts);
  const std::uint64_t polygons = twin.geometry->shapes.size();
  Bounds space = twin.geometry->scene_bounds;
  if (!scene.modelling_space.empty()) space.extend(scene.modelling_space);

  // A ray meets the host's link into the chain first (the probe lists stages as named).
  modules::LatencyProbe& probe = run.probe();
  const std::string link_in = std::string(kPipeline) + ".link_in";
  probe.stage(link_in);
  EngineChain chain(kPipeline, run);
  // Faults in flight on a processor's input, then those of the memory at rest.
  std::vector<MemoryFault> at_rest = opts.faults;
  chain.set_faults(ullner_pipeline::description_faults(kPipeline, chain.engines(), at_rest));
  inject_faults(name(), at_rest, {&chain.registers});
  const ullner::HostAttachment attached{
      .ray_queue = chain.input.fifo,
      .ray_link_name = link_in,
      .ray_link_params = link_in,
      .ray_bits = tasks::RayDescription::kWireBits,
      .max_in_flight = PipelineHost::rays_in_flight(modules::ModuleParams(r, kHost)),
      .result_slots = PipelineHost::result_slots(modules::ModuleParams(r, kHost)),
      .answers_first = PipelineHost::answers_first(modules::ModuleParams(r, kHost)),
      .lighting = {}};
  PipelineHost host(kHost, run, attached, chain.engines(), space);
  host.load_out.bind(chain.load);
  host.ray_out.bind(chain.input.socket);
  chain.result_out.bind(host.results.socket);
  chain.set_result_queue(host.results.fifo);
  run.simulate();

  const sc_core::sc_time frame_time = host.frame_time();
  const double frame_s = frame_time.to_seconds();
  run.stats_over(host.load_time(), frame_time);
  const std::uint64_t n = chain.engines();
  // The chain's own counts (its processors' class, pipeline.engine).
  const auto count = [](const char* stat) {
    return modules::StatDirectory::instance().count_over("pipeline.engine", stat);
  };
  const std::uint64_t passed = count("descriptions");
  const double descriptions = static_cast<double>(passed);

  const ullner_pipeline::ChainTiming& ct = chain.timing();
  const auto& et = ct.engine();
  const double rays = std::max(descriptions, 1.0);
  const double busy_fraction = frame_s > 0 ? chain.engine_busy().to_seconds() / frame_s : 0.0;
  // The chain empty: the host's link in, N-1 hops, the last processor passing it on with its
  // result fields, the link out.
  const double latency_s = (ct.description_time() + ct.link_latency()).to_seconds() * 2 +
                           ct.hop().to_seconds() * static_cast<double>(n - 1) +
                           et.hop_latency.to_seconds() + et.compute_latency.to_seconds();
  nlohmann::ordered_json& res = run.machine_stats();
  res["intersection_tests"] = passed * n;
  res["pipeline"] = {
      {"engines", n},
      {"polygons", polygons},
      {"description_bits", tasks::RayDescription::kWireBits},
      {"description_time_s", ct.description_time().to_seconds()},
      {"hop_s", ct.hop().to_seconds()},
      {"spacing_s", ct.spacing().to_seconds()},
      {"latency_s", latency_s},
      {"mean_transit_s", chain.transit_total().to_seconds() / rays},
      {"time_per_ray_s", frame_s / rays},
      {"rays", passed},
      {"host_utilization", frame_s > 0 ? host.busy().to_seconds() / frame_s : 0.0},
      {"chain_utilization", frame_s > 0 ? ct.spacing().to_seconds() * descriptions / frame_s : 0.0},
      {"load_time_s", host.load_time().to_seconds()},
      {"load_descriptions", count("load_descriptions")},
      {"load_description_time_s", chain.polygon_time().to_seconds()},
      // "So long as the pipe is kept full" (L743), measured: at the host's end and the far end.
      {"kept_full",
       {{"descriptions", chain.kept_full()},
        {"fraction",
         passed > 1 ? static_cast<double>(chain.kept_full()) / (descriptions - 1) : 0.0},
        {"host_starved_s", chain.host_starved().to_seconds()},
        {"chain_held_s", chain.chain_held().to_seconds()},
        {"far_end_held_s", chain.far_end_held().to_seconds()}}},
      {"along_chain",
       along_chain(chain, passed, busy_fraction, host.load_time(), host.load_time() + frame_time)}};
  if (!chain.faults().empty()) {
    nlohmann::ordered_json& in_flight = res["pipeline"]["faults_in_flight"];
    for (const auto& f : chain.faults())
      in_flight.push_back({{"at", f.name(kPipeline)},
                           {"word", f.word},
                           {"xor_mask", f.xor_mask},
                           {"applied", f.applied}});
  }
  using modules::StatUnit;
  run.machine_units() = {{"intersection_tests", StatUnit::count},
                         {"pipeline.description_bits", StatUnit::bits},
                         {"pipeline.*utilization", StatUnit::fraction},
                         {"pipeline.kept_full.fraction", StatUnit::fraction},
                         {"pipeline.along_chain.busy_fraction", StatUnit::fraction},
                         {"pipeline.*_s", StatUnit::seconds},
                         {"pipeline.along_chain.*_s", StatUnit::seconds},
                         // Processors, polygons, rays, descriptions, the fault's words.
                         {"pipeline.*", StatUnit::count}};
  return run.finish(host.latency(), {&chain.registers});
}

namespace {

const RegisterMachine<UllnerPipeline> kRegistered(
    {.name = "ullner-pipeline",
     .description = "Ullner's ray tracing pipeline: one intersection processor per polygon on "
                    "bit-serial links, rays streaming past, host at both ends (seed 000 §2.4)",
     .sample_scene = "builtin:ullner-cubes",
     .test_runs =
         {"--scene builtin:ullner-cubes",
          "--scene builtin:ullner-sheets-10 -p pipeline.engines=10 -p host.clock=\"100 GHz\""},
     .benchmark_runs = {"--scene builtin:ullner-cubes", "--scene builtin:ullner-random-1000",
                        "--scene builtin:ullner-sheets-1000"},
     .report_plots = {{.object = "pipeline",
                       .key = "along_chain",
                       .script = "chain_profile.py",
                       .title = "busy fraction along the chain",
                       .caption = "Each polygon processor's busy fraction along the chain, and per "
                                  "ray description how often it overwrote the description and "
                                  "gave the answer: the useful part of its work (stats.json "
                                  "pipeline.along_chain; analysis/chain_profile.py)"}}});

}  // namespace
}  // namespace rtsim::platform
