// pixelflow: PixelFlow's deferred shading (seed 004 L1-L193; note 004 "Paper 1"): identical
// nodes assigned as rasterizers and shaders (L160) on an image-composition network, a frame-
// buffer node (L93), the screen in 128 x 64 regions taken one at a time (L21), shaders taking one
// of every s regions (L23), and a frame of passes: shadow maps, a reflection map, the camera's
// image at 5 samples a pixel (L114-L128). It rasterizes rather than traces: firmware/raster/
// scan-converts, firmware/deferred/ shades.
#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <systemc>

#include "common/input_error.hpp"
#include "modules/module_params.hpp"
#include "modules/stat_directory.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_support.hpp"
#include "platform/machines/mesh_params.hpp"
#include "platform/machines/pixelflow/composition_network.hpp"
#include "platform/machines/pixelflow/frame_buffer_node.hpp"
#include "platform/machines/pixelflow/functional_passes.hpp"
#include "platform/machines/pixelflow/pass_plan.hpp"
#include "platform/machines/pixelflow/rasterizer_node.hpp"
#include "platform/machines/pixelflow/shading_node.hpp"

namespace rtsim::platform {

class Pixelflow final : public Machine {
 public:
  using Machine::Machine;
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
};

namespace {

constexpr const char* kRasterizer = "rasterizer";
constexpr const char* kShader = "shader";
constexpr const char* kNetwork = "composition";
constexpr const char* kFrameBuffer = "frame_buffer";

const modules::CountParam kRasterizers(
    {.name = "nodes.rasterizers",
     .default_value = "3",
     .min = "1",
     .max = "64",
     .unit = "nodes",
     .description = "nodes assigned as rasterizers; the primitives are divided among them",
     .source = "seed 004 L93 (the bowling configuration); L160: chosen at run time"});
const modules::CountParam kShaders(
    {.name = "nodes.shaders",
     .default_value = "12",
     .min = "1",
     .max = "256",
     .unit = "nodes",
     .description = "nodes assigned as shaders; each takes one of every s region-samples",
     .source = "seed 004 L93 (the bowling configuration); L23, L160"});

// What the image depends on: the machine's own conversion of the scene and its maps.
const modules::IntParam kMapSize({.name = "maps.size",
                                  .default_value = "512",
                                  .min = "128",
                                  .max = "4096",
                                  .description = "texels a side of the shadow and reflection maps",
                                  .source = "seed 004 L116"});
const modules::RealParam kShadowBias(
    {.name = "shading.shadow_bias",
     .default_value = "1.5",
     .min = "0",
     .max = "100",
     .unit = "texels",
     .description = "how much farther than the shadow map's depth a surface may be and still be "
                    "lit, in the map's texels at its depth (more on surfaces steep to the light)",
     .source = "assumption: the seed gives none; 1.5 texels removes self-shadowing on the "
               "bowling frame's curved pins without detaching the ball's shadow"});
const modules::RealParam kBumpScale(
    {.name = "shading.bump_scale",
     .default_value = "0.004",
     .min = "0",
     .max = "1",
     .description = "how far the scuffs' bump map tilts a pin's normal per unit of its height "
                    "field's slope",
     .source = "assumption: the seed gives the bump map (L97), not its depth"});

using pixelflow::FrameSettings;

FrameSettings read_frame_settings(const params::ParamRegistry& r,
                                  const shading::ShadeParams& shade) {
  const modules::ModuleParams p(r, "");
  FrameSettings s;
  s.mesh = read_mesh_params(r);
  s.map_size = static_cast<int>(p.get(kMapSize));
  s.shadow_bias_texels = p.get(kShadowBias);
  s.bump_scale = p.get(kBumpScale);
  s.shade = shade;
  return s;
}

}  // namespace

void Pixelflow::declare_params(params::ParamRegistry& r) const {
  // The twin reads render.spp, scene.seed, view.* and the shading model's ambient and light
  // intensity: it searches nothing (no grid, no shells) and traces no ray tree.
  declare_common_params(r, {.accel = false,
                            .shells = false,
                            .polygon_kernel = false,
                            .bezier = false,
                            .ray_tree = false});
  const modules::ParamDecls machine(r, "", /*per_instance=*/false);
  machine.add(kRasterizers);
  machine.add(kShaders);
  const modules::ParamDecls image = machine.affecting_image();
  declare_mesh_params(image);
  image.add(kMapSize);
  image.add(kShadowBias);
  image.add(kBumpScale);
  r.declare_family({.cls = kRasterizer, .count_param = kRasterizers.name()});
  pixelflow::RasterizerNode::declare_params(machine.sub(kRasterizer));
  r.declare_family({.cls = kShader, .count_param = kShaders.name()});
  pixelflow::ShadingNode::declare_params(machine.sub(kShader));
  pixelflow::CompositionNetwork::declare_params(machine.sub(kNetwork));
}

FunctionalTwin Pixelflow::make_twin(scenes::Scene& scene, const params::ParamRegistry& r) const {
  auto settings = functional::read_render_settings(r);
  settings.accel = functional::AccelKind::None;
  FunctionalTwin twin = make_functional_twin(scene, settings);
  const FrameSettings frame = read_frame_settings(r, twin.settings.shade);
  // Checked now: a scene the machine cannot hold is bad input before anything runs.
  (void)pixelflow::make_frame_setup(scene, frame, 1, 1, 1);
  twin.render = [frame](const scenes::Scene& s, const Tracer&,
                        const functional::RenderOptions& opts) {
    const auto start = std::chrono::steady_clock::now();
    const int w = opts.width > 0 ? opts.width : s.camera.width;
    const int h = opts.height > 0 ? opts.height : s.camera.height;
    const int spp = std::max(1, opts.spp);
    const auto f = pixelflow::make_frame_setup(s, frame, w, h, spp);
    const auto maps = pixelflow::render_maps(f);
    functional::FrameState state(w, h, spp, opts.aov_id, opts.aov_depth);
    pixelflow::render_camera(f, maps, state);
    return state.finish(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  };
  return twin;
}

RunResult Pixelflow::run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& r,
                         const RunOptions& opts) const {
  using namespace pixelflow;
  if (opts.sample_every > 0) throw InputError("--sample", 0, "pixelflow does not sample");
  MachineRun run(name(), scene, twin, r, opts, /*rows_sampled=*/false);
  const modules::ModuleParams top(r, "");
  const int rasterizers = static_cast<int>(top.get(kRasterizers));
  const int shaders = static_cast<int>(top.get(kShaders));
  const FrameSetup frame = make_frame_setup(scene, read_frame_settings(r, twin.settings.shade),
                                            run.width(), run.height(), run.frame().spp());
  const PassPlan plan = plan_passes(frame, rasterizers);
  const Pass& camera = *plan.camera();

  // In-flight faults on the composition network; the machine has no memory at rest to corrupt.
  std::vector<MemoryFault> at_rest = opts.faults;
  std::vector<CompositionFault> in_flight;
  for (const auto& f : take_faults(
           at_rest, [](const std::string& n) { return n == CompositionNetwork::kFaultPoint; })) {
    const std::uint64_t words =
        static_cast<std::uint64_t>(camera.region_samples()) * CompositionNetwork::kWordsPerRegion;
    if (f.word >= words)
      throw InputError(
          "--fault " + f.memory + ":" + std::to_string(f.word), 0,
          "the camera pass composites " + std::to_string(words) + " words of records (" +
              std::to_string(camera.region_samples()) + " region-samples of " +
              std::to_string(CompositionNetwork::kWordsPerRegion) + "): give a word below that");
    in_flight.push_back({f.word, f.xor_mask, false});
  }
  inject_faults(name(), at_rest, {}, {CompositionNetwork::kFaultPoint});

  // --latency-probe follows the camera pass's region-samples through the nodes.
  modules::LatencyProbe& probe = run.probe();
  probe.describe("region-sample",
                 "a camera region-sample, from the first rasterizer beginning it to the frame "
                 "buffer taking its colours");
  const ProbeStages stages{.rasterizer = probe.stage("rasterizer*"),
                           .from_rasterizer = probe.stage("composition.from_rasterizer*"),
                           .network = probe.stage(kNetwork),
                           .link = probe.stage("composition.link"),
                           .shader_in = probe.stage("shader*.in"),
                           .shader = probe.stage("shader*"),
                           .from_shader = probe.stage("composition.from_shader*"),
                           .frame_buffer_in = probe.stage("frame_buffer.in")};
  std::vector<std::unique_ptr<ShadingNode>> shader_nodes;
  for (int s = 0; s < shaders; ++s)
    shader_nodes.push_back(std::make_unique<ShadingNode>((kShader + std::to_string(s)).c_str(), run,
                                                         frame, plan, s, shaders, stages));
  FrameBufferNode fb(kFrameBuffer, run, camera.region_samples(), stages.frame_buffer_in);
  NetworkEnds ends;
  for (const auto& s : shader_nodes) {
    ends.shaders.push_back(&s->in.fifo);
    ends.tables.push_back(&s->table.in.fifo);
  }
  ends.frame_buffer = &fb.in.fifo;
  const std::size_t buffers =
      RasterizerNode::buffered_regions(modules::ModuleParams(r, std::string(kRasterizer) + "0"));
  CompositionNetwork network(kNetwork, run, plan, shaders, buffers, ends, in_flight, stages);
  std::vector<std::unique_ptr<RasterizerNode>> rasterizer_nodes;
  for (int k = 0; k < rasterizers; ++k) {
    rasterizer_nodes.push_back(std::make_unique<RasterizerNode>(
        (kRasterizer + std::to_string(k)).c_str(), run, plan, k,
        network.from_rasterizer[static_cast<std::size_t>(k)]->fifo));
    rasterizer_nodes.back()->out.bind(network.from_rasterizer[static_cast<std::size_t>(k)]->socket);
  }
  for (int s = 0; s < shaders; ++s) {
    auto& node = *shader_nodes[static_cast<std::size_t>(s)];
    network.to_shader[static_cast<std::size_t>(s)]->bind(node.in.socket);
    network.to_table[static_cast<std::size_t>(s)]->bind(node.table.in.socket);
    node.out.bind(network.from_shader[static_cast<std::size_t>(s)]->socket);
    node.feeds(network.from_shader[static_cast<std::size_t>(s)]->fifo);
  }
  network.to_frame_buffer.bind(fb.in.socket);
  run.simulate();

  const sc_core::sc_time end = fb.frame_end();
  run.stats_over(sc_core::SC_ZERO_TIME, end);

  // Each pass: when its first rasterization began and its result was in place (a map stored in
  // every table memory, the camera's last region-sample in the frame buffer), its work.
  nlohmann::ordered_json passes = nlohmann::ordered_json::object();
  sc_core::sc_time previous_done = sc_core::SC_ZERO_TIME;
  for (std::size_t pi = 0; pi < plan.passes.size(); ++pi) {
    const Pass& p = plan.passes[pi];
    sc_core::sc_time raster_busy = sc_core::SC_ZERO_TIME, raster_max = sc_core::SC_ZERO_TIME;
    std::uint64_t triangles = 0;
    sc_core::sc_time begun = end;
    for (const auto& n : rasterizer_nodes) {
      begun = std::min(begun, n->began_pass()[pi]);
      raster_busy += n->busy_by_pass()[pi];
      raster_max = std::max(raster_max, n->busy_by_pass()[pi]);
      triangles += n->triangles_by_pass()[pi];
    }
    sc_core::sc_time shade_busy = sc_core::SC_ZERO_TIME, shade_max = sc_core::SC_ZERO_TIME;
    for (const auto& n : shader_nodes) {
      shade_busy += n->busy_by_pass()[pi];
      shade_max = std::max(shade_max, n->busy_by_pass()[pi]);
    }
    // A map is in place when the last table memory has stored it; the camera's image at the end.
    std::optional<sc_core::sc_time> stored;
    for (const auto& n : shader_nodes)
      for (const auto& [index, at] : n->table.stored_at())
        if (static_cast<std::size_t>(index) == pi) stored = std::max(stored.value_or(at), at);
    const sc_core::sc_time done = stored.value_or(end);
    passes[p.name()] = {{"region_samples", p.region_samples()},
                        {"front_facing_triangles", p.setup.front_facing},
                        {"triangles_set_up", triangles},
                        {"rasterize_s", raster_busy.to_seconds()},
                        {"rasterize_busiest_s", raster_max.to_seconds()},
                        {"shade_s", shade_busy.to_seconds()},
                        {"shade_busiest_s", shade_max.to_seconds()},
                        {"network_bytes", network.bytes_by_pass()[pi]},
                        {"begin_s", begun.to_seconds()},
                        {"done_s", done.to_seconds()},
                        // The seed adds the passes' times (L158): each from the one before's end.
                        {"time_s", done.to_seconds() - previous_done.to_seconds()}};
    previous_done = done;
  }
  nlohmann::ordered_json regions_per_shader = nlohmann::ordered_json::array();
  sc_core::sc_time worst = sc_core::SC_ZERO_TIME;
  const deferred::RegionWork* worst_work = nullptr;
  for (const auto& n : shader_nodes) {
    std::uint64_t total = 0;
    for (const auto c : n->regions_by_pass()) total += c;
    regions_per_shader.push_back(total);
    if (n->worst_time() > worst) {
      worst = n->worst_time();
      worst_work = &n->worst_work();
    }
  }
  nlohmann::ordered_json& res = run.machine_stats();
  auto& pf = res["pixelflow"];
  pf["rasterizers"] = rasterizers;
  pf["shaders"] = shaders;
  pf["regions"] = camera.grid.count();
  pf["samples"] = camera.samples;
  pf["triangles"] = frame.mesh.triangles.size();
  pf["passes"] = std::move(passes);
  pf["regions_per_shader"] = std::move(regions_per_shader);
  std::uint64_t network_bytes = 0;
  for (const auto b : network.bytes_by_pass()) network_bytes += b;
  pf["network_bytes"] = network_bytes;
  if (worst_work) {
    nlohmann::ordered_json pixels = nlohmann::ordered_json::object();
    for (int f = 0; f < deferred::kShadingFunctions; ++f)
      pixels[std::string(deferred::kShadingFunctionNames[static_cast<std::size_t>(f)])] =
          worst_work->pixels[static_cast<std::size_t>(f)];
    nlohmann::ordered_json lookups = nlohmann::ordered_json::object();
    for (int l = 0; l < deferred::kLookups; ++l)
      lookups[std::string(deferred::kLookupNames[static_cast<std::size_t>(l)])] =
          worst_work->lookups[static_cast<std::size_t>(l)];
    pf["worst_region"] = {{"time_s", worst.to_seconds()},
                          {"pixels", std::move(pixels)},
                          {"lookup_pixels", std::move(lookups)}};
  }
  // The shading programs' instructions and their time at Fig. 6's (whichever model timed the
  // nodes), and the region-sample whose shading parts took longest (lookups aside).
  const ShadingCosts& costs = shader_nodes.front()->costs();
  nlohmann::ordered_json programs = nlohmann::ordered_json::object();
  for (int k = 0; k < deferred::kShadingParts; ++k) {
    const auto& mix = costs.programs().parts[static_cast<std::size_t>(k)];
    programs[std::string(deferred::kShadingPartNames[static_cast<std::size_t>(k)])] = {
        {"instructions", mix.total()}, {"time_s", costs.instruction_times().time_of(mix)}};
  }
  pf["shading_programs"] = std::move(programs);
  const ShadingNode* worst_shading = nullptr;
  for (const auto& n : shader_nodes)
    if (!worst_shading || n->worst_shading() > worst_shading->worst_shading())
      worst_shading = n.get();
  {
    const deferred::RegionWork& w = worst_shading->worst_shading_work();
    nlohmann::ordered_json pixels = nlohmann::ordered_json::object();
    for (int f = 0; f < deferred::kShadingFunctions; ++f)
      pixels[std::string(deferred::kShadingFunctionNames[static_cast<std::size_t>(f)])] =
          w.pixels[static_cast<std::size_t>(f)];
    pf["worst_shading"] = {
        {"time_s", worst_shading->worst_shading().to_seconds()},
        {"instructions", deferred::region_instructions(costs.programs(), w).total()},
        {"pixels", std::move(pixels)}};
  }
  for (const auto& f : network.faults())
    pf["faults_in_flight"].push_back(
        {{"at", kNetwork}, {"word", f.word}, {"xor_mask", f.xor_mask}, {"applied", f.applied}});
  using modules::StatUnit;
  run.machine_units() = {{"pixelflow.passes.*_s", StatUnit::seconds},
                         {"pixelflow.worst_region.time_s", StatUnit::seconds},
                         {"pixelflow.worst_shading.time_s", StatUnit::seconds},
                         {"pixelflow.shading_programs.*.time_s", StatUnit::seconds},
                         {"pixelflow.*network_bytes", StatUnit::bytes},
                         {"pixelflow.passes.network_bytes", StatUnit::bytes},
                         // Nodes, regions, samples, triangles, pixels, words.
                         {"pixelflow.*", StatUnit::count}};
  return run.finish(modules::LatencyRecorder{}, {});
}

namespace {

const RegisterMachine<Pixelflow> kRegistered(
    {.name = "pixelflow",
     .description = "PixelFlow's deferred shading: rasterizer and shader nodes on an "
                    "image-composition network, shadow and reflection map passes, 128 x 64 "
                    "regions (seed 004, Lastra et al. 1995)",
     .sample_scene = "builtin:bowling",
     .test_runs = {"--scene builtin:bowling", "--scene builtin:default -p nodes.shaders=3",
                   "--scene builtin:spd-teapot -p nodes.rasterizers=1"},
     .benchmark_runs = {"--scene builtin:bowling", "--scene builtin:default",
                        "--scene builtin:spd-teapot"},
     .report_plots = {{.object = "pixelflow",
                       .key = "passes",
                       .script = "pixelflow_passes.py",
                       .title = "PixelFlow's passes",
                       .caption = "When each pass ran, from its first rasterization to its result "
                                  "in place, and its busiest rasterizer's, busiest shader's and "
                                  "the composition network's busy time (stats.json "
                                  "pixelflow.passes; analysis/pixelflow_passes.py)"}},
     .samples = false,
     .sampling_refusal =
         "its frame is passes of regions, each map needed whole before the camera's pass (seed "
         "004 L116), and a frame of the paper's size takes half a second whole; run the whole "
         "frame"});

}  // namespace
}  // namespace rtsim::platform
