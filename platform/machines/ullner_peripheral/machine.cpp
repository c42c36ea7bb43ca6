// ullner-peripheral: Ullner's ray tracing peripheral (seed 000 §2.3, L458-L680) attached to a
// medium-sized host. The host runs two tasks (vision-ray generation; result processing and
// shading) with a ray queue and a result queue between it and the peripheral; the peripheral
// fetches polygons from 20 parallel parameter memories into the intersection pipeline (13
// logical stages; 17 or 33 physical, one intersection per 1/3 us), keeps the closest valid hit
// (any hit for shadow rays), and has the lighting extension. With peripheral.grid.divisions > 0
// the grid auxiliary processor feeds it the polygon addresses of the subvolumes along the ray.
#include <chrono>
#include <systemc>

#include "common/input_error.hpp"
#include "modules/latency_probe.hpp"
#include "modules/sim_time.hpp"
#include "modules/stat_directory.hpp"
#include "platform/functional/frame_state.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_support.hpp"
#include "platform/machines/ullner_peripheral/host.hpp"
#include "platform/machines/ullner_peripheral/peripheral.hpp"

namespace rtsim::platform {

class UllnerPeripheral final : public Machine {
 public:
  using Machine::Machine;
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
};

namespace {
/// The module tree: the host and its peripheral (their names and their parameters' paths).
constexpr const char* kHost = "host";
constexpr const char* kPeripheral = "peripheral";
}  // namespace

void UllnerPeripheral::declare_params(params::ParamRegistry& r) const {
  // Its twin searches with the peripheral's own grid (peripheral.grid.*) and Ullner's quad
  // kernel, and holds polygons only: no render.accel, render.grid, render.shells,
  // render.polygon_kernel or bezier parameter is read.
  declare_common_params(
      r, {.accel = false, .shells = false, .polygon_kernel = false, .bezier = false});
  // The module tree: the host and its peripheral, each declaring its own.
  ullner::Host::declare_params(modules::ParamDecls(r, kHost));
  ullner::Peripheral::declare_params(modules::ParamDecls(r, kPeripheral));
}

FunctionalTwin UllnerPeripheral::make_twin(scenes::Scene& scene,
                                           const params::ParamRegistry& r) const {
  // The peripheral holds convex quadrilaterals only (seed 000 L267): polygons are converted
  // into convex quads and triangles-as-quads; anything else cannot be loaded.
  require_polygons(name(), scene);
  const ullner::PeripheralSettings pc =
      ullner::Peripheral::read_search_settings(modules::ModuleParams(r, kPeripheral));
  auto settings = functional::read_render_settings(r);
  settings.polygon_kernel = functional::PolygonKernel::UllnerQuad;
  settings.accel =
      pc.grid_divisions > 0 ? functional::AccelKind::Grid : functional::AccelKind::None;
  settings.grid_divisions = pc.grid_divisions;
  settings.dda_as_printed = pc.dda_as_printed;
  FunctionalTwin twin = make_functional_twin(scene, settings);
  if (twin.geometry->shapes.size() > pc.memory_polygons)
    throw InputError(scene.name, 0,
                     "the scene needs " + std::to_string(twin.geometry->shapes.size()) +
                         " quadrilaterals but the parameter memories hold " +
                         std::to_string(pc.memory_polygons) + " (" + pc.memory_polygons_name + ")");
  return twin;
}

RunResult UllnerPeripheral::run(scenes::Scene& scene, FunctionalTwin& twin,
                                const params::ParamRegistry& r, const RunOptions& opts) const {
  MachineRun run(name(), scene, twin, r, opts);
  ullner::PeripheralSettings pc =
      ullner::Peripheral::read_settings(modules::ModuleParams(r, kPeripheral));
  const std::uint64_t quads = twin.geometry->shapes.size();
  pc.modelling_space = twin.geometry->scene_bounds;
  if (!scene.modelling_space.empty()) pc.modelling_space.extend(scene.modelling_space);

  tasks::ShadeTask shade(scene, twin.settings.shade);
  // One journey per ray from the host putting it into the ray queue to task 2 taking its
  // answer (ray_latency_s's window); the peripheral names its stages first, as a ray meets them.
  modules::LatencyProbe& probe = run.probe();
  // A ray meets the host's ray link first (the probe lists stages in the order they are named).
  const std::string ray_link = std::string(kHost) + "." + ullner::Host::kRayLink;
  probe.stage(ray_link);
  // The peripheral searches its own memories; the twin's tracer only checks afterwards.
  ullner::Peripheral peripheral(kPeripheral, run, shade, pc);
  inject_faults(name(), opts.faults, {&peripheral.parameters});
  const ullner::HostAttachment attached{
      .ray_queue = peripheral.rays.fifo,
      .ray_link_name = ray_link,
      .ray_link_params = ray_link,
      .lighting = {.unit_name = std::string(kPeripheral) + ".lighting",
                   .enabled = pc.lighting,
                   .interval = pc.intersect_interval,
                   .adder_stages = pc.adder_stages,
                   .rsqrt_stages = pc.rsqrt_stages}};
  ullner::Host host(kHost, run, attached);
  host.load_out.bind(peripheral.parameters.socket);
  host.ray_out.bind(peripheral.rays.socket);
  peripheral.result_out.bind(host.results.socket);
  run.simulate();

  const sc_core::sc_time frame_time = host.frame_time();
  // Utilisation over time and queue occupancy over the frame (after the scene load).
  run.stats_over(host.load_time(), frame_time);
  nlohmann::ordered_json& res = run.machine_stats();
  // What the hardware did: every polygon address fed to the pipe is an intersection.
  res["intersection_tests"] = peripheral.pipeline().issued();

  const ullner::Peripheral::Served& served = peripheral.served();
  const double rays = static_cast<double>(std::max<std::uint64_t>(served.rays.value(), 1));
  const double issued = static_cast<double>(peripheral.pipeline().issued());
  const double extent = functional::scene_extent(pc.modelling_space);
  // The grid auxiliary processor's walk (a class of one; none with brute force).
  const modules::StatDirectory& stats = modules::StatDirectory::instance();
  const std::string aux = std::string(kPeripheral) + ".aux";
  res["peripheral"] = {
      {"polygons", quads},
      {"intersect_interval_s",
       issued > 0 ? peripheral.pipeline().busy().to_seconds() / issued : 0.0},
      {"pipeline_stages", pc.pipeline_stages},
      {"pipeline_latency_s", peripheral.pipeline().latency().to_seconds()},
      {"time_per_ray_s", served.service.value().to_seconds() / rays},
      {"tests_per_ray", issued / rays},
      {"dda_steps_per_ray", static_cast<double>(stats.count_over(aux, "dda_steps")) / rays},
      {"subvolumes_visited_per_ray",
       static_cast<double>(stats.count_over(aux, "subvolumes_visited")) / rays},
      {"mean_ray_travel", served.primary_hits.value() > 0
                              ? served.primary_travel.value() /
                                    static_cast<double>(served.primary_hits.value()) / extent
                              : 0.0},
      {"load_time_s", host.load_time().to_seconds()},
      {"grid_divisions", pc.grid_divisions}};
  using modules::StatUnit;
  run.machine_units() = {{"intersection_tests", StatUnit::count},
                         {"peripheral.*_s", StatUnit::seconds},
                         // A share of the modelling space's extent.
                         {"peripheral.mean_ray_travel", StatUnit::ratio},
                         // Polygons, stages, divisions and the means per ray.
                         {"peripheral.*", StatUnit::count}};
  return run.finish(host.latency(), {&peripheral.parameters});
}

namespace {

const RegisterMachine<UllnerPeripheral> kRegistered(
    {.name = "ullner-peripheral",
     .description =
         "Ullner's ray tracing peripheral with host, queues, 20 parameter memories, the "
         "intersection pipeline, lighting extension and optional grid auxiliary processor "
         "(seed 000 §2.3)",
     .sample_scene = "builtin:ullner-cubes",
     .test_runs = {"--scene builtin:ullner-cubes",
                   "--scene builtin:ullner-random-1000 -p peripheral.grid.divisions=11"},
     .benchmark_runs = {"--scene builtin:ullner-cubes", "--scene builtin:ullner-random-1000",
                        "--scene builtin:ullner-sheets-1000"},
     // The first machine of the thesis, and the simplest: what `rtsim run` runs unless told.
     .default_machine = true});

}  // namespace
}  // namespace rtsim::platform
