#include "platform/machines/ullner_peripheral.hpp"

#include <chrono>
#include <systemc>

#include "common/input_error.hpp"
#include "modules/latency_probe.hpp"
#include "modules/sim_time.hpp"
#include "modules/stats_registry.hpp"
#include "platform/functional/frame_state.hpp"
#include "platform/machines/machine_support.hpp"
#include "platform/machines/ullner/host.hpp"
#include "platform/machines/ullner/peripheral.hpp"
#include "platform/processor_params.hpp"

namespace rtsim::platform {

using params::ParamKind;
using ullner::HostConfig;
using ullner::PeripheralConfig;

namespace {

PeripheralConfig read_peripheral(const params::ParamRegistry& r) {
  PeripheralConfig c;
  c.intersect_interval = modules::from_ps(r.get_time_ps("peripheral.intersect_interval"));
  c.adder_stages = static_cast<unsigned>(r.get_int("peripheral.adder_stages"));
  c.pipeline_stages = PeripheralConfig::stages_for_adder(c.adder_stages);
  c.fetch_stages = static_cast<unsigned>(r.get_int("peripheral.fetch_stages"));
  c.select_stages = static_cast<unsigned>(r.get_int("peripheral.select_stages"));
  c.ray_queue_depth = static_cast<std::size_t>(r.get_int("peripheral.ray_queue_depth"));
  c.result_queue_depth = static_cast<std::size_t>(r.get_int("host.result_queue_depth"));
  c.shadow_early_exit = r.get_bool("peripheral.shadow_early_exit");
  c.grid_divisions = static_cast<int>(r.get_int("peripheral.grid.divisions"));
  c.step_time = modules::from_ps(r.get_time_ps("peripheral.grid.step_time"));
  c.indirection_stages = static_cast<unsigned>(r.get_int("peripheral.grid.indirection_stages"));
  c.lighting = r.get_bool("peripheral.lighting.enabled");
  c.rsqrt_stages = static_cast<unsigned>(r.get_int("peripheral.lighting.rsqrt_stages"));
  c.load_word_time = modules::from_ps(r.get_time_ps("peripheral.memory.load_word_time"));
  c.memory_polygons = static_cast<std::uint64_t>(r.get_int("peripheral.memory.polygons"));
  return c;
}

}  // namespace

void UllnerPeripheral::declare_params(params::ParamRegistry& r) const {
  // Its twin searches with the peripheral's own grid (peripheral.grid.*) and Ullner's quad
  // kernel, and holds polygons only: no render.accel, render.grid, render.shells,
  // render.polygon_kernel or bezier parameter is read.
  declare_common_params(
      r, {.accel = false, .shells = false, .polygon_kernel = false, .bezier = false});
  declare_processor_params(
      r, "host",
      {.clock = "5 MHz",
       .fp_add = 6,
       .fp_mul = 8,
       .fp_div = 20,
       .fp_sqrt = 60,
       .mem_word = 2,
       .instruction = 2,
       .source = "assumption: the thesis gives no host costs (seed 000 L476); a VAX-11/780-class "
                 "\"medium-sized host\" (L462) with floating-point accelerator"});
  r.declare({.name = "host.result_queue_depth",
             .kind = ParamKind::kInt,
             .default_value = "16",
             .min = "1",
             .max = "1000000",
             .unit = "results",
             .description = "Depth of the result queue from the peripheral to the host",
             .source = "assumption: queue depths are not given (seed 000 L476)"});
  r.declare({.name = "peripheral.intersect_interval",
             .kind = ParamKind::kTime,
             .default_value = "333.333 ns",
             .min = "1 ps",
             .description = "Issue interval (= stage time) of the intersection pipeline: one "
                            "ray/polygon intersection per interval",
             .source = "seed 000 L584, L588 (three results every microsecond)"});
  r.declare({.name = "peripheral.adder_stages",
             .kind = ParamKind::kInt,
             .default_value = "1",
             .min = "1",
             .max = "3",
             .unit = "stages",
             .description = "Pipeline stages of one floating-point addition (1 or 3); sets the "
                            "physical depth 17 or 33 and the latency 5.6 or 11 us",
             .source = "seed 000 L572-L578 (Fig. 2-17), L588"});
  r.declare({.name = "peripheral.fetch_stages",
             .kind = ParamKind::kInt,
             .default_value = "1",
             .min = "0",
             .max = "16",
             .unit = "stages",
             .description = "Stages of polygon fetch from the 20 parameter memories",
             .source = "assumption: one memory cycle reads a whole polygon (seed 000 L544)"});
  r.declare({.name = "peripheral.select_stages",
             .kind = ParamKind::kInt,
             .default_value = "1",
             .min = "0",
             .max = "16",
             .unit = "stages",
             .description = "Stages of the closest-intersection selection (Fig. 2-11 stage 3)",
             .source = "assumption: one compare-and-keep stage (seed 000 L484)"});
  r.declare({.name = "peripheral.ray_queue_depth",
             .kind = ParamKind::kInt,
             .default_value = "16",
             .min = "1",
             .max = "1000000",
             .unit = "rays",
             .description = "Depth of the ray queue from the host to the peripheral",
             .source = "assumption: queue depths are not given (seed 000 L476)"});
  r.declare({.name = "peripheral.shadow_early_exit",
             .kind = ParamKind::kBool,
             .default_value = "false",
             .description = "Brute force: stop streaming polygons at a shadow ray's first hit",
             .source = "assumption: the thesis does not say how the shadow-ray saving is "
                       "realised without subdivision (seed 000 L472; note §7.6)"});
  r.declare({.name = "peripheral.grid.divisions",
             .kind = ParamKind::kInt,
             .default_value = "0",
             .min = "0",
             .max = "1024",
             .unit = "per axis",
             .description = "Subvolumes per axis of the grid auxiliary processor; 0 = none "
                            "(brute force)",
             .source = "seed 000 L592-L606 (optimum 11 for 1000 polygons, L654)"});
  r.declare({.name = "peripheral.grid.dda",
             .kind = ParamKind::kString,
             .default_value = "corrected",
             .allowed = {"corrected", "as-printed"},
             .description = "Subvolume stepping: the corrected 3-D DDA, or Appendix B exactly "
                            "as printed (wrong; for fidelity experiments)",
             .source = "seed 000 L2112-L2171; errata in note 000 §4.6"});
  r.declare({.name = "peripheral.grid.step_time",
             .kind = ParamKind::kTime,
             .default_value = "1 us",
             .min = "0 s",
             .description = "t_d: time to step to the next subvolume",
             .source = "seed 000 L654"});
  r.declare({.name = "peripheral.grid.indirection_stages",
             .kind = ParamKind::kInt,
             .default_value = "1",
             .min = "0",
             .max = "16",
             .unit = "stages",
             .description = "Extra pipeline stage(s) of the subvolume address indirection",
             .source = "seed 000 L596 (\"yet another pipeline stage\")"});
  r.declare({.name = "peripheral.lighting.enabled",
             .kind = ParamKind::kBool,
             .default_value = "true",
             .description = "Lighting extension: the host's vector arithmetic runs on the "
                            "inner-product and reciprocal-square-root devices",
             .source = "seed 000 L548-L566"});
  r.declare({.name = "peripheral.lighting.rsqrt_stages",
             .kind = ParamKind::kInt,
             .default_value = "2",
             .min = "1",
             .max = "16",
             .unit = "stages",
             .description = "Stages of the reciprocal-square-root device",
             .source = "assumption: as the square root of Fig. 2-17 (seed 000 L576)"});
  r.declare({.name = "peripheral.memory.polygons",
             .kind = ParamKind::kInt,
             .default_value = "1048576",
             .min = "1",
             .max = "100000000",
             .unit = "polygons",
             .description = "Capacity of the 20 parameter memories",
             .source = "assumption: a million polygons (seed 000 note §7.5 S7)"});
  r.declare({.name = "peripheral.memory.load_word_time",
             .kind = ParamKind::kTime,
             .default_value = "1 us",
             .min = "0 s",
             .description = "Time to load one 32-bit parameter word through the dual-ported "
                            "load path (before the frame; not part of the frame time)",
             .source = "assumption: \"the port need not be fast\" (seed 000 L544)"});
}

FunctionalTwin UllnerPeripheral::make_twin(scenes::Scene& scene,
                                           const params::ParamRegistry& r) const {
  // The peripheral holds convex quadrilaterals only (seed 000 L267): polygons are converted
  // into convex quads and triangles-as-quads; anything else cannot be loaded.
  std::size_t other = 0;
  std::uint32_t first_line = 0;
  for (const auto& p : scene.primitives) {
    if (p.kind == scenes::PrimitiveKind::Polygon) continue;
    if (other++ == 0) first_line = p.source_line;
  }
  if (other > 0)
    throw InputError(scene.name, first_line,
                     "ullner-peripheral intersects polygons only (convex quadrilaterals, seed "
                     "000 L267); this scene has " +
                         std::to_string(other) +
                         " sphere/cone/patch primitive(s). Use a polygon scene or another "
                         "machine (`rtsim list machines`)");
  if (const auto a = r.get_int("peripheral.adder_stages"); a != 1 && a != 3)
    throw InputError(r.where_set("peripheral.adder_stages"), 0,
                     "peripheral.adder_stages must be 1 or 3 (Fig. 2-17, seed 000 L572-L578), "
                     "got " +
                         std::to_string(a));
  auto settings = functional::read_render_settings(r);
  settings.polygon_kernel = functional::PolygonKernel::UllnerQuad;
  const int n = static_cast<int>(r.get_int("peripheral.grid.divisions"));
  settings.accel = n > 0 ? functional::AccelKind::Grid : functional::AccelKind::None;
  settings.grid_divisions = n;
  settings.dda_as_printed = r.get_string("peripheral.grid.dda") == "as-printed";
  FunctionalTwin twin = make_functional_twin(scene, settings);
  const auto capacity = static_cast<std::size_t>(r.get_int("peripheral.memory.polygons"));
  if (twin.geometry->shapes.size() > capacity)
    throw InputError(scene.name, 0,
                     "the scene needs " + std::to_string(twin.geometry->shapes.size()) +
                         " quadrilaterals but the parameter memories hold " +
                         std::to_string(capacity) + " (peripheral.memory.polygons)");
  return twin;
}

RunResult UllnerPeripheral::run(scenes::Scene& scene, FunctionalTwin& twin,
                                const params::ParamRegistry& r, const RunOptions& opts) const {
  const auto start = std::chrono::steady_clock::now();
  const int w = opts.width > 0 ? opts.width : scene.camera.width;
  const int h = opts.height > 0 ? opts.height : scene.camera.height;
  functional::FrameState frame(w, h, twin.settings.spp, opts.aov_id, opts.aov_depth);
  PeripheralConfig pc = read_peripheral(r);
  HostConfig hc;
  hc.timing = read_processor_timing(r, "host");
  const std::uint64_t quads = twin.geometry->shapes.size();
  pc.modelling_space = twin.geometry->scene_bounds;
  if (!scene.modelling_space.empty()) pc.modelling_space.extend(scene.modelling_space);

  begin_simulation(r);
  MachineTrace trace(opts);
  tasks::ShadeTask shade(scene, twin.settings.shade);
  // One journey per ray from the host putting it into the ray queue to task 2 taking its
  // answer (ray_latency_s's window); the peripheral names its stages first, as a ray meets them.
  modules::LatencyProbe probe(opts.latency_probe);
  // The peripheral searches its own memories; the twin's tracer only checks afterwards.
  ullner::Peripheral peripheral("peripheral", *twin.geometry, scene, twin.settings, shade, quads,
                                pc, frame.counters(), trace, probe);
  inject_faults(name(), opts.faults, {&peripheral.parameters});
  ullner::Host host("host", scene, twin.settings.shade, frame, peripheral.rays.fifo, hc, pc, opts,
                    trace, *twin.geometry, probe);
  host.load_out.bind(peripheral.parameters.socket);
  host.ray_out.bind(peripheral.rays.socket);
  peripheral.result_out.bind(host.results.socket);
  sc_core::sc_start();

  const sc_core::sc_time frame_time = host.frame_time();
  RunResult res;
  res.simulated_time_s = frame_time.to_seconds();
  // Utilisation over time and queue occupancy over the frame (after the scene load).
  modules::StatsRegistry stats(host.load_time(), host.load_time() + frame_time);
  auto& hs = stats.busy_module("host", host.busy(), host.timeline());
  hs.values["vision_rays"] = static_cast<double>(host.vision_rays());
  hs.values["results_processed"] = static_cast<double>(host.results_processed());
  hs.values["backlog_peak"] = static_cast<double>(host.backlog_peak());
  stats.queue("peripheral.ray_queue", peripheral.rays.fifo.occupancy(), pc.ray_queue_depth);
  stats.queue("host.result_queue", host.results.fifo.occupancy(), pc.result_queue_depth);
  auto& ps = stats.busy_module("peripheral.pipeline", peripheral.pipeline().busy(),
                               peripheral.pipeline().timeline());
  ps.values["intersections"] = static_cast<double>(peripheral.pipeline().issued());
  ps.values["stages"] = pc.pipeline_stages;
  auto& ls = stats.busy_module("peripheral.lighting", host.lighting_unit().busy(),
                               host.lighting_unit().timeline());
  ls.values["inner_products"] = static_cast<double>(host.lighting_unit().issued());
  if (pc.grid_divisions > 0) {
    auto& as =
        stats.busy_module("peripheral.aux", peripheral.aux_busy(), peripheral.aux_timeline());
    as.values["dda_steps"] = static_cast<double>(peripheral.dda_steps());
    as.values["subvolumes_visited"] = static_cast<double>(peripheral.subvolumes_visited());
  }
  auto& ms = stats.busy_module("peripheral.parameter_memories", peripheral.parameters.read_busy(),
                               peripheral.parameters.read_timeline());
  ms.values["polygons"] = static_cast<double>(quads);
  ms.values["words_loaded"] = static_cast<double>(peripheral.parameters.words_written());
  ms.values["lines_read"] = static_cast<double>(peripheral.parameters.lines_read());
  res.stats["modules"] = stats.to_json(frame_time);
  res.stats["ray_latency_s"] = host.latency().to_json();
  if (probe.enabled()) res.stats["latency_probe"] = probe.to_json();
  if (!opts.faults.empty()) res.stats["faults"] = faults_json({&peripheral.parameters});
  // What the hardware did: every polygon address fed to the pipe is an intersection.
  res.stats["intersection_tests"] = peripheral.pipeline().issued();

  const double rays = static_cast<double>(std::max<std::uint64_t>(peripheral.rays_served(), 1));
  const double issued = static_cast<double>(peripheral.pipeline().issued());
  const double extent = functional::scene_extent(pc.modelling_space);
  res.stats["peripheral"] = {
      {"polygons", quads},
      {"intersect_interval_s",
       issued > 0 ? peripheral.pipeline().busy().to_seconds() / issued : 0.0},
      {"pipeline_stages", pc.pipeline_stages},
      {"pipeline_latency_s", peripheral.pipeline().latency().to_seconds()},
      {"time_per_ray_s", peripheral.service_time_total().to_seconds() / rays},
      {"tests_per_ray", issued / rays},
      {"dda_steps_per_ray", static_cast<double>(peripheral.dda_steps()) / rays},
      {"subvolumes_visited_per_ray", static_cast<double>(peripheral.subvolumes_visited()) / rays},
      {"mean_ray_travel", peripheral.primary_hits() > 0
                              ? peripheral.primary_travel_sum() /
                                    static_cast<double>(peripheral.primary_hits()) / extent
                              : 0.0},
      {"load_time_s", host.load_time().to_seconds()},
      {"grid_divisions", pc.grid_divisions}};
  if (trace.on()) res.stats["trace"] = trace.finish(stats);
  res.image =
      frame.finish(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return res;
}

}  // namespace rtsim::platform
