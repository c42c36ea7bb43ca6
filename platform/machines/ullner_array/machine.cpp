// ullner-array: Ullner's ray-tracing array (seed 000 §2.5, L755-L895). An R x C grid of
// processors on four bidirectional links; each owns a column of subvolumes along the depth axis
// (or a skewed assignment, with wrap links) and a block of the frame buffer; rays travel as
// messages between them, and the image is the sum of the contributions the result messages carry.
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <systemc>

#include "common/input_error.hpp"
#include "modules/removal_order.hpp"
#include "modules/sim_time.hpp"
#include "modules/stat_directory.hpp"
#include "modules/wake_queue.hpp"
#include "platform/functional/scene_tracer.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_support.hpp"
#include "platform/machines/ullner_array/array_host.hpp"
#include "platform/machines/ullner_array/array_node.hpp"
#include "platform/machines/ullner_array/frame_buffer_readout.hpp"

namespace rtsim::platform {

class UllnerArray final : public Machine {
 public:
  using Machine::Machine;
  /// No warm-up: its processors start their own rays at once, so there is no fill to wait out,
  /// and window completions bunch at the frame's end; a warm-up's windows only push the exact
  /// start later (measured: an error of 6% became 108% on ullner-sheets-1000 at K = 8,
  /// docs/sampling.md).
  int sample_warmup_rays(const params::ParamRegistry&) const override { return 0; }
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
};

namespace {

using ullner_array::Mapping;
using ullner_array::SubvolumeMapping;

// The array's own parameters (array.*), each named once.
const modules::CountParam kRows(
    {.name = "rows",
     .default_value = "8",
     .min = "1",
     .max = "64",
     .unit = "processors",
     .description = "Rows of processors in the array (at most 64)",
     .source = "seed 000 L773 (Fig. 2-25: sixty-four processors, 8 x 8)",
     .affects_image = true});
const modules::CountParam kCols({.name = "cols",
                                 .default_value = "8",
                                 .min = "1",
                                 .max = "64",
                                 .unit = "processors",
                                 .description = "Columns of processors in the array (at most 64)",
                                 .source = "seed 000 L773 (Fig. 2-25)",
                                 .affects_image = true});
const modules::CountParam kSubvolumes(
    {.name = "subvolumes",
     .default_value = "0",
     .max = "256",
     .unit = "per axis",
     .description = "Subvolumes per axis of the modelling space; 0: as many as the larger side of "
                    "the array (one column of subvolumes a processor, Fig. 2-26). More give each "
                    "processor several (L883-L889: 16 on an 8 x 8 array)",
     .source = "seed 000 L767-L779, L883-L889",
     .affects_image = true});
const modules::ChoiceParam kMapping(
    {.name = "mapping",
     .default_value = "straight",
     .allowed = {"straight", "skew", "torus"},
     .description = "Subvolumes to processors: each a depth column (straight), layers shifted "
                    "right with the side edges joined (skew), or shifted right and down in turn "
                    "with both pairs joined (torus)",
     .source = "seed 000 L860-L881 (Figs. 2-26, 2-31, 2-32); the both-ways pattern is an "
               "assumption (docs/machines.md)"});
const modules::ChoiceParam kDepthAxis(
    {.name = "depth_axis",
     .default_value = "auto",
     .allowed = {"auto", "x", "y", "z"},
     .description = "The axis simulated inside the processors; auto: the one most along the view "
                    "(the eye in front, Fig. 2-29)",
     .source = "seed 000 L779 (Fig. 2-26), L862"});
const modules::ChoiceParam kInterconnect(
    {.name = "interconnect",
     .default_value = "mesh",
     .allowed = {"mesh", "ring"},
     .description = "How processors exchange messages: links to the four neighbours, a message "
                    "copied hop by hop (mesh, L854), or one token ring (ring.*) carrying each "
                    "message straight to its destination",
     .source = "seed 000 L854 (mesh); the ring is a what-if after Pixel-Planes 5's (seed 004 "
               "L284)"});
const modules::CountParam kDropResult(
    {.name = "fault.drop_result",
     .default_value = "0",
     .max = "1000000000000",
     .unit = "messages",
     .description = "A fault for tests: the result message with this number (counted where "
                    "results are added) is lost; 0 loses none",
     .source = "test setting: fault injection, not a machine property",
     .affects_image = true});
/// The array's parameters are the machine's own, under this path; its ring's under kRing.
constexpr const char* kArray = "array";
constexpr const char* kRing = "ring";

/// The array's size and its subvolumes per axis (0 given: the larger side); an InputError if
/// some processor would have no subvolume.
struct ArraySize {
  int rows, cols, subvolumes;
};
ArraySize array_size(const params::ParamRegistry& r) {
  const modules::ModuleParams a(r, kArray);
  const int rows = static_cast<int>(a.get(kRows));
  const int cols = static_cast<int>(a.get(kCols));
  const int n = static_cast<int>(a.get(kSubvolumes));
  if (n > 0 && n < std::max(rows, cols))
    throw InputError(a.where_set(kSubvolumes.name()), 0,
                     a.path_of(kSubvolumes.name()) + " = " + std::to_string(n) +
                         " leaves processors without a subvolume on a " + std::to_string(rows) +
                         " x " + std::to_string(cols) + " array: use at least " +
                         std::to_string(std::max(rows, cols)) + " (or 0)");
  return {rows, cols, n > 0 ? n : std::max(rows, cols)};
}

/// Credit the host gives for each vision ray: a power of two large enough that a ray tree of
/// any depth the shading allows can share it out (assumption; checked where it is shared).
constexpr std::uint64_t kCreditPerRay = std::uint64_t{1} << 40;

Mapping mapping_of(const std::string& s) {
  return s == "skew" ? Mapping::kSkew : s == "torus" ? Mapping::kTorus : Mapping::kStraight;
}

/// The array's layout for the scene's view: the depth axis is the one most along the view
/// (unless set), the columns run along the one most along the image's right, the rows down
/// the image (so with the eye in front a pixel's processor owns the subvolumes its ray enters).
SubvolumeMapping layout(const params::ParamRegistry& r, const scenes::Camera& cam) {
  const modules::ModuleParams array(r, kArray);
  SubvolumeMapping m;
  const ArraySize size = array_size(r);
  m.rows = size.rows;
  m.cols = size.cols;
  m.n = size.subvolumes;
  m.mapping = mapping_of(array.get(kMapping));
  const Vec3 dir = glm::normalize(cam.at - cam.from);
  Vec3 right = glm::cross(dir, cam.up);
  if (glm::length(right) == 0.0) right = Vec3(1.0, 0.0, 0.0);
  right = glm::normalize(right);
  const Vec3 up = glm::cross(right, dir);
  const std::string& axis = array.get(kDepthAxis);
  if (axis == "auto") {
    m.depth_axis = 0;
    for (int k = 1; k < 3; ++k)
      if (std::fabs(dir[k]) > std::fabs(dir[m.depth_axis])) m.depth_axis = k;
  } else {
    m.depth_axis = axis == "x" ? 0 : axis == "y" ? 1 : 2;
  }
  const int a = (m.depth_axis + 1) % 3, b = (m.depth_axis + 2) % 3;
  m.col_axis = std::fabs(right[a]) >= std::fabs(right[b]) ? a : b;
  m.row_axis = m.col_axis == a ? b : a;
  m.flip_cols = right[m.col_axis] < 0.0;
  m.flip_rows = up[m.row_axis] > 0.0;  // row 0 at the top of the image
  return m;
}

}  // namespace

void UllnerArray::declare_params(params::ParamRegistry& r) const {
  // Its twin walks the array's own subvolume grid with Ullner's quad kernel, a subvolume at a
  // time: no render.accel, grid, shells, polygon_kernel or bezier parameter is read.
  declare_common_params(
      r, {.accel = false, .shells = false, .polygon_kernel = false, .bezier = false});
  const modules::ParamDecls array(r, kArray, false);
  for (const auto* p : {&kRows, &kCols, &kSubvolumes}) array.add(*p);
  array.add(kMapping);
  array.add(kDepthAxis);
  array.add(kInterconnect);
  modules::TokenRing::declare_params(
      modules::ParamDecls(r, kRing, false),
      {.bandwidth = "48 Mbit/s",
       .bandwidth_source = "assumption: one mesh link's rate (16 bits a 333 ns memory cycle), so "
                           "the comparison is one shared medium against the mesh's many links",
       .hop_latency = "333.333 ns",
       .max_packet_bytes = "68",
       .header_bytes = "4",
       .service = "exhaustive",
       .source = "assumption: a node passes the token or a packet's bits on in one memory cycle; "
                 "a packet holds one 17-word message with a one-word header"});
  array.add(kDropResult);
  ullner_array::ArrayHost::declare_params(modules::ParamDecls(r, ullner_array::ArrayHost::kName));
  ullner_array::FrameBufferReadout::declare_params(
      modules::ParamDecls(r, ullner_array::FrameBufferReadout::kName));
  ullner_array::ArrayNode::declare_params(modules::ParamDecls(r, ullner_array::ArrayNode::kClass));
}

FunctionalTwin UllnerArray::make_twin(scenes::Scene& scene, const params::ParamRegistry& r) const {
  require_polygons(name(), scene);
  const ArraySize size = array_size(r);
  auto settings = functional::read_render_settings(r);
  settings.polygon_kernel = functional::PolygonKernel::UllnerQuad;
  settings.accel = functional::AccelKind::Grid;
  settings.grid_divisions = size.subvolumes;
  settings.grid_by_subvolume = true;
  FunctionalTwin twin = make_functional_twin(scene, settings);
  require_surviving_primitives(name(), scene, twin, "its processors would hold nothing");
  return twin;
}

RunResult UllnerArray::run(scenes::Scene& scene, FunctionalTwin& twin,
                           const params::ParamRegistry& r, const RunOptions& opts) const {
  using ullner_array::ArrayHost;
  using ullner_array::ArrayNode;
  MachineRun run(name(), scene, twin, r, opts);
  functional::FrameState& frame = run.frame();
  const auto grid = functional::grid_of(*twin.tracer);
  if (!grid) throw std::logic_error("ullner-array: its twin has no subvolume grid");

  ullner_array::ArrayContext ctx;
  ctx.mapping = layout(r, scene.camera);
  const modules::MeshTopology topology(ctx.mapping.rows, ctx.mapping.cols, ctx.mapping.wrap_rows(),
                                       ctx.mapping.wrap_cols());
  ctx.topology = &topology;
  ctx.grid = grid.get();
  ullner_array::RecordCells record_cells(*grid);
  ctx.record_cells = &record_cells;
  ctx.shade = twin.settings.shade;
  ctx.frame = &frame;
  // The vision rays of the rows simulated in detail (all of them unless --sample).
  const std::uint64_t rays = frame.detailed_pixels() * static_cast<std::uint64_t>(frame.spp());
  ctx.credit_per_ray = kCreditPerRay;
  while (ctx.credit_per_ray > 1 && rays > (std::uint64_t{1} << 62) / ctx.credit_per_ray)
    ctx.credit_per_ray >>= 1;
  ctx.total_credit = ctx.credit_per_ray * rays;
  ctx.drop_result = static_cast<std::uint64_t>(modules::ModuleParams(r, kArray).get(kDropResult));

  // Each processor must hold what it keeps of the broadcast (L835: 128 KB).
  const std::size_t capacity = ArrayNode::memory_words(r);
  const modules::ModuleParams array(r, kArray);
  const std::size_t attribute_words = ArrayHost::attribute_words(scene);
  const std::size_t view_words = ArrayHost::view_words(scene.camera);
  const std::vector<std::size_t> needs = ullner_array::load_words_needed(
      *grid, ctx.mapping, topology, *twin.geometry, attribute_words, view_words);
  for (int i = 0; i < topology.nodes(); ++i) {
    const std::size_t need = needs[static_cast<std::size_t>(i)];
    if (need > capacity)
      throw InputError(scene.name, 0,
                       "processor node" + std::to_string(i) + " of the array would need " +
                           std::to_string(need) +
                           " words for its polygons, subvolume lists and the scene's attributes "
                           "but its memory has " +
                           std::to_string(capacity) + " words (" + ArrayNode::memory_words_name(r) +
                           "); use more processors or "
                           "subvolumes (" +
                           array.path_of(kRows.name()) + ", " + array.path_of(kCols.name()) + ", " +
                           array.path_of(kSubvolumes.name()) + ") or a larger memory");
  }
  // Before the array's first module, so that its thousands are unregistered each at the front
  // of SystemC's registry after the run, not looked for through all the others.
  modules::RemovalOrder removal_order;
  // The interconnect: the mesh links of each processor, or one ring (its parameters are read
  // either way, so a bad value is an error whichever is chosen).
  const modules::TokenRing::Config ring_config =
      modules::TokenRing::read_config(modules::ModuleParams(r, kRing));
  std::unique_ptr<modules::TokenRing> ring;
  std::unique_ptr<modules::RingChannel<ullner_array::RayMessage>> ring_channel;
  const std::string& interconnect = modules::ModuleParams(r, kArray).get(kInterconnect);
  if (interconnect == "ring") {
    ring = std::make_unique<modules::TokenRing>(kRing, ring_config,
                                                static_cast<std::size_t>(topology.nodes()),
                                                ullner_array::message_type_names());
    ring->trace_to(run.trace());
    ring_channel =
        std::make_unique<modules::RingChannel<ullner_array::RayMessage>>("ring_channel", *ring);
    ctx.ring = ring_channel.get();
    ctx.ring_medium = ring.get();
  }
  // The host, on the array's edge at processor (0, 0), and the ready line it waits on.
  std::vector<MemoryFault> faults = opts.faults;
  ullner_array::ReadyLine ready;
  ArrayHost host(ArrayHost::kName, r, *twin.geometry, scene, ready, faults);
  ctx.loaded = &host.loaded();
  ctx.ready = &ready;
  std::vector<ullner_array::MessageFault> message_faults;
  if (!ring) message_faults = ullner_array::message_faults(topology, faults);
  ctx.message_faults = &message_faults;
  // A walk crosses at most 3n subvolumes after a route across the array, a result the array
  // once more, and a ray tree is max_depth + 2 generations (shadow rays the last). Four times
  // that is never reached without a fault.
  ctx.hop_limit =
      static_cast<std::uint32_t>(4 * (topology.rows() + topology.cols() + 3 * ctx.mapping.n) *
                                     (std::max(ctx.shade.max_depth, 0) + 2) +
                                 16);
  // --latency-probe: the stages of a ray by class (every node alike), in the order it meets
  // them: made at a node, searched by its unit, carried on a link (or the ring) into the next
  // node's input queue.
  modules::LatencyProbe& probe = run.probe();
  ctx.probe = &probe;
  ctx.stages.node = probe.stage("node*");
  ctx.stages.pipeline = probe.stage("node*.pipeline");
  if (ring)
    ctx.stages.ring = probe.stage(kRing);
  else
    ctx.stages.link = probe.stage("node*.link_*");
  ctx.stages.in = probe.stage(ring ? "node*.in_ring" : "node*.in_*");
  // node.process = queue (the default): the array's own event queue runs its processors, one
  // SystemC process for all of them; it starts them once the host has sent the view.
  std::optional<modules::WakeQueue> queue;
  if (ArrayNode::process_kind(r) == "queue") {
    queue.emplace("queue", host.loaded());
    ctx.queue = &*queue;
  }
  ullner_array::ArrayTally tally;
  std::vector<std::unique_ptr<ArrayNode>> nodes;
  // Destroyed last made first: SystemC looks for a port to unregister from the newest, so the
  // other order walks every processor's ports for each (seconds at 32 x 32 after the run).
  struct NewestFirst {
    std::vector<std::unique_ptr<ArrayNode>>& nodes;
    ~NewestFirst() {
      while (!nodes.empty()) nodes.pop_back();
    }
  } const destroy_newest_first{nodes};
  nodes.reserve(static_cast<std::size_t>(topology.nodes()));
  for (int i = 0; i < topology.nodes(); ++i)
    nodes.push_back(std::make_unique<ArrayNode>(("node" + std::to_string(i)).c_str(), r, ctx, tally,
                                                topology.node(i), run.trace()));
  for (int i = 0; i < topology.nodes(); ++i) {
    if (ring_channel) {
      ring_channel->attach(static_cast<std::size_t>(i),
                           *nodes[static_cast<std::size_t>(i)]->in[ullner_array::kRingPort]);
      continue;
    }
    for (const modules::Direction d : modules::kDirections)
      if (const auto m = topology.neighbour(topology.node(i), d))
        nodes[static_cast<std::size_t>(i)]->connect(
            d, *nodes[static_cast<std::size_t>(topology.index(*m))]);
  }
  // The broadcast's spanning tree, from the host at processor (0, 0).
  host.out.bind(nodes.front()->broadcast_in);
  for (auto& n : nodes) {
    const std::vector<modules::GridNode> children = n->broadcast_children();
    for (std::size_t k = 0; k < children.size(); ++k)
      n->connect_broadcast(k, *nodes[static_cast<std::size_t>(topology.index(children[k]))]);
  }
  std::vector<const ArrayNode*> by_index;
  for (auto& n : nodes) by_index.push_back(n.get());
  ullner_array::FrameBufferReadout readout(ullner_array::FrameBufferReadout::kName, r,
                                           std::move(by_index), topology, frame, tally.frame_done);
  // The array's last module: from here on its modules go newest first, each found first.
  const modules::RemovalOrder::Release removal_order_first{removal_order};
  std::vector<modules::Memory*> memories;
  for (auto& n : nodes) memories.push_back(&n->memory);
  for (auto& n : nodes) memories.push_back(&n->frame_buffer);
  std::vector<std::string> fault_points{ullner_array::ArrayHost::kFaultPoint};
  if (!ring) fault_points.emplace_back("nodeK.link_D");  // message_fault.hpp
  inject_faults(name(), faults, memories, fault_points);
  run.simulate();

  // A corrupted credit word loses or adds credit: the end of the frame cannot be trusted, whether
  // or not the detector's sum happened to come right.
  for (const auto& f : message_faults)
    if (f.credit && f.applied > 0)
      throw InputError("--fault " + f.name() + ":" + std::to_string(f.word), 0,
                       "corrupted the credit of " + std::to_string(f.applied) +
                           " messages: the termination detector cannot tell when the frame "
                           "ended (no output written)");
  // Without a fault in flight neither can happen (2^40 credits a ray; the hop limit's margin):
  // it would be a defect of the model.
  const bool corrupted = std::any_of(message_faults.begin(), message_faults.end(),
                                     [](const auto& f) { return f.applied > 0; });
  if (tally.credit_exhausted > 0 && !corrupted)
    throw std::logic_error("ullner-array: a message's credit could not be shared any further");
  if (tally.looping > 0 && !corrupted)
    throw std::logic_error("ullner-array: a message crossed more links than any ray tree needs");
  if (!tally.done) {
    throw std::runtime_error("ullner-array: the termination detector never held all the credit");
  }
  if (!readout.done())
    throw std::runtime_error("ullner-array: the frame buffer was never read out");
  const sc_core::sc_time frame_start = host.view_sent();
  const sc_core::sc_time compute = *tally.done - frame_start;
  const sc_core::sc_time readout_time = *readout.done() - *tally.done;
  const sc_core::sc_time frame_time = *readout.done() - frame_start;
  run.stats_over(frame_start, frame_time);

  nlohmann::ordered_json busy = nlohmann::ordered_json::array();
  std::uint64_t kept = 0;
  for (int row = 0; row < topology.rows(); ++row) {
    nlohmann::ordered_json line = nlohmann::ordered_json::array();
    for (int col = 0; col < topology.cols(); ++col) {
      const ArrayNode& n = *nodes[static_cast<std::size_t>(topology.index({row, col}))];
      kept += n.polygons();
      line.push_back(frame_time > sc_core::SC_ZERO_TIME
                         ? n.accounts().busy.to_seconds() / frame_time.to_seconds()
                         : 0.0);
    }
    busy.push_back(std::move(line));
  }
  // The array's totals over its processors' own counters (node*.intersections, ...).
  const modules::StatDirectory& stats = modules::StatDirectory::instance();
  const std::uint64_t tests = stats.count_over("node*", "intersections");
  const std::uint64_t words = stats.count_over("node*.pipeline", "words_fetched");
  const std::vector<std::string> type_names = ullner_array::message_type_names();
  std::vector<std::uint64_t> sent(type_names.size(), 0);
  for (const modules::CounterArray* c : stats.of_class<modules::CounterArray>("node*", "sent_"))
    for (std::size_t t = 0; t < sent.size(); ++t) sent[t] += (*c)[t];
  nlohmann::ordered_json by_type = nlohmann::ordered_json::object();
  for (std::size_t t = 0; t < sent.size(); ++t) by_type[type_names[t]] = sent[t];
  const auto& m = ctx.mapping;
  nlohmann::ordered_json& res = run.machine_stats();
  res["intersection_tests"] = tests;
  res["array"] = {{"rows", m.rows},
                  {"cols", m.cols},
                  {"subvolumes", m.n},
                  {"mapping", modules::ModuleParams(r, kArray).get(kMapping)},
                  {"interconnect", interconnect},
                  {"depth_axis", std::string(1, "xyz"[m.depth_axis])},
                  {"polygons", twin.geometry->shapes.size()},
                  {"polygons_kept", kept},
                  {"load_time_s", frame_start.to_seconds()},
                  {"compute_time_s", compute.to_seconds()},
                  {"readout_time_s", readout_time.to_seconds()},
                  {"words_fetched", words},
                  {"messages_sent_by_type", std::move(by_type)},
                  {"termination",
                   {{"method", "credit recovery"},
                    {"credit_message_hops", sent[4]},
                    {"credit_carried_on_messages", tally.credit_carried},
                    {"credit_bits", sent[4] * ullner_array::RayMessage::kWireBits}}},
                  {"results_added", tally.results_added},
                  {"results_dropped", tally.results_dropped},
                  {"messages_destroyed_looping", tally.looping},
                  {"credit_exhausted", tally.credit_exhausted},
                  {"node_busy_fraction", std::move(busy)}};
  nlohmann::ordered_json in_flight = host.faults_json();
  for (const auto& f : message_faults)
    in_flight.push_back(
        {{"at", f.name()}, {"word", f.word}, {"xor_mask", f.xor_mask}, {"applied", f.applied}});
  if (!in_flight.empty()) res["array"]["faults_in_flight"] = std::move(in_flight);
  using modules::StatUnit;
  run.machine_units() = {{"intersection_tests", StatUnit::count},
                         {"array.load_time_s", StatUnit::seconds},
                         {"array.compute_time_s", StatUnit::seconds},
                         {"array.readout_time_s", StatUnit::seconds},
                         {"array.words_fetched", StatUnit::words},
                         {"array.termination.credit_bits", StatUnit::bits},
                         {"array.node_busy_fraction", StatUnit::fraction},
                         // rows, cols, subvolumes, polygons, messages, results, credits,
                         // the faults' words
                         {"array.*", StatUnit::count}};
  return run.finish(tally.latency, memories);
}

namespace {

const RegisterMachine<UllnerArray> kRegistered(
    {.name = "ullner-array",
     .description =
         "Ullner's ray tracing array: a grid of processors, each a CPU with an intersection "
         "unit owning a column of subvolumes, passing ray messages to its neighbours "
         "(seed 000 §2.5)",
     .sample_scene = "builtin:ullner-cubes",
     .test_runs = {"--scene builtin:ullner-cubes",
                   "--scene builtin:ullner-cubes -p array.rows=4 -p array.cols=4",
                   "--scene builtin:ullner-cubes -p array.mapping=torus"},
     .benchmark_runs = {"--scene builtin:ullner-cubes", "--scene builtin:ullner-random-1000",
                        "--scene builtin:ullner-sheets-1000"},
     .report_plots = {
         {.object = "array",
          .key = "node_busy_fraction",
          .script = "array_heatmap.py",
          .title = "load balance of the array",
          .caption = "Each processor's CPU busy fraction laid out as the array, and the "
                     "utilisation of every link toward its neighbour (stats.json "
                     "array.node_busy_fraction and modules nodeK.link_D; "
                     "analysis/array_heatmap.py)"}}});

}  // namespace
}  // namespace rtsim::platform
