// ullner-scanline-tree: Ullner's real-time scan-line tree (seed 000 §3.3, L1062-L1667; note
// 000-ch3 §2.3-2.8): a T&C processor a polygon on one broadcast bus (SIMD, L1100-L1102), a scan
// conversion processor each, a binary tree of merging processors merging their segment streams,
// and the pixel conversion processor at the root painting the root's stream as the beam passes
// (Fig. 3-9). With tree.split_levels = n the top n levels are replaced by splitting and merging
// processors (L1561-L1637), and each of the 2^n strips of the screen has its own pixel
// conversion processor (L1596). It does not trace rays: firmware/scanline/ transforms, clips,
// scan-converts, merges and paints, on the 12-bit words the segments carry.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <systemc>

#include "common/input_error.hpp"
#include "firmware/scanline/splitting.hpp"
#include "firmware/scanline/tree_frame.hpp"
#include "modules/module_params.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/camera_turn.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_support.hpp"
#include "platform/machines/mesh_params.hpp"
#include "platform/machines/ullner_scanline_tree/frame_output.hpp"
#include "platform/machines/ullner_scanline_tree/frame_sequencer.hpp"
#include "platform/machines/ullner_scanline_tree/merging_node.hpp"
#include "platform/machines/ullner_scanline_tree/pixel_converter_node.hpp"
#include "platform/machines/ullner_scanline_tree/scan_converter_node.hpp"
#include "platform/machines/ullner_scanline_tree/splitting_node.hpp"
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
     .allowed = {"random", "scene", "subvolume"},
     .description = "which polygon sits at which leaf: shuffled; in the scene's order (a "
                    "scene's neighbouring polygons then share subtrees); or by subvolume, each "
                    "subvolume's polygons dealt evenly over the subtrees at every depth",
     .source = "seed 000 L1592: polygons assigned to leaves at random, or by subvolume"});
const modules::CountParam kSubvolumes(
    {.name = "tree.subvolumes",
     .default_value = "8",
     .min = "1",
     .max = "64",
     .unit = "cells a side",
     .description = "tree.assignment = subvolume: the grid over the polygons' bounds whose "
                    "cells are the subvolumes (a polygon's is its centroid's)",
     .source = "assumption: the seed names the scheme (L1592), not its grid; 8 a side, 512 "
               "subvolumes"});
const modules::IntParam kSplitLevels(
    {.name = "tree.split_levels",
     .default_value = "0",
     .min = "0",
     .max = "6",
     .description = "levels of the tree's top replaced by splitting and merging processors: 2^n "
                    "roots, each a strip of the screen with its own pixel conversion processor",
     .source = "seed 000 L1561-L1637 (Figs. 3-23, 3-24): n levels give 2^n times the root's "
               "bandwidth with n 2^n splitting and (n - 1) 2^n + 1 more merging processors"});
const modules::IntParam kSeed({.name = "tree.seed",
                               .default_value = "1983",
                               .min = "0",
                               .max = "2147483647",
                               .description = "the random assignment's seed",
                               .source = "assumption: any fixed seed (the same tree every run)"});
const modules::CountParam kFrames(
    {.name = "frames",
     .default_value = "1",
     .min = "1",
     .max = "1000",
     .unit = "versions",
     .description = "versions of the scene, one a view (the eye turned camera.spin between "
                    "them, the last the scene's own): the run shows frames at pcp.frame_rate "
                    "until the last version is on the screen, re-scanning a version whose "
                    "successor is not transformed in time; the image is the last frame's",
     .source = "study setting: T&C and scan conversion pipelined across frames (seed 000 "
               "L1350-L1352)"});
const modules::RealParam kSpin({.name = "camera.spin",
                                .default_value = "0",
                                .min = "-360",
                                .max = "360",
                                .unit = "degrees",
                                .description = "turn of the eye about the view's vertical axis "
                                               "between one version and the next",
                                .source = "study setting: a simple camera path"});
/// The most frames a run shows (each takes every processor of the tree through a frame).
constexpr int kMaxFrames = 10000;
/// The most polygons the host loads (the estimate before tessellating, against a mesh without
/// bound).
constexpr std::size_t kMaxPolygons = 200000;
/// The most polygons a simulated tree holds: each has a scan converter and a merging processor,
/// a SystemC thread each, whose stacks the host maps. Past about 30,000 threads (16,384
/// polygons did) the kernel's map count (vm.max_map_count 65530) runs out and SystemC cannot
/// start the run; 12,000 polygons (24,000 threads, and a split root's) start.
constexpr std::size_t kMaxSimulatedPolygons = 12000;

struct TreeSettings {
  raster::MeshSettings mesh;
  scanline::LeafPlan leaves;
  int split_levels = 0;
};

TreeSettings read_settings(const params::ParamRegistry& r) {
  const modules::ModuleParams p(r, "");
  TreeSettings s;
  s.mesh = read_mesh_params(r);
  const std::string order = p.get(kAssignment);
  s.leaves.order = order == "random"  ? scanline::LeafOrder::Random
                   : order == "scene" ? scanline::LeafOrder::Scene
                                      : scanline::LeafOrder::Subvolume;
  s.leaves.seed = static_cast<std::uint64_t>(p.get(kSeed));
  s.leaves.subvolumes = static_cast<int>(p.get(kSubvolumes));
  s.split_levels = static_cast<int>(p.get(kSplitLevels));
  return s;
}

/// The polygon (or idle scan converter) at each leaf: one a polygon, at least one, and at least
/// one a subtree of a split root (a scene with fewer polygons has idle leaves).
std::vector<std::uint32_t> assign_leaves(const scanline::TcFrame& frame, const TreeSettings& s) {
  const std::size_t leaves =
      std::max({frame.polygons.size(), std::size_t{1}, std::size_t{1} << s.split_levels});
  return scanline::leaf_assignment(frame.polygons, leaves, s.leaves);
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
  std::vector<std::unique_ptr<ScanConverterNode>> scps;  ///< by leaf index (polygon, or idle)
  std::vector<std::unique_ptr<MergingNode>> mps;
  /// The split root's splitting processors, stage by stage (0: the subtrees' roots').
  std::vector<std::vector<std::unique_ptr<SplittingNode>>> sps;
  std::vector<std::unique_ptr<PixelConverterNode>> pcps;  ///< a strip each, left to right
};

MergingNode& add_mp(MachineRun& run, Tree& tree, modules::MessageQueue<SegmentMessage>& parent,
                    const ProbeStages& stages) {
  auto mp = std::make_unique<MergingNode>(
      (std::string(MergingNode::kClass) + std::to_string(tree.mps.size())).c_str(), run,
      parent.fifo, stages);
  mp->out.bind(parent.socket);
  tree.mps.push_back(std::move(mp));
  return *tree.mps.back();
}

/// The subtree over leaves [lo, hi), hi > lo, whose root feeds `parent`.
void build(MachineRun& run, Tree& tree, const std::vector<std::uint32_t>& leaf, std::size_t lo,
           std::size_t hi, int lines, const ProbeStages& stages,
           modules::MessageQueue<SegmentMessage>& parent) {
  if (hi - lo == 1) {
    const std::uint32_t polygon = leaf[lo];
    auto scp = std::make_unique<ScanConverterNode>(
        (std::string(ScanConverterNode::kClass) + std::to_string(polygon)).c_str(), run, polygon,
        lines, parent.fifo, stages);
    scp->out.bind(parent.socket);
    tree.scps[polygon] = std::move(scp);
    return;
  }
  MergingNode& m = add_mp(run, tree, parent, stages);
  const std::size_t mid = (lo + hi) / 2;
  build(run, tree, leaf, lo, mid, lines, stages, m.in0);
  build(run, tree, leaf, mid, hi, lines, stages, m.in1);
}

/// The split root (splitting.hpp's network) from the strips' pixel conversion processors down:
/// the queues the 2^n subtrees' roots feed, left to right.
std::vector<modules::MessageQueue<SegmentMessage>*> build_split(MachineRun& run, Tree& tree,
                                                                int levels,
                                                                const ProbeStages& stages) {
  std::vector<modules::MessageQueue<SegmentMessage>*> feeds;
  for (auto& pcp : tree.pcps) feeds.push_back(&pcp->in);
  tree.sps.resize(static_cast<std::size_t>(levels));
  for (int stage = levels - 1; stage >= 0; --stage) {
    std::vector<modules::MessageQueue<SegmentMessage>*> below(feeds.size());
    for (const scanline::SplitPair& p : scanline::split_stage(levels, stage)) {
      MergingNode& left = add_mp(run, tree, *feeds[p.left], stages);
      MergingNode& right = add_mp(run, tree, *feeds[p.right], stages);
      for (const auto& [stream, input] : {std::pair{p.first, 0}, std::pair{p.second, 1}}) {
        auto& l_in = input == 0 ? left.in0 : left.in1;
        auto& r_in = input == 0 ? right.in0 : right.in1;
        auto sp =
            std::make_unique<SplittingNode>((std::string(SplittingNode::kClass) +
                                             std::to_string(stage) + "_" + std::to_string(stream))
                                                .c_str(),
                                            run, l_in.fifo, r_in.fifo, stages);
        sp->outputs[0]->out.bind(l_in.socket);
        sp->outputs[1]->out.bind(r_in.socket);
        below[stream] = &sp->in;
        tree.sps[static_cast<std::size_t>(stage)].push_back(std::move(sp));
      }
    }
    feeds = std::move(below);
  }
  return feeds;
}

/// A split tree whose strips did not all finish deadlocked: a splitting processor's output
/// queue filled while the merging processor it feeds waited for the other output's segments of
/// the same line (L1633-L1637). That is a queue too short for the scene: bad input, said so.
void check_finished(const Tree& tree, std::size_t frames) {
  bool finished = true;
  for (const auto& p : tree.pcps) finished = finished && p->frames_done() == frames;
  if (finished) return;
  std::string full;
  int line = -1;
  std::uint32_t need = 0;
  for (const auto& stage : tree.sps)
    for (const auto& sp : stage) {
      need = std::max(need, sp->line_segments_max());
      for (const auto& o : sp->outputs)
        if (o->queue.fifo.full() && full.empty()) {
          full = o->queue.fifo.name();
          line = sp->line();
        }
    }
  throw InputError(
      SplittingNode::kClass + std::string(".queue_depth"), 0,
      "the split tree deadlocked" + (line >= 0 ? " at line " + std::to_string(line) : "") +
          (full.empty() ? "" : " (" + full + " full)") +
          ": a splitting processor's output queue filled while the merging processor it feeds "
          "waited for the other output's segments of the line; a queue must hold the segments "
          "a line brings to its input (seed 000 L1633-L1637), and here a line brought up to " +
          std::to_string(need) + " before it stopped; raise sp.queue_depth (now " +
          std::to_string(tree.sps.front().front()->outputs[0]->queue.fifo.capacity()) +
          ") above that, or spread every subtree's polygons over the screen (tree.assignment = "
          "random or subvolume)");
}

/// The frame's pixels into the run's frame buffer and id/depth images. Every pixel's visibility
/// is answered (a segment's or the background), as every machine reports its primary rays; the
/// pixels a segment covered are its hits.
void deliver(MachineRun& run, const scanline::TcFrame& frame,
             const std::vector<scanline::PixelRow>& rows, const Tree& tree) {
  TraceCounters& counters = run.frame().counters();
  counters.rays[static_cast<std::size_t>(RayKind::Primary)] +=
      static_cast<std::uint64_t>(run.width()) * static_cast<std::uint64_t>(run.height());
  for (const auto& p : tree.pcps) counters.hits += p->pixels();
  deliver_rows(rows, frame.view, frame.primitive, run.frame());
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
  image.add(kSubvolumes);
  image.add(kSplitLevels);
  machine.add(kFrames);
  machine.add(kSpin);
  TcArray::declare_params(machine.sub(TcArray::kName));
  ScanConverterNode::declare_params(machine.sub(ScanConverterNode::kClass));
  MergingNode::declare_params(machine.sub(MergingNode::kClass));
  SplittingNode::declare_params(machine.sub(SplittingNode::kClass));
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
    const scanline::TreeFrame out =
        scanline::evaluate_tree(frame, h, assign_leaves(frame, tree), tree.split_levels);
    functional::FrameState state(w, h, 1, opts.aov_id, opts.aov_depth);
    deliver_rows(scanline::paint_frame(out.strips, w, h, s.background, opts.aov_id, opts.aov_depth),
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
  if (frame.polygons.size() > kMaxSimulatedPolygons)
    throw InputError(
        scene.name, 0,
        "ullner-scanline-tree: the scene makes " + std::to_string(frame.polygons.size()) +
            " polygons; a simulated tree holds at most " + std::to_string(kMaxSimulatedPolygons) +
            " (a SystemC thread a scan converter and a merging processor, and the "
            "host maps their stacks); render --machine ullner-scanline-tree draws "
            "larger scenes");
  const auto leaves = assign_leaves(frame, settings);
  const int levels = settings.split_levels;

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
  ProbeStages stages{.scp = probe.stage("scp*"),
                     .scp_link = probe.stage("scp*.link"),
                     .mp_in = probe.stage("mp*.in*"),
                     .mp = probe.stage("mp*"),
                     .mp_link = probe.stage("mp*.link"),
                     .pcp_in = probe.stage("pcp.in"),
                     .pcp = probe.stage("pcp")};
  if (levels > 0) {
    stages.sp_in = probe.stage("sp*.in");
    stages.sp = probe.stage("sp*");
    stages.sp_out = probe.stage("sp*.queue");
    stages.sp_link = probe.stage("sp*.link");
  }
  // The versions of the scene, one a frame's view.
  const modules::ModuleParams top(r, "");
  const int versions = static_cast<int>(top.get(kFrames));
  const sc_core::sc_time period(1.0 / modules::ModuleParams(r, PixelConverterNode::kName)
                                          .get(PixelConverterNode::frame_rate())
                                          .hz,
                                sc_core::SC_SEC);
  // The frames the run will show: a version takes ceil(broadcast / period) frames after the
  // first. A run of more than kMaxFrames is refused before it starts.
  const double broadcast_s =
      (TcArray::instruction_time(r) *
       static_cast<double>(scanline::build_tc_program(frame.literals).total() +
                           TcArray::motion_instructions(r)))
          .to_seconds();
  const double frames_shown =
      1.0 + (versions - 1) * std::max(1.0, std::ceil(broadcast_s / period.to_seconds()));
  if (frames_shown > kMaxFrames) {
    char why[256];
    std::snprintf(why, sizeof why,
                  "ullner-scanline-tree: %d versions, each a broadcast of %.4g s, at %.4g frames "
                  "a second would show %.0f frames; at most %d (fewer frames, fewer "
                  "tc.motion_instructions, or a shorter tc.instruction_time)",
                  versions, broadcast_s, 1.0 / period.to_seconds(), frames_shown, kMaxFrames);
    throw InputError("frames", 0, why);
  }
  // Version v: the scene loaded with the eye turned back from its own camera by camera.spin a
  // version, so that the last is the scene's (the image); each version's polygons face its eye.
  const double spin = top.get(kSpin);
  const scenes::Camera own = scene.camera;
  const raster::RasterMesh mesh =
      versions > 1 ? raster::build_raster_mesh(scene, settings.mesh) : raster::RasterMesh{};
  scanline::TcFrame turned_frame;  // the version being loaded, before the last
  TcArray tc(TcArray::kName, run, versions, [&](int v) -> const scanline::TcFrame& {
    if (v + 1 == versions) return frame;
    scene.camera = turned_about_up(own, -(versions - 1 - v) * spin);
    turned_frame = scanline::tc_frame(scene, mesh, run.width(), run.height(), twin.settings.shade);
    scene.camera = own;
    return turned_frame;
  });
  FrameSequencer sequencer(FrameSequencer::kName, run, tc, leaves.size(), frame.polygons.size(),
                           versions, period);
  std::vector<scanline::PixelRow> rows = scanline::blank_frame(
      run.width(), run.height(), scene.background, run.options().aov_id, run.options().aov_depth);
  Tree tree;
  const std::size_t strips = std::size_t{1} << levels;
  for (std::size_t k = 0; k < strips; ++k) {
    // Unsplit, the one processor is "pcp"; the faults are the first strip's.
    const std::string name =
        std::string(PixelConverterNode::kName) + (levels > 0 ? std::to_string(k) : std::string());
    tree.pcps.push_back(std::make_unique<PixelConverterNode>(
        name.c_str(), run, sequencer, rows,
        scanline::Strip{.levels = levels, .index = static_cast<int>(k)},
        k == 0 ? root_faults : std::vector<RootFault>{}, stages));
  }
  if (levels == 0) SplittingNode::check_params(r);
  const auto roots = build_split(run, tree, levels, stages);
  tree.scps.resize(leaves.size());
  const auto subtrees = scanline::subtree_ranges(leaves.size(), levels);
  for (std::size_t k = 0; k < subtrees.size(); ++k)
    build(run, tree, leaves, subtrees[k].first, subtrees[k].second, run.height(), stages,
          *roots[k]);
  for (std::size_t k = 0; k < tree.scps.size(); ++k)
    sequencer.to_scp[k]->bind(tree.scps[k]->in.socket);
  run.simulate();

  check_finished(tree, sequencer.shown().size());
  sc_core::sc_time end = sc_core::SC_ZERO_TIME;
  for (const auto& pcp : tree.pcps) end = std::max(end, pcp->frame_end());
  run.stats_over(sc_core::SC_ZERO_TIME, end);
  const PixelConverterNode& pcp = *tree.pcps.front();
  for (const RootFault& f : pcp.faults())
    if (!f.applied)
      throw InputError("--fault root:" + std::to_string(f.word), 0,
                       std::string("the root sent fewer words than that (11 a segment)") +
                           (levels > 0 ? " to the first strip's pixel conversion processor" : ""));
  deliver(run, frame, rows, tree);

  nlohmann::ordered_json& res = run.machine_stats();
  auto& st = res["scanline_tree"];
  st["polygons"] = frame.polygons.size();
  st["merging_processors"] = tree.mps.size();
  // The T&C broadcast: its instructions against the frame's (L1334-L1336).
  const double frame_period = period.to_seconds();
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
  // The scan-out: from the first broadcast's end to the last frame's end, every strip's
  // segments a line, over the frames.
  const auto h = static_cast<std::size_t>(run.height());
  const std::size_t shown = sequencer.shown().size();
  std::uint64_t late_lines = 0, segments = 0, busiest = 0;
  nlohmann::ordered_json late_by_frame = nlohmann::ordered_json::array();
  for (std::size_t f = 0; f < shown; ++f) {
    std::uint64_t late_here = 0;
    for (std::size_t y = 0; y < h; ++y) {
      bool late = false;
      std::uint64_t on_line = 0;
      for (const auto& p : tree.pcps) {
        on_line += p->segments_on(f, y);
        late = late || p->line_late(f, y);
      }
      late_here += late ? 1 : 0;
      segments += on_line;
      busiest = std::max(busiest, on_line);
    }
    late_lines += late_here;
    late_by_frame.push_back(late_here);
  }
  const double frame_lines = static_cast<double>(h * shown);
  st["scan_out"] = {{"time_s", (end - sequencer.frame_start(0)).to_seconds()},
                    {"line_time_s", pcp.line_time().to_seconds()},
                    {"paced", pcp.paced()},
                    {"late_lines", late_lines},
                    {"root_segments", segments},
                    {"segments_a_line_mean",
                     frame_lines > 0.0 ? static_cast<double>(segments) / frame_lines : 0.0},
                    {"segments_a_line_max", busiest}};
  // The frames (L1350-L1352): versions transformed, frames shown, versions shown again.
  nlohmann::ordered_json version_by_frame = nlohmann::ordered_json::array();
  for (const int v : sequencer.shown()) version_by_frame.push_back(v);
  st["frames"] = {{"versions", versions},
                  {"shown", shown},
                  {"rescans", sequencer.rescans()},
                  {"rescanned_polygons", sequencer.rescans() * frame.polygons.size()},
                  {"tc_version_time_s", broadcast_s},
                  {"version_by_frame", std::move(version_by_frame)},
                  {"late_lines_by_frame", std::move(late_by_frame)}};
  // The split root (L1594): its processors, and the most segments a splitting processor's
  // output queue held, stage by stage (L1637: the same at every stage).
  const scanline::SplitCounts counts = scanline::split_counts(levels);
  nlohmann::ordered_json queued = nlohmann::ordered_json::array(),
                         needed = nlohmann::ordered_json::array();
  std::uint64_t broken = 0;
  for (const auto& stage : tree.sps) {
    int most = 0;
    std::uint32_t need = 0;
    for (const auto& sp : stage) {
      most = std::max(most, sp->max_queued());
      need = std::max(need, sp->line_segments_max());
      broken += sp->broken();
    }
    queued.push_back(most);
    needed.push_back(need);
  }
  st["split"] = {{"levels", levels},
                 {"strips", strips},
                 {"splitting_processors", counts.splitters},
                 {"extra_merging_processors", counts.extra_merging},
                 {"broken_segments", broken},
                 {"line_segments_max_by_stage", std::move(needed)},
                 {"queue_max_by_stage", std::move(queued)}};
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
                   "--scene builtin:ullner-cubes -p mp.queue_depth=1 -p tree.split_levels=3 "
                   "-p tree.assignment=subvolume",
                   "--scene builtin:spd-teapot -p pcp.paced=false -p tree.assignment=scene"},
     .benchmark_runs = {"--scene builtin:spd-teapot", "--scene builtin:ullner-cubes"},
     .samples = false,
     .sampling_refusal = "its frame is one pass down the scan lines through a tree whose every "
                         "processor holds the stream's state; run the whole frame"});

}  // namespace
}  // namespace rtsim::platform
