// ullner-scanline-tree: Ullner's real-time scan-line tree (seed 000 §3.3, L1062-L1667; note
// 000-ch3 §2.3-2.8): a T&C processor a polygon on one broadcast bus (SIMD, L1100-L1102), a scan
// conversion processor each, a binary tree of merging processors merging their segment streams,
// and the pixel conversion processor at the root painting the root's stream as the beam passes
// (Fig. 3-9). It does not trace rays: firmware/scanline/ transforms, clips, scan-converts, merges
// and paints, on the 12-bit words the segments carry.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <systemc>

#include "common/input_error.hpp"
#include "firmware/scanline/tree_frame.hpp"
#include "modules/module_params.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_support.hpp"
#include "platform/machines/mesh_params.hpp"
#include "platform/machines/ullner_scanline_tree/frame_output.hpp"
#include "platform/machines/ullner_scanline_tree/merging_node.hpp"
#include "platform/machines/ullner_scanline_tree/pixel_converter_node.hpp"
#include "platform/machines/ullner_scanline_tree/scan_converter_node.hpp"
#include "platform/machines/ullner_scanline_tree/tc_array.hpp"

namespace rtsim::platform {

class UllnerScanlineTree final : public Machine {
 public:
  using Machine::Machine;
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
};

namespace {

using namespace ullner_scanline_tree;

const modules::ChoiceParam kAssignment(
    {.name = "tree.assignment",
     .default_value = "random",
     .allowed = {"random", "scene"},
     .description = "which polygon sits at which leaf: shuffled, or in the scene's order (a "
                    "scene's neighbouring polygons then share subtrees)",
     .source = "seed 000 L1592: polygons assigned to leaves at random, or by subvolume"});
const modules::IntParam kSeed({.name = "tree.seed",
                               .default_value = "1983",
                               .min = "0",
                               .max = "2147483647",
                               .description = "the random assignment's seed",
                               .source = "assumption: any fixed seed (the same tree every run)"});
/// The most polygons a run takes: one T&C processor, scan converter and merging processor each.
constexpr std::size_t kMaxPolygons = 200000;

struct TreeSettings {
  raster::MeshSettings mesh;
  bool random = true;
  std::uint64_t seed = 1983;
};

TreeSettings read_settings(const params::ParamRegistry& r) {
  const modules::ModuleParams p(r, "");
  TreeSettings s;
  s.mesh = read_mesh_params(r);
  s.random = p.get(kAssignment) == "random";
  s.seed = static_cast<std::uint64_t>(p.get(kSeed));
  return s;
}

/// The scene as the tree's host loads it, checked: a scene the machine cannot hold is bad input.
scanline::TcFrame load_frame(const scenes::Scene& scene, const TreeSettings& s, int width,
                             int height, const shading::ShadeParams& shade) {
  const double estimate = raster::estimated_triangles(scene, s.mesh);
  if (estimate > static_cast<double>(kMaxPolygons))
    throw InputError(scene.name, 0,
                     "ullner-scanline-tree: the scene makes about " +
                         std::to_string(static_cast<long long>(estimate)) +
                         " polygons, a T&C processor, scan converter and merging processor each; "
                         "at most " +
                         std::to_string(kMaxPolygons) + " (lower mesh.* for a tessellated scene)");
  if (width > scanline::kWordSteps || height >= scanline::kDummyLine)
    throw InputError("--width/--height", 0,
                     "ullner-scanline-tree: x and the line number are 12-bit words (seed 000 "
                     "L1348): at most 4096 pixels a line and 4094 lines");
  return scanline::tc_frame(scene, raster::build_raster_mesh(scene, s.mesh), width, height, shade);
}

void check_samples(int spp) {
  if (spp > 1)
    throw InputError("render.spp", 0,
                     "ullner-scanline-tree paints one sample a pixel: its segments are scan "
                     "lines (seed 000 L1657 leaves supersampling as an extension); use 1");
}

/// The tree's processors, built from the root down so that each knows the queue it feeds.
struct Tree {
  std::vector<std::unique_ptr<ScanConverterNode>> scps;  ///< by polygon
  std::vector<std::unique_ptr<MergingNode>> mps;
};

/// Leaves [lo, hi), hi > lo.
template <class Target>
void build(MachineRun& run, Tree& tree, const std::vector<std::uint32_t>& leaf, std::size_t lo,
           std::size_t hi, int lines, const ProbeStages& stages,
           modules::MessageQueue<SegmentMessage>& parent, Target& feeds) {
  if (hi - lo == 1) {
    const std::uint32_t polygon = leaf[lo];
    auto scp = std::make_unique<ScanConverterNode>(
        (std::string(ScanConverterNode::kClass) + std::to_string(polygon)).c_str(), run, polygon,
        lines, parent.fifo, stages);
    scp->out.bind(feeds);
    tree.scps[polygon] = std::move(scp);
    return;
  }
  auto mp = std::make_unique<MergingNode>(
      (std::string(MergingNode::kClass) + std::to_string(tree.mps.size())).c_str(), run,
      parent.fifo, stages);
  mp->out.bind(feeds);
  MergingNode& m = *mp;
  tree.mps.push_back(std::move(mp));
  const std::size_t mid = (lo + hi) / 2;
  build(run, tree, leaf, lo, mid, lines, stages, m.in0, m.in0.socket);
  build(run, tree, leaf, mid, hi, lines, stages, m.in1, m.in1.socket);
}

}  // namespace

void UllnerScanlineTree::declare_params(params::ParamRegistry& r) const {
  // The twin reads view.*, the shading model's ambient and light intensity and render.spp (one
  // sample): it searches nothing and traces no rays.
  declare_common_params(r, {.accel = false,
                            .shells = false,
                            .polygon_kernel = false,
                            .bezier = false,
                            .ray_tree = false});
  const modules::ParamDecls machine(r, "", /*per_instance=*/false);
  const modules::ParamDecls image = machine.affecting_image();
  declare_mesh_params(image);
  image.add(kAssignment);
  image.add(kSeed);
  TcArray::declare_params(machine.sub(TcArray::kName));
  ScanConverterNode::declare_params(machine.sub(ScanConverterNode::kClass));
  MergingNode::declare_params(machine.sub(MergingNode::kClass));
  PixelConverterNode::declare_params(machine.sub(PixelConverterNode::kName));
}

FunctionalTwin UllnerScanlineTree::make_twin(scenes::Scene& scene,
                                             const params::ParamRegistry& r) const {
  auto settings = functional::read_render_settings(r);
  settings.accel = functional::AccelKind::None;
  check_samples(settings.spp);
  FunctionalTwin twin = make_functional_twin(scene, settings);
  const TreeSettings tree = read_settings(r);
  // Checked now: a scene the machine cannot hold is bad input before anything runs.
  (void)raster::estimated_triangles(scene, tree.mesh);
  twin.render = [tree](const scenes::Scene& s, const Tracer&,
                       const functional::RenderOptions& opts) {
    const auto start = std::chrono::steady_clock::now();
    const int w = opts.width > 0 ? opts.width : s.camera.width;
    const int h = opts.height > 0 ? opts.height : s.camera.height;
    const scanline::TcFrame frame = load_frame(s, tree, w, h, opts.shade);
    const auto leaves = scanline::leaf_assignment(frame.polygons.size(), tree.random, tree.seed);
    const scanline::TreeFrame out = scanline::evaluate_tree(frame, h, leaves);
    functional::FrameState state(w, h, 1, opts.aov_id, opts.aov_depth);
    deliver_rows(scanline::paint_frame(out.root, w, h, s.background, opts.aov_id, opts.aov_depth),
                 frame.view, frame.primitive, state);
    return state.finish(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  };
  return twin;
}

RunResult UllnerScanlineTree::run(scenes::Scene& scene, FunctionalTwin& twin,
                                  const params::ParamRegistry& r, const RunOptions& opts) const {
  if (opts.sample_every > 0)
    throw InputError("--sample", 0, "ullner-scanline-tree does not sample");
  check_samples(twin.settings.spp);
  MachineRun run(name(), scene, twin, r, opts, /*rows_sampled=*/false);
  const TreeSettings settings = read_settings(r);
  const scanline::TcFrame frame =
      load_frame(scene, settings, run.width(), run.height(), twin.settings.shade);
  // A scene with no polygon keeps one leaf, whose scan converter sends the dummy alone.
  const auto leaves = scanline::leaf_assignment(std::max<std::size_t>(1, frame.polygons.size()),
                                                settings.random, settings.seed);

  // In-flight faults on the root's link; the machine has no memory at rest to corrupt.
  std::vector<MemoryFault> at_rest = opts.faults;
  std::vector<RootFault> root_faults;
  for (const auto& f : take_faults(
           at_rest, [](const std::string& n) { return n == PixelConverterNode::kFaultPoint; }))
    root_faults.push_back({f.word, f.xor_mask, false});
  inject_faults(name(), at_rest, {}, {PixelConverterNode::kFaultPoint});

  // --latency-probe follows segments from the scan converter that formed them up the tree to
  // the pixels they became (a segment hidden on the way, or broken, ends or forks there).
  modules::LatencyProbe& probe = run.probe();
  probe.describe("segment",
                 "a segment, from its scan converter forming it to the pixel conversion "
                 "processor painting it");
  const ProbeStages stages{.scp = probe.stage("scp*"),
                           .scp_link = probe.stage("scp*.link"),
                           .mp_in = probe.stage("mp*.in*"),
                           .mp = probe.stage("mp*"),
                           .mp_link = probe.stage("mp*.link"),
                           .pcp_in = probe.stage("pcp.in"),
                           .pcp = probe.stage("pcp")};
  TcArray tc(TcArray::kName, run, frame);
  PixelConverterNode pcp(PixelConverterNode::kName, run, tc, frame, root_faults, stages);
  Tree tree;
  tree.scps.resize(leaves.size());
  build(run, tree, leaves, 0, leaves.size(), run.height(), stages, pcp.in, pcp.in.socket);
  for (std::size_t k = 0; k < tree.scps.size(); ++k) tc.to_scp[k]->bind(tree.scps[k]->in.socket);
  run.simulate();

  const sc_core::sc_time end = pcp.frame_end();
  run.stats_over(sc_core::SC_ZERO_TIME, end);
  for (const RootFault& f : pcp.faults())
    if (!f.applied)
      throw InputError("--fault root:" + std::to_string(f.word), 0,
                       "the root sent fewer words than that (11 a segment)");

  nlohmann::ordered_json& res = run.machine_stats();
  auto& st = res["scanline_tree"];
  st["polygons"] = frame.polygons.size();
  st["merging_processors"] = tree.mps.size();
  // The T&C broadcast: its instructions against the frame's (L1334-L1336).
  const double frame_period = pcp.line_time().to_seconds() * run.height();  // pcp.frame_rate's
  const double instruction_s = tc.instruction_time().to_seconds();
  st["tc"] = {{"instructions", tc.program().total()},
              {"time_s", tc.done().to_seconds()},
              {"instructions_a_frame",
               instruction_s > 0.0 ? std::floor(frame_period / instruction_s) : 0.0}};
  nlohmann::ordered_json tasks = nlohmann::ordered_json::object();
  for (int t = 0; t < scanline::kTcTasks; ++t)
    tasks[std::string(scanline::kTcTaskNames[static_cast<std::size_t>(t)])] =
        tc.program().count[static_cast<std::size_t>(t)];
  st["tc"]["tasks"] = std::move(tasks);
  // The scan-out: from the broadcast's end to the frame's.
  const auto& per_line = pcp.segments_per_line();
  std::uint64_t segments = 0, busiest = 0;
  for (const auto n : per_line) {
    segments += n;
    busiest = std::max<std::uint64_t>(busiest, n);
  }
  st["scan_out"] = {{"time_s", (end - pcp.scan_out_begin()).to_seconds()},
                    {"line_time_s", pcp.line_time().to_seconds()},
                    {"paced", pcp.paced()},
                    {"late_lines", pcp.late_lines()},
                    {"root_segments", segments},
                    {"segments_a_line_mean",
                     per_line.empty() ? 0.0 : static_cast<double>(segments) / per_line.size()},
                    {"segments_a_line_max", busiest}};
  std::array<std::uint64_t, scanline::kMergeCases> cases{};
  for (const auto& mp : tree.mps)
    for (std::size_t k = 0; k < cases.size(); ++k) cases[k] += mp->passes()[k];
  nlohmann::ordered_json passes = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < cases.size(); ++k)
    passes[std::string(scanline::kMergeCaseNames[k])] = cases[k];
  st["merge_passes"] = std::move(passes);
  for (const auto& f : pcp.faults())
    st["faults_in_flight"].push_back({{"at", PixelConverterNode::kFaultPoint},
                                      {"word", f.word},
                                      {"xor_mask", f.xor_mask},
                                      {"applied", f.applied}});
  using modules::StatUnit;
  run.machine_units() = {{"scanline_tree.*time_s", StatUnit::seconds},
                         {"scanline_tree.*.time_s", StatUnit::seconds},
                         {"scanline_tree.scan_out.line_time_s", StatUnit::seconds},
                         {"scanline_tree.*", StatUnit::count}};
  return run.finish(modules::LatencyRecorder{}, {});
}

namespace {

const RegisterMachine<UllnerScanlineTree> kRegistered(
    {.name = "ullner-scanline-tree",
     .description = "Ullner's real-time scan-line tree: a T&C processor a polygon on a SIMD "
                    "broadcast bus, scan converters, a binary tree of merging processors and the "
                    "pixel conversion processor at its root (seed 000 §3.3)",
     .sample_scene = "builtin:spd-teapot",
     // One T&C processor, scan converter and merging processor a polygon: the generic tests run
     // scenes of 100 to 1000 polygons.
     .test_runs = {"--scene builtin:ullner-random-100",
                   "--scene builtin:ullner-cubes -p mp.queue_depth=1",
                   "--scene builtin:spd-teapot -p pcp.paced=false -p tree.assignment=scene"},
     .benchmark_runs = {"--scene builtin:spd-teapot", "--scene builtin:ullner-cubes"},
     .samples = false,
     .sampling_refusal = "its frame is one pass down the scan lines through a tree whose every "
                         "processor holds the stream's state; run the whole frame"});

}  // namespace
}  // namespace rtsim::platform
