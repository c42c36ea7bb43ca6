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
#include "modules/token_ring.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_support.hpp"
#include "platform/machines/pxpl5_raytrace/camera_path.hpp"
#include "platform/machines/pxpl5_raytrace/functional_regions.hpp"
#include "platform/machines/pxpl5_raytrace/nodes.hpp"
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

[[noreturn]] void bad_param(const params::ParamRegistry& r, const std::string& name,
                            const std::string& what) {
  throw InputError(name + " (set at " + r.where_set(name) + ")", 0, "pxpl5-raytrace: " + what);
}

bool power_of_two(long v) { return v > 0 && (v & (v - 1)) == 0; }

/// The layout a run's parameters give (its size is the run's), with the sampling rule checked.
pxpl5::Layout read_layout(const params::ParamRegistry& r) {
  using namespace pxpl5;
  Layout lay;
  lay.casters = static_cast<int>(r.get_int("caster_count"));
  lay.compositors = static_cast<int>(r.get_int("compositor_count"));
  lay.band_rows = static_cast<int>(r.get_int("compositor.band_rows"));
  lay.scheme = r.get_string("assign.scheme") == "rows" ? Scheme::kRows : Scheme::kSquares;
  lay.square = static_cast<int>(r.get_int("assign.square"));
  lay.rule.finest = static_cast<int>(r.get_int("sampling.finest"));
  lay.rule.start = static_cast<int>(r.get_int("sampling.start"));
  if (lay.rule.start == 0) lay.rule.start = lay.rule.finest;
  lay.rule.threshold = r.get_double("sampling.threshold");
  lay.rule.object_edges = r.get_bool("sampling.object_edges");
  lay.rule.subdivision = r.get_string("sampling.subdivision") == "conventional"
                             ? tasks::Subdivision::kConventional
                             : tasks::Subdivision::kPartial;
  lay.update_period = 100 / static_cast<int>(std::stol(r.get_string("update.fraction")));
  const auto square = static_cast<long>(lay.square);
  if (!power_of_two(lay.rule.finest))
    bad_param(r, "sampling.finest",
              "the pixels between rays must be a power of two (1, 2, 4, 8, ...)");
  if (lay.scheme == Scheme::kRows) {
    lay.rule.start = lay.rule.finest;  // rows preclude adaptive sampling (L352)
  } else {
    if (square % lay.rule.finest != 0)
      bad_param(r, "sampling.finest",
                "a square of assign.square = " + std::to_string(square) +
                    " pixels must hold a whole number of lattice steps of sampling.finest = " +
                    std::to_string(lay.rule.finest));
    if (lay.rule.adaptive()) {
      if (!power_of_two(lay.rule.start))
        bad_param(r, "sampling.start", "the pixels between rays must be a power of two");
      if (square % lay.rule.start != 0)
        bad_param(r, "sampling.start",
                  "adaptive squares of assign.square = " + std::to_string(square) +
                      " pixels are cut into cells of sampling.start = " +
                      std::to_string(lay.rule.start) + ": it must divide the square");
      if (lay.update_period > 1)
        bad_param(r, "update.fraction",
                  "partial updating casts a fixed share of the lattice each frame, and adaptive "
                  "subdivision needs every corner of a cell in the same frame: use one of them "
                  "(sampling.start = sampling.finest for partial updating)");
    }
  }
  if (lay.rule.start < lay.rule.finest)
    bad_param(r, "sampling.start",
              "rays start at most as close as they end: sampling.start (" +
                  std::to_string(lay.rule.start) + ") must be at least sampling.finest (" +
                  std::to_string(lay.rule.finest) + ")");
  return lay;
}

/// Whether the image is the plain functional render's: every pixel cast every frame.
bool every_pixel(const pxpl5::Layout& lay) {
  return lay.rule.finest == 1 && !lay.rule.adaptive() && lay.update_period == 1;
}

}  // namespace

void Pxpl5Raytrace::declare_params(params::ParamRegistry& r) const {
  // The ray casters run the ordinary software ray tracer on their copy of the scene: every
  // render parameter is read.
  declare_common_params(r, {});
  const modules::ParamDecls top(r, "", false);
  top.count("caster_count", "16", "1", "1024", "GPs",
            "Ray-caster GPs (i860s with the scene replicated)",
            "seed 004 L369: Fig. 9's system has 21 GPs, 4 of them compositors, one master");
  top.count("compositor_count", "4", "1", "256", "GPs",
            "Compositor GPs, each owning every compositor_count-th band of rows",
            "seed 004 L369 (4 in Fig. 9; 8 typical, L310)");
  top.count("frames", "1", "1", "100000", "frames",
            "Frames rendered; the camera turns between them (camera.spin) and the image is the "
            "last frame's",
            "assumption: a camera path for frame rates (the issue's multi-frame runs)");
  top.declare({.name = "camera.spin",
               .kind = params::ParamKind::kDouble,
               .default_value = "0",
               .min = "-360",
               .max = "360",
               .unit = "degrees",
               .description = "Turn of the eye about the vertical axis (the view's up through "
                              "the point looked at) from one frame to the next",
               .source = "assumption: a simple camera path"});
  const modules::ParamDecls assign(r, "assign", false);
  assign.declare({.name = "scheme",
                  .kind = params::ParamKind::kString,
                  .default_value = "squares",
                  .allowed = {"rows", "squares"},
                  .description = "Work the master GP hands out: sample rows, in order from the top "
                                 "(L352), or square regions (L360)",
                  .source = "seed 004 L352, L360"});
  assign.count(
      "square", "64", "1", "4096", "pixels",
      "Side of a square region in pixels (VOL2: 64, 1/80 of 640 x 512). With adaptive sampling "
      "a square also casts its right and bottom edges, shared with its neighbours: 65 x "
      "65 pixels, \"two edges of replicated rays\"",
      "seed 004 L360");
  assign.declare({.name = "order",
                  .kind = params::ParamKind::kString,
                  .default_value = "cost",
                  .allowed = {"screen", "cost"},
                  .description = "Order the regions are handed out in: screen order, or "
                                 "descending cost in the previous frame (0th-order prediction)",
                  .source = "seed 004 L360"});
  top.declare({.name = "bypass",
               .kind = params::ParamKind::kString,
               .default_value = "none",
               .allowed = {"none", "all", "all-but-master", "casters-and-master"},
               .description =
                   "By-pass code: nodes that keep their message passing and drop their compute, "
                   "to measure each part's greatest rate: all (the pipeline's, Fig. 4), "
                   "all-but-master (the master GP's, Fig. 5), casters-and-master (the "
                   "compositing, resampling and display back end's, Fig. 6). A by-passed caster "
                   "sends samples of no radiance: the image is black",
               .source = "seed 004 L333-L350"});
  top.declare({.name = "camera.distance",
               .kind = params::ParamKind::kDouble,
               .default_value = "1",
               .min = "0.01",
               .max = "100",
               .unit = "x",
               .description = "The eye's distance from the point it looks at, times the scene's "
                              "(larger: the scene covers less of the screen)",
               .source = "seed 004 L369: Fig. 9 varies screen coverage by viewing distance"});
  const modules::ParamDecls sampling(r, "sampling", false);
  sampling.count("finest", "1", "1", "64", "pixels",
                 "Pixels between rays at the finest level, a power of two: 1 casts a ray per "
                 "pixel (the image of every other machine); VOL2 ends at one ray per 4 x 4; the "
                 "renderers resample to display pixels",
                 "seed 004 L369 (4; rows every 8 x 8 or 4 x 4)");
  sampling.count("start", "0", "0", "256", "pixels",
                 "Pixels between rays before adaptive refinement, squares only (rows cannot "
                 "adapt, L352): larger than sampling.finest turns adaptive sampling on; 0 is "
                 "sampling.finest (no refinement)",
                 "seed 004 L369 (16: one ray per 16 x 16 refined to 4 x 4)");
  sampling.declare({.name = "threshold",
                    .kind = params::ParamKind::kDouble,
                    .default_value = "0.05",
                    .min = "0",
                    .max = "1000",
                    .unit = "radiance",
                    .description = "Colour difference between two corner samples (any channel) "
                                   "that refines a square",
                    .source = "seed 004 L362 (a user-defined threshold; 0.05 is about 13 of 255 "
                              "display levels: an assumption)"});
  sampling.declare({.name = "subdivision",
                    .kind = params::ParamKind::kString,
                    .default_value = "partial",
                    .allowed = {"partial", "conventional"},
                    .description = "Refinement of a square whose corners differ: new samples "
                                   "only between differing pairs and the centre (partial), or "
                                   "all five (conventional)",
                    .source = "seed 004 L362, Fig. 8 (L358)"});
  sampling.declare({.name = "object_edges",
                    .kind = params::ParamKind::kBool,
                    .default_value = "true",
                    .description = "Corner samples that hit different primitives differ whatever "
                                   "their colour (edges and intersection curves are refined)",
                    .source = "seed 004 L364 (isosurface encoding; here the primitive hit)"});
  r.declare({.name = "update.fraction",
             .kind = params::ParamKind::kString,
             .default_value = "100",
             .allowed = {"100", "50", "25"},
             .unit = "percent",
             .description = "Partial updating: the share of lattice positions cast each frame, "
                            "on a regular grid (a modulus of the position with the frame "
                            "number); the compositors keep the rest from earlier frames. The "
                            "first frame casts all",
             .source = "seed 004 L373-L379"});
  const modules::ParamDecls gp(r, "gp", false);
  modules::declare_processor_params(
      gp, {.clock = "40 MHz",
           .fp_add = 1,
           .fp_mul = 1,
           .fp_div = 20,
           .fp_sqrt = 20,
           .mem_word = 1,
           .instruction = 1,
           .source = "assumption: the seed names the i860 only (L282); a 40 MHz i860 XR issuing "
                     "an add or multiply a cycle, divides and square roots by Newton "
                     "iterations"});
  gp.declare({.name = "memory",
              .kind = params::ParamKind::kDataSize,
              .default_value = "8 MiB",
              .min = "1 B",
              .description = "Local memory of each GP; a ray caster must hold the whole scene",
              .source = "seed 004 L282"});
  gp.count("scene_bytes_per_primitive", "256", "1", "1000000", "bytes",
           "Memory a ray caster's copy of the scene takes per primitive (its kernel's "
           "parameters, material and its share of the acceleration structure)",
           "assumption: a triangle's or sphere's precomputed kernel and its grid references");
  r.declare({.name = "master.assign_time",
             .kind = params::ParamKind::kTime,
             .default_value = "20 us",
             .min = "0 s",
             .max = "1 s",
             .description = "Master GP time to take a request and hand out a region",
             .source = "assumption: the seed gives no master GP costs (Fig. 5, L347, measures "
                       "its limit without numbers); 800 i860 cycles"});
  r.declare({.name = "compositor.sample_time",
             .kind = params::ParamKind::kTime,
             .default_value = "500 ns",
             .min = "0 s",
             .max = "1 s",
             .description = "Compositor GP time per sample received (store it in its band)",
             .source = "assumption: 20 i860 cycles a sample"});
  r.declare({.name = "compositor.band_rows",
             .kind = params::ParamKind::kInt,
             .default_value = "64",
             .min = "1",
             .max = "16384",
             .unit = "rows",
             .description = "Rows of one band; band b belongs to compositor b mod compositor_count",
             .source = "seed 004 L310 (640 x 64 bands)"});
  r.declare({.name = "renderer.tile_time",
             .kind = params::ParamKind::kTime,
             .default_value = "1 ms",
             .min = "0 s",
             .max = "1 s",
             .description = "SIMD renderer time to resample its 128 x 128 tile (all pixels at "
                            "once, whatever their content)",
             .source = "assumption: the seed gives none (Fig. 6, L350, without numbers)"});
  r.declare({.name = "frame_buffer.pixel_time",
             .kind = params::ParamKind::kTime,
             .default_value = "10 ns",
             .min = "0 s",
             .max = "1 s",
             .description = "Frame buffer time to write one display pixel",
             .source = "assumption"});
  const modules::ParamDecls wire(r, "wire", false);
  wire.count("control_bytes", "16", "1", "65536", "bytes",
             "Bytes of a control message on the ring (frame start, request, assignment, frame "
             "done)",
             "assumption: the seed gives no message formats (note 004 A)");
  wire.count("sample_bytes", "8", "1", "65536", "bytes",
             "Bytes of one sample on the ring (samples and band messages)",
             "assumption: 24-bit colour, depth and flags");
  wire.count("pixel_bytes", "4", "1", "65536", "bytes", "Bytes of one display pixel on the ring",
             "assumption: 24-bit colour and a byte of alpha");
  wire.count("header_bytes", "16", "0", "65536", "bytes",
             "Bytes of header on a samples, band or pixels message", "assumption");
  modules::TokenRing::declare_params(
      modules::ParamDecls(r, "ring", false),
      {.bandwidth = "5 Gbit/s",
       .bandwidth_source = "seed 004 L284",
       .hop_latency = "50 ns",
       .max_packet_bytes = "1024",
       .header_bytes = "8",
       .service = "exhaustive",
       .source = "assumption: the seed gives only the bandwidth (note 004 A; Fuchs et al., "
                 "SIGGRAPH 89, would give the rest)"});
  r.declare({.name = "fault.corrupt_samples",
             .kind = params::ParamKind::kInt,
             .default_value = "0",
             .min = "0",
             .max = "1000000000000",
             .unit = "messages",
             .description = "A fault for tests: the samples message with this number (counted "
                            "over all casters from 1) has its first sample changed on the ring; "
                            "0 changes none",
             .source = "assumption: fault injection, not a machine property"});
}

FunctionalTwin Pxpl5Raytrace::make_twin(scenes::Scene& scene,
                                        const params::ParamRegistry& r) const {
  const pxpl5::Layout layout = read_layout(r);  // bad sampling settings are bad input
  // The image is the last frame's: the scene's camera, moved to camera.distance, is that
  // frame's; the earlier ones are turned back from it (run()).
  pxpl5::move_eye(scene.camera, r.get_double("camera.distance"));
  FunctionalTwin twin = make_functional_twin(scene, functional::read_render_settings(r));
  if (!every_pixel(layout)) {
    const int frames = static_cast<int>(r.get_int("frames"));
    const double spin = r.get_double("camera.spin");
    twin.render = [layout, frames, spin](const scenes::Scene& s, const Tracer& tracer,
                                         const functional::RenderOptions& opts) {
      return pxpl5::sampled_render(s, tracer, opts, layout, frames, spin);
    };
  }
  // A ray caster holds the whole scene (L310): it must fit in a GP's memory.
  const double bytes = static_cast<double>(twin.geometry->shapes.size()) *
                       static_cast<double>(r.get_int("gp.scene_bytes_per_primitive"));
  const double memory = r.get_data_size_bits("gp.memory") / 8.0;
  if (bytes > memory)
    throw InputError(scene.name, 0,
                     "pxpl5-raytrace: the scene's " + std::to_string(twin.geometry->shapes.size()) +
                         " primitives take " + std::to_string(static_cast<long long>(bytes)) +
                         " bytes on a ray caster (gp.scene_bytes_per_primitive) but a GP has " +
                         std::to_string(static_cast<long long>(memory)) +
                         " (gp.memory): the scene cannot be replicated, and splitting it into "
                         "slabs (L310) is not modelled");
  return twin;
}

int Pxpl5Raytrace::sample_units(const params::ParamRegistry& r, int width, int height) const {
  pxpl5::Layout layout = read_layout(r);
  layout.width = width;
  layout.height = height;
  return static_cast<int>(layout.regions().size());
}

RunResult Pxpl5Raytrace::run(scenes::Scene& scene, FunctionalTwin& twin,
                             const params::ParamRegistry& r, const RunOptions& opts) const {
  using namespace pxpl5;
  MachineRun run(name(), scene, twin, r, opts, /*rows_sampled=*/false);
  Context ctx;
  ctx.layout = read_layout(r);
  ctx.layout.width = run.width();
  ctx.layout.height = run.height();
  ctx.cost_order = r.get_string("assign.order") == "cost";
  ctx.frames = static_cast<int>(r.get_int("frames"));
  ctx.sizes = {.control = static_cast<std::uint64_t>(r.get_int("wire.control_bytes")),
               .sample = static_cast<std::uint64_t>(r.get_int("wire.sample_bytes")),
               .pixel = static_cast<std::uint64_t>(r.get_int("wire.pixel_bytes")),
               .header = static_cast<std::uint64_t>(r.get_int("wire.header_bytes"))};
  ctx.gp_timing = modules::read_processor_timing(modules::ModuleParams(r, "gp"));
  const double spin = r.get_double("camera.spin");
  for (int f = 0; f < ctx.frames; ++f)
    ctx.cameras.emplace_back(frame_camera(scene.camera, f, ctx.frames, spin), run.width(),
                             run.height());
  ctx.tracer = twin.tracer.get();
  ctx.scene = &scene;
  ctx.shade = twin.settings.shade;
  ctx.frame = &run.frame();
  ctx.opts = &opts;
  const std::string bypass = r.get_string("bypass");
  ctx.bypass_casters = bypass != "none";
  ctx.bypass_master = bypass == "all" || bypass == "casters-and-master";
  ctx.bypass_back_end = bypass == "all" || bypass == "all-but-master";
  ctx.corrupt_samples = static_cast<std::uint64_t>(r.get_int("fault.corrupt_samples"));
  // --latency-probe follows samples: a caster traces a region in one go, and the renderers
  // and the frame buffer work on whole tiles and frames, not on samples.
  modules::LatencyProbe& probe = run.probe();
  probe.describe("sample",
                 "from its caster beginning its region to its compositor having composited it; "
                 "the renderers and the frame buffer work on whole tiles and frames, so a "
                 "sample's journey ends at its compositor");
  ctx.probe = &probe;
  ctx.stages = {.caster = probe.stage("caster*"),
                .ring = probe.stage("ring"),
                .inbox = probe.stage("compositor*.inbox"),
                .compositor = probe.stage("compositor*")};
  if (opts.sample_every > 1) {
    // Sampled: every K-th region (in the master's order, which is screen order in a first
    // frame) in detail, the others cast functionally and handed to the compositors.
    if (ctx.frames != 1 || bypass != "none")
      throw InputError("--sample", 0,
                       "pxpl5-raytrace samples the regions of a single frame with its casters "
                       "working: set frames = 1 and bypass = none (a later frame's regions and "
                       "order depend on the frames before it in detail)");
    ctx.sample = run.sample_units(static_cast<int>(ctx.layout.regions().size()), "regions",
                                  ctx.layout.casters);
    ctx.functional_samples = cast_functionally(
        ctx, [&](int id) { return !ctx.sample->detailed_unit(id); }, !opts.sample_pilot);
  }

  const Layout& lay = ctx.layout;
  modules::TokenRing ring("ring", modules::TokenRing::read_config(modules::ModuleParams(r, "ring")),
                          static_cast<std::size_t>(lay.nodes()), kTrafficClasses);
  modules::RingChannel<Message> channel("ring_channel", ring);
  Host host("host", run.trace(), channel, ctx);
  MasterGp master("master", run.trace(), channel, ctx,
                  modules::from_ps(r.get_time_ps("master.assign_time")));
  std::vector<std::unique_ptr<RayCaster>> casters;
  for (int k = 0; k < lay.casters; ++k)
    casters.push_back(std::make_unique<RayCaster>(("caster" + std::to_string(k)).c_str(),
                                                  run.trace(), channel, ctx, k));
  std::vector<std::unique_ptr<Compositor>> compositors;
  for (int k = 0; k < lay.compositors; ++k)
    compositors.push_back(std::make_unique<Compositor>(
        ("compositor" + std::to_string(k)).c_str(), run.trace(), channel, ctx, k,
        modules::from_ps(r.get_time_ps("compositor.sample_time"))));
  std::vector<std::unique_ptr<Renderer>> renderers;
  for (int k = 0; k < lay.renderers(); ++k)
    renderers.push_back(
        std::make_unique<Renderer>(("renderer" + std::to_string(k)).c_str(), run.trace(), channel,
                                   ctx, k, modules::from_ps(r.get_time_ps("renderer.tile_time"))));
  FrameBuffer fb("frame_buffer", run.trace(), channel, ctx,
                 modules::from_ps(r.get_time_ps("frame_buffer.pixel_time")));
  inject_faults(name(), opts.faults, {});  // its answers come from the messages, not a memory
  run.simulate();

  if (host.done().size() != static_cast<std::size_t>(ctx.frames))
    throw std::runtime_error("pxpl5-raytrace: the frame buffer never had every pixel");
  const sc_core::sc_time end = host.done().back();
  run.stats_over(sc_core::SC_ZERO_TIME, end);
  nlohmann::ordered_json workload = nlohmann::ordered_json::array();
  double most = 0;
  for (const auto& c : casters) most = std::max(most, c->accounts().busy.to_seconds());
  std::uint64_t rays = 0, cast_last = 0, covered_last = 0;
  for (const auto& c : casters) {
    cast_last += c->cast_last_frame();
    covered_last += c->covered_last_frame();
    rays += c->rays();
    workload.push_back(most > 0 ? c->accounts().busy.to_seconds() / most : 0.0);
  }
  nlohmann::ordered_json frame_times = nlohmann::ordered_json::array();
  double sum = 0;
  for (std::size_t f = 0; f < host.done().size(); ++f) {
    const double t = (host.done()[f] - host.started()[f]).to_seconds();
    frame_times.push_back(t);
    sum += t;
  }
  const double last = (host.done().back() - host.started().back()).to_seconds();
  nlohmann::ordered_json& res = run.machine_stats();
  res["pxpl5"] = {
      {"casters", lay.casters},
      {"compositors", lay.compositors},
      {"renderers", lay.renderers()},
      {"ring_nodes", lay.nodes()},
      {"scheme", r.get_string("assign.scheme")},
      {"order", r.get_string("assign.order")},
      {"bypass", bypass},
      {"regions_per_frame", lay.regions().size()},
      {"lattice", {lay.lattice().nx(), lay.lattice().ny()}},
      {"sampling",
       {{"finest", lay.rule.finest},
        {"start", lay.rule.start},
        {"adaptive", lay.rule.adaptive()},
        {"update_fraction", 1.0 / lay.update_period}}},
      {"rays_per_frame", static_cast<double>(rays) / ctx.frames},
      // Fig. 9's abscissa: the share of the screen the scene covers (last frame's
      // rays on the screen that hit; adaptive squares cast more where it is).
      {"screen_coverage", cast_last > 0 ? static_cast<double>(covered_last) / cast_last : 0.0},
      {"rays_per_pixel",
       static_cast<double>(rays) / ctx.frames / (static_cast<double>(lay.width) * lay.height)},
      {"frames", ctx.frames},
      {"frame_times_s", std::move(frame_times)},
      {"frames_per_second", sum > 0 ? static_cast<double>(ctx.frames) / sum : 0.0},
      // The last frame's rate: the steady state once a previous frame's costs order the squares
      // (L360).
      {"last_frame_per_second", last > 0 ? 1.0 / last : 0.0},
      {"caster_workload", std::move(workload)},
      {"samples_messages", ctx.samples_messages}};
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
                        "--scene builtin:npp-412 -p assign.scheme=rows"}});

}  // namespace
}  // namespace rtsim::platform
