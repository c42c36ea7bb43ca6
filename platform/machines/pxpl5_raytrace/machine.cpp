// pxpl5-raytrace: ray tracing on Pixel-Planes 5 with VOL2's organisation (seed 004 L259-L452):
// a host, a master GP handing out screen regions, i860 ray-caster GPs with the whole scene,
// compositor GPs owning bands of rows, SIMD renderers owning 128 x 128 tiles and a frame buffer,
// all on the kit's 5 Gbit/s token ring (L284).
#include <cmath>
#include <memory>
#include <numeric>
#include <systemc>

#include "common/input_error.hpp"
#include "modules/module_params.hpp"
#include "modules/sim_time.hpp"
#include "modules/stat_directory.hpp"
#include "modules/token_ring.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_support.hpp"
#include "platform/machines/pxpl5_raytrace/camera_path.hpp"
#include "platform/machines/pxpl5_raytrace/functional_regions.hpp"
#include "platform/machines/pxpl5_raytrace/graphics_processor.hpp"
#include "platform/machines/pxpl5_raytrace/nodes.hpp"
#include "platform/machines/pxpl5_raytrace/sample_journeys.hpp"
#include "platform/machines/pxpl5_raytrace/sampled_render.hpp"

namespace rtsim::platform {

class Pxpl5Raytrace final : public Machine {
 public:
  using Machine::Machine;
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
  /// Its casters sample screen regions on a lattice handed out by the master GP, not rows of
  /// vision rays: a sampled run's windows are regions (FrameSample::of_units).
  int sample_units(const params::ParamRegistry& registry, int width, int height) const override;
  /// Its estimate rests on each region's busy time, which does not grow as queues fill.
  int sample_warmup_rays(const params::ParamRegistry&) const override { return 0; }
};

namespace {

/// The ring's module (and its parameters' class).
constexpr const char* kRing = "ring";

/// Whether the image is the plain functional render's: every pixel cast, at the scene's view, in
/// the displayed frame, which is the last.
bool every_pixel(const pxpl5::Layout& lay, const tasks::RefinementSchedule& schedule,
                 int display_frame) {
  const tasks::FramePlan& shown = schedule.plan(display_frame);
  return lay.rule.finest == 1 && !lay.rule.adaptive() && lay.update_period == 1 &&
         lay.refine_levels == 1 && display_frame == schedule.frames() - 1 &&
         shown.cast_level == 0 && shown.phase < 0;
}

/// The run's refinement schedule: its camera path's moving frames, its layout's levels and
/// partial updating.
tasks::RefinementSchedule schedule_of(const pxpl5::Layout& lay, const pxpl5::CameraPath& path) {
  return {path.moving, lay.refine_levels, lay.update_period};
}

}  // namespace

void Pxpl5Raytrace::declare_params(params::ParamRegistry& r) const {
  // The ray casters run the ordinary software ray tracer on their copy of the scene: every
  // render parameter is read.
  declare_common_params(r, {});
  pxpl5::Layout::declare_params(r);
  pxpl5::CameraPath::declare_params(r);
  pxpl5::Bypass::declare_params(r);
  pxpl5::declare_gp_params(r);
  pxpl5::Host::declare_params(r);
  pxpl5::MasterGp::declare_params(r);
  pxpl5::Compositor::declare_params(r);
  pxpl5::Renderer::declare_params(r);
  pxpl5::FrameBuffer::declare_params(r);
  pxpl5::WireSizes::declare_params(r);
  modules::TokenRing::declare_params(
      modules::ParamDecls(r, kRing, false),
      {.bandwidth = "5 Gbit/s",
       .bandwidth_source = "seed 004 L284",
       .hop_latency = "50 ns",
       .max_packet_bytes = "1024",
       .header_bytes = "8",
       .service = "exhaustive",
       .source = "assumption: the seed gives only the bandwidth (note 004 A; Fuchs et al., "
                 "SIGGRAPH 89, would give the rest)"});
  pxpl5::SamplesFault::declare_params(r);
}

FunctionalTwin Pxpl5Raytrace::make_twin(scenes::Scene& scene,
                                        const params::ParamRegistry& r) const {
  // What the picture depends on only (bad sampling settings are bad input); the GP counts are
  // read by run().
  const pxpl5::Layout layout = pxpl5::Layout::read_sampling(r);
  const pxpl5::CameraPath path = pxpl5::CameraPath::read(r);
  // The image is the last frame's: the scene's camera, moved to camera.distance, is that
  // frame's; the earlier ones are turned back from it (run()).
  pxpl5::move_eye(scene.camera, path.distance);
  const tasks::RefinementSchedule schedule = schedule_of(layout, path);
  const int shown = pxpl5::FrameBuffer::display_frame(r, path.frames);
  FunctionalTwin twin = make_functional_twin(scene, functional::read_render_settings(r));
  if (!every_pixel(layout, schedule, shown)) {
    twin.render = [layout, path, schedule, shown](const scenes::Scene& s, const Tracer& tracer,
                                                  const functional::RenderOptions& opts) {
      return pxpl5::sampled_render(s, tracer, opts, layout, path, schedule, shown);
    };
  }
  pxpl5::check_scene_fits(scene.name, twin.geometry->shapes.size(), r);
  return twin;
}

int Pxpl5Raytrace::sample_units(const params::ParamRegistry& r, int width, int height) const {
  pxpl5::Layout layout = pxpl5::Layout::read(r);
  layout.width = width;
  layout.height = height;
  return static_cast<int>(layout.regions().size());
}

RunResult Pxpl5Raytrace::run(scenes::Scene& scene, FunctionalTwin& twin,
                             const params::ParamRegistry& r, const RunOptions& opts) const {
  using namespace pxpl5;
  MachineRun run(name(), scene, twin, r, opts, /*rows_sampled=*/false);
  Setup setup;
  setup.layout = Layout::read(r);
  setup.layout.width = run.width();
  setup.layout.height = run.height();
  const CameraPath path = CameraPath::read(r);
  setup.frames = path.frames;
  setup.schedule = schedule_of(setup.layout, path);
  setup.display_frame = FrameBuffer::display_frame(r, path.frames);
  for (int f = 0; f < setup.frames; ++f)
    setup.cameras.emplace_back(frame_camera(scene.camera, path, f), run.width(), run.height());
  setup.sizes = WireSizes::read(r);
  setup.gp_timing = read_gp_timing(r);
  setup.bypass = Bypass::read(r);
  // --latency-probe follows samples (a caster traces a region in one go) to the display
  // (sample_journeys.hpp).
  modules::LatencyProbe& probe = run.probe();
  probe.describe("sample",
                 "from its caster beginning its region to the frame buffer displaying its "
                 "frame; at the renderer and the frame buffer, which work on whole tiles, a "
                 "sample takes its own display pixel's tile's times");
  setup.stages = {.caster = probe.stage("caster*"),
                  .ring = probe.stage("ring"),
                  .inbox = probe.stage("compositor*.inbox"),
                  .compositor = probe.stage("compositor*"),
                  .renderer = probe.stage("renderer*"),
                  .frame_buffer = probe.stage("frame_buffer")};
  SampleJourneys journeys;
  if (probe.enabled()) setup.journeys = &journeys;
  if (opts.sample_every > 1) {
    // Sampled: every K-th region (in the master's order, which is screen order in a first
    // frame) in detail, the others cast functionally and handed to the compositors.
    if (setup.frames != 1 || setup.bypass.code != "none")
      throw InputError("--sample", 0,
                       "pxpl5-raytrace samples the regions of a single frame with its casters "
                       "working: set frames = 1 and bypass = none (a later frame's regions and "
                       "order depend on the frames before it in detail)");
    setup.sample = run.sample_units(static_cast<int>(setup.layout.regions().size()), "regions",
                                    setup.layout.casters);
    setup.functional_samples = cast_functionally(
        setup, run, [&](int id) { return !setup.sample->detailed_unit(id); },
        !opts.sample_pilot && opts.image);
  }

  const Layout& lay = setup.layout;
  modules::TokenRing ring(kRing, modules::TokenRing::read_config(modules::ModuleParams(r, kRing)),
                          static_cast<std::size_t>(lay.nodes()), kTrafficClasses);
  ring.trace_to(run.trace());
  modules::RingChannel<Message> channel("ring_channel", ring);
  SamplesFault fault(r);
  Host host("host", run, channel, setup);
  MasterGp master("master", run, channel, setup);
  std::vector<std::unique_ptr<RayCaster>> casters;
  for (int k = 0; k < lay.casters; ++k)
    casters.push_back(std::make_unique<RayCaster>(("caster" + std::to_string(k)).c_str(), run,
                                                  channel, setup, k, fault));
  std::vector<std::unique_ptr<Compositor>> compositors;
  for (int k = 0; k < lay.compositors; ++k)
    compositors.push_back(std::make_unique<Compositor>(("compositor" + std::to_string(k)).c_str(),
                                                       run, channel, setup, k));
  std::vector<std::unique_ptr<Renderer>> renderers;
  for (int k = 0; k < lay.renderers(); ++k)
    renderers.push_back(std::make_unique<Renderer>(("renderer" + std::to_string(k)).c_str(), run,
                                                   channel, setup, k));
  FrameBuffer fb("frame_buffer", run, channel, setup);
  inject_faults(name(), opts.faults, {});  // its answers come from the messages, not a memory
  run.simulate();

  if (host.done().size() != static_cast<std::size_t>(setup.frames))
    throw std::runtime_error("pxpl5-raytrace: the frame buffer never had every pixel");
  const sc_core::sc_time end = host.done().back();
  run.stats_over(sc_core::SC_ZERO_TIME, end);
  nlohmann::ordered_json workload = nlohmann::ordered_json::array();
  double most = 0;
  for (const auto& c : casters) most = std::max(most, c->accounts().busy.to_seconds());
  for (const auto& c : casters)
    workload.push_back(most > 0 ? c->accounts().busy.to_seconds() / most : 0.0);
  // Over every caster: their own counts, summed.
  const auto casters_total = [](const char* stat) {
    return modules::StatDirectory::instance().count_over("caster*", stat);
  };
  const std::uint64_t rays = casters_total("rays"), cast_last = casters_total("cast_last_frame"),
                      covered_last = casters_total("covered_last_frame");
  // Each frame: when the host started it (its view read), when the frame buffer displayed it,
  // the latency between, and its interval since the display before (the first: since its start).
  const auto& shown = fb.displayed();
  nlohmann::ordered_json per_frame = nlohmann::ordered_json::array();
  nlohmann::ordered_json frame_times = nlohmann::ordered_json::array();
  double latency_sum = 0, latency_max = 0;
  for (std::size_t f = 0; f < shown.size(); ++f) {
    const double latency = (shown[f] - host.started()[f]).to_seconds();
    const double interval = (shown[f] - (f == 0 ? host.started()[0] : shown[f - 1])).to_seconds();
    const tasks::FramePlan& plan = setup.schedule.plan(static_cast<int>(f));
    per_frame.push_back({{"frame", f},
                         {"new_view", plan.new_view},
                         {"cast_level", plan.cast_level},
                         {"display_level", plan.display_level},
                         {"start_s", host.started()[f].to_seconds()},
                         {"display_s", shown[f].to_seconds()},
                         {"latency_s", latency},
                         {"interval_s", interval}});
    frame_times.push_back(interval);
    latency_sum += latency;
    latency_max = std::max(latency_max, latency);
  }
  const double span = (shown.back() - host.started().front()).to_seconds();
  const double last = frame_times.back().get<double>();
  const double fps = span > 0 ? static_cast<double>(shown.size()) / span : 0.0;
  const double last_fps = last > 0 ? 1.0 / last : 0.0;
  // The steady rate: frames after the first over the time between the first display and the last
  // (the pipeline full); a single frame's is its own.
  const double steady_span = (shown.back() - shown.front()).to_seconds();
  const double steady_fps = shown.size() > 1 && steady_span > 0
                                ? static_cast<double>(shown.size() - 1) / steady_span
                                : last_fps;
  nlohmann::ordered_json& res = run.machine_stats();
  res["pxpl5"] = {
      {"casters", lay.casters},
      {"compositors", lay.compositors},
      {"renderers", lay.renderers()},
      {"ring_nodes", lay.nodes()},
      {"scheme", scheme_name(lay.scheme)},
      {"order", master.order()},
      {"bypass", setup.bypass.code},
      {"regions_per_frame", lay.regions().size()},
      {"lattice", {lay.lattice().nx(), lay.lattice().ny()}},
      {"sampling",
       {{"finest", lay.rule.finest},
        {"start", lay.rule.start},
        {"adaptive", lay.rule.adaptive()},
        {"update_fraction", 1.0 / lay.update_period},
        {"refine_levels", lay.refine_levels}}},
      {"rays_per_frame", static_cast<double>(rays) / setup.frames},
      // Fig. 9's abscissa: the share of the screen the scene covers (last frame's
      // rays on the screen that hit; adaptive squares cast more where it is).
      {"screen_coverage", cast_last > 0 ? static_cast<double>(covered_last) / cast_last : 0.0},
      {"rays_per_pixel",
       static_cast<double>(rays) / setup.frames / (static_cast<double>(lay.width) * lay.height)},
      {"frames", setup.frames},
      {"frames_in_flight", host.frames_in_flight()},
      {"frame_times_s", std::move(frame_times)},
      {"frames_per_second", fps},
      // The last frame's rate: the steady state once a previous frame's costs order the squares
      // (L360).
      {"last_frame_per_second", last_fps},
      {"steady_frames_per_second", steady_fps},
      {"caster_workload", std::move(workload)},
      {"samples_messages", fault.messages()}};
  // What an interactive user sees, for the console and any machine with a frame sequence.
  res["frame_sequence"] = {{"frames", setup.frames},
                           {"frames_per_second", fps},
                           {"last_frame_per_second", last_fps},
                           {"steady_frames_per_second", steady_fps},
                           {"steady_frames_per_second", steady_fps},
                           {"latency_mean_s", latency_sum / static_cast<double>(shown.size())},
                           {"latency_max_s", latency_max},
                           {"per_frame", std::move(per_frame)}};
  using modules::StatUnit;
  run.machine_units() = {{"*_per_second", StatUnit::rate},
                         {"pxpl5.frame_times_s", StatUnit::seconds},
                         {"pxpl5.screen_coverage", StatUnit::fraction},
                         {"pxpl5.sampling.update_fraction", StatUnit::fraction},
                         // Each caster's busy time over the busiest one's.
                         {"pxpl5.caster_workload", StatUnit::fraction},
                         {"pxpl5.rays_per_pixel", StatUnit::ratio},
                         {"frame_sequence.*_s", StatUnit::seconds},
                         // Processors, regions, lattice points, rays, frames, levels, messages.
                         {"pxpl5.*", StatUnit::count},
                         {"frame_sequence.*", StatUnit::count}};
  return run.finish(modules::LatencyRecorder{}, {});
}

namespace {

const RegisterMachine<Pxpl5Raytrace> kRegistered(
    {.name = "pxpl5-raytrace",
     .description =
         "Ray tracing on Pixel-Planes 5 (VOL2's organisation): a master GP handing out screen "
         "regions to i860 ray casters, compositors, SIMD renderers and a frame buffer on a "
         "5 Gbit/s token ring (seed 004)",
     .sample_scene = "builtin:default",
     .test_runs = {"--scene builtin:default -p assign.scheme=rows",
                   "--scene builtin:default -p frames=2",
                   "--scene builtin:default -p assign.scheme=rows -p ring.service=gated"},
     .benchmark_runs = {"--scene builtin:default -p assign.scheme=rows",
                        "--scene builtin:spd-teapot -p assign.scheme=rows",
                        "--scene builtin:npp-412 -p assign.scheme=rows"},
     .report_plots = {
         {.object = "pxpl5",
          .key = "caster_workload",
          .script = "pxpl5_workload.py",
          .title = "the ray casters' workloads",
          .caption = "Each ray caster's busy time over the busiest's, with the regions "
                     "it was given (VOL2's Plate 4), and the bytes each traffic class "
                     "put on the token ring (stats.json pxpl5.caster_workload, modules "
                     "ring; analysis/pxpl5_workload.py)"}}});

}  // namespace
}  // namespace rtsim::platform
