// gaudet-pert: Gaudet's multi-PERT machine (seed 001, Chapters 4-6). N PERTs — each a ring of
// ShadeProcessor -> ShellProcessor -> PrimProcessor (L841) — get the three disjoint data sets
// (shade, shell, prim) from three Broadcast Processors cycling over three broadcast buses,
// adaptively or not, or (the baseline) hold them in their own memories. A control processor
// preprocesses the scene, loads the broadcasters and starts the frame. See docs/machines.md.
#include <chrono>
#include <memory>
#include <systemc>

#include "common/input_error.hpp"
#include "firmware/shading/camera.hpp"
#include "firmware/tasks/pert_task_costs.hpp"
#include "modules/sim_time.hpp"
#include "modules/stat_directory.hpp"
#include "platform/functional/frame_state.hpp"
#include "platform/functional/scene_tracer.hpp"
#include "platform/machine_registry.hpp"
#include "platform/machines/gaudet_pert/control_processor.hpp"
#include "platform/machines/gaudet_pert/data_sets.hpp"
#include "platform/machines/gaudet_pert/expected_latency.hpp"
#include "platform/machines/gaudet_pert/pert.hpp"
#include "platform/machines/gaudet_pert/prim_processor.hpp"
#include "platform/machines/gaudet_pert/ray_probe.hpp"
#include "platform/machines/gaudet_pert/shade_processor.hpp"
#include "platform/machines/gaudet_pert/shell_processor.hpp"
#include "platform/machines/machine_run.hpp"
#include "platform/machines/machine_support.hpp"

namespace rtsim::platform {

namespace {

// The machine's own parameters, each named once: how many PERTs, how the data sets reach them,
// the words of their records.
const modules::ChoiceParam kProcess(
    {.name = "process",
     .default_value = "queue",
     .allowed = {"queue", "method"},
     .description =
         "How the simulator runs the programs of the PERT processors and the Broadcast "
         "Processors: on the machine's own event queue, which runs them ahead of SystemC while "
         "nothing else is due (queue), or as an SC_METHOD each (method: the reference). The "
         "statistics and the image are the same (tests/gaudet_sync_test.cpp)",
     .source = "simulator setting, not of the machine"});
const modules::CountParam kPertCount(
    {.name = "pert_count",
     .default_value = "1",
     .min = "1",
     .max = "1024",
     .unit = "PERTs",
     .description = "Number of PERTs (rings of Shade, Shell and Prim processors) in parallel",
     .source = "seed 001 L841, L1103 (1 to 8 and beyond in Figs. 6-12..6-14)"});
const modules::ChoiceParam kMode(
    {.name = "broadcast.mode",
     .default_value = "adaptive",
     .allowed = {"adaptive", "non-adaptive", "direct"},
     .description = "adaptive: a packet is sent only if some BIC raised the hit line; "
                    "non-adaptive: every packet every cycle; direct: no broadcast, every "
                    "processor holds its whole data set",
     .source = "seed 001 L835-L837 (adaptive), L1047, L806 and L1103 (direct memory)"});
const modules::ChoiceParam kOrder(
    {.name = "broadcast.order",
     .default_value = "breadth",
     .allowed = {"breadth", "depth", "random"},
     .description = "Order of the ID lists: SHELL packets breadth-first or depth-first over the "
                    "hierarchy, or every data set shuffled",
     .source = "seed 001 L1019 (Fig. 6-11: breadth-first best)"});
const modules::CountParam kRandomSeed(
    {.name = "broadcast.random_seed",
     .default_value = "1985",
     .min = "0",
     .max = "9223372036854775807",
     .description = "Seed of the shuffle of broadcast.order = random",
     .source = "assumption: the thesis does not say how its random order was drawn"});

const char* const kWordsSource =
    "assumption: 32-bit words, one per int or float, COORD and RGB 3 words (note 001 §6.2); the "
    "thesis gives the structs (Figs. 4-3, 4-5, 4-7) but no sizes";
/// Words of one kind of record (data.words.*): at least `fewest`, the default.
modules::CountParam words(const char* name, const char* fewest, const char* description,
                          const std::string& source = kWordsSource) {
  return modules::CountParam({.name = name,
                              .default_value = fewest,
                              .min = fewest,
                              .max = "64",
                              .unit = "words",
                              .description = description,
                              .source = source});
}
const modules::CountParam kIdListEntryWords =
    words("id_list_entry", "3", "Words of an ID list entry {ID, address, size}",
          std::string("seed 001 L877; ") + kWordsSource);
const modules::CountParam kShellWords =
    words("shell", "8", "Words of a SHELL record: leaf, child_index, max[3], min[3]");
const modules::CountParam kPrimHeaderWords =
    words("prim_header", "3", "Words of a PRIM record's header: prim_id, surface_index, type");
const modules::CountParam kSphereWords =
    words("sphere", "4", "Words of a sphere's PTYPE: centre[3], radius");
const modules::CountParam kPolygonFixedWords = words(
    "polygon_fixed", "1", "Words of a polygon's PTYPE besides its vertices: the vertex count");
const modules::CountParam kPolygonVertexWords =
    words("polygon_vertex", "3", "Words per polygon vertex");
const modules::CountParam kShadeWords =
    words("shade", "9", "Words of a SHADE record: k_s, k_d, n, reflectance[3], transmittance[3]");
/// Where the words are declared and read.
constexpr const char* kWords = "data.words";
/// The module tree's classes: the buses, the control processor, the PERTs.
constexpr const char* kBroadcast = "broadcast";
constexpr const char* kControl = "control";
constexpr const char* kPert = "pert";

}  // namespace

class GaudetPert final : public Machine {
 public:
  using Machine::Machine;
  void declare_params(params::ParamRegistry& registry) const override;
  FunctionalTwin make_twin(scenes::Scene& scene,
                           const params::ParamRegistry& registry) const override;
  RunResult run(scenes::Scene& scene, FunctionalTwin& twin, const params::ParamRegistry& registry,
                const RunOptions& opts) const override;
  /// A sampled window spans every PERT: each takes every N-th scanline (L938).
  int sample_window_rows(const params::ParamRegistry& registry) const override {
    return static_cast<int>(modules::ModuleParams(registry, "").get(kPertCount));
  }
};

using gaudet::BroadcastMode;
using gaudet::BroadcastOrder;
using modules::from_ps;
using params::ParamKind;

namespace {

constexpr const char* kKinds[] = {"shade", "shell", "prim"};

accel::RecordWords read_words(const params::ParamRegistry& r) {
  const modules::ModuleParams p(r, kWords);
  const auto u = [&p](const modules::CountParam& n) {
    return static_cast<std::uint32_t>(p.get(n));
  };
  accel::RecordWords w;
  w.id_list_entry = u(kIdListEntryWords);
  w.shell = u(kShellWords);
  w.prim_header = u(kPrimHeaderWords);
  w.sphere = u(kSphereWords);
  w.polygon_fixed = u(kPolygonFixedWords);
  w.polygon_per_vertex = u(kPolygonVertexWords);
  w.shade = u(kShadeWords);
  return w;
}

/// Everything of one run: the modules, built in elaboration order.
struct PertPlatform {
  BroadcastMode mode = BroadcastMode::kAdaptive;
  BroadcastOrder order = BroadcastOrder::kBreadth;
  std::vector<std::unique_ptr<gaudet::BroadcastProcessor>> buses;  // shade, shell, prim
  std::vector<std::unique_ptr<gaudet::Pert>> perts;
  std::unique_ptr<modules::WakeQueue> queue;  ///< the programs (process = queue)
  std::unique_ptr<gaudet::ControlProcessor> control;

  bool broadcasting() const { return mode != BroadcastMode::kDirect; }
};

nlohmann::ordered_json split_json(const gaudet::TimeSplit& t) {
  const double rays = static_cast<double>(std::max<std::uint64_t>(t.rays, 1));
  return {{"rays", t.rays},
          {"processing_per_ray_s", t.processing.to_seconds() / rays},
          {"latency_per_ray_s", t.latency.to_seconds() / rays},
          {"pipeline_wait_per_ray_s", t.pipeline_wait.to_seconds() / rays},
          {"starved_per_ray_s", t.starved.to_seconds() / rays},
          {"processing_s", t.processing.to_seconds()},
          {"latency_s", t.latency.to_seconds()},
          {"pipeline_wait_s", t.pipeline_wait.to_seconds()},
          {"starved_s", t.starved.to_seconds()}};
}

/// stats.json's machine keys (scene_stats, gaudet): sums over the PERTs, the buses' figures.
nlohmann::ordered_json gaudet_stats(const accel::ShellTree& tree, const gaudet::PertDataSets& sets,
                                    const PertPlatform& p, const sc_core::sc_time& frame) {
  nlohmann::ordered_json out;
  gaudet::TimeSplit totals[3];
  for (const auto& pert : p.perts) {
    const gaudet::PertProcessor* procs[] = {pert->shade.get(), pert->shell.get(), pert->prim.get()};
    for (int k = 0; k < 3; ++k) totals[k] += procs[k]->split();
  }
  // Over every PERT: the processors' own statistics, summed (or their peak) by class.
  const auto& stats = modules::StatDirectory::instance();
  const auto sum = [&stats](const char* cls, const char* stat) {
    return stats.count_over(cls, stat);
  };
  const auto peak = [&stats](const char* cls, const char* stat) {
    std::uint64_t most = 0;
    for (const auto* c : stats.of_class<modules::Peak>(cls, stat))
      most = std::max(most, c->value());
    return most;
  };
  const char* const shell = "pert*.shell";
  const char* const prim = "pert*.prim";
  const std::uint64_t box_tests = sum(shell, "box_tests"),
                      shell_packets = sum(shell, "packets_caught");
  const std::uint64_t shell_uses = sum(shell, "packet_uses"),
                      leaf_shells = sum(shell, "leaf_shells");
  const std::uint64_t overflow_peak = peak(shell, "overflow_peak");
  const std::uint64_t over_capacity = sum(shell, "rays_over_list_capacity");
  const std::uint64_t rejected = sum(shell, "records_rejected");
  const std::uint64_t prim_rejected = sum(prim, "records_rejected");
  const std::uint64_t prim_packets = sum(prim, "packets_caught"),
                      cancelled = sum(prim, "packets_cancelled");
  const std::uint64_t rays_with_packets = sum(prim, "rays_with_packets");
  sc_core::sc_time first_packet_total = sc_core::SC_ZERO_TIME;
  for (const auto* d : stats.of_class<modules::Duration>(prim, "first_packet_latency_total_s"))
    first_packet_total += d->value();
  const std::uint64_t first_packet_count = sum(prim, "first_packets");
  const std::uint64_t backlog_peak = peak("pert*.shade", "backlog_peak");
  nlohmann::ordered_json buses = nlohmann::ordered_json::object();
  const gaudet::DataSetImage* set_of[] = {&sets.shade, &sets.shell, &sets.prim};
  for (std::size_t b = 0; b < p.buses.size(); ++b) {
    const auto& bp = *p.buses[b];
    const auto s = bp.stats();
    const double hits = static_cast<double>(std::max<std::uint64_t>(s.hit_packets, 1));
    buses[kKinds[b]] = {
        {"packets_in_data_set", set_of[b]->order.size()},
        {"data_set_words", set_of[b]->memory.size()},
        {"minimum_cycle_s", bp.minimum_cycle().to_seconds()},
        {"mean_cycle_s", s.cycles ? frame.to_seconds() / static_cast<double>(s.cycles) : 0.0},
        {"cycles", s.cycles},
        {"packets_broadcast", s.packets},
        {"hit_packets", s.hit_packets},
        {"captures", s.captures},
        {"mean_hit_packet_time_s", s.hit_packet_time.to_seconds() / hits},
        {"utilization",
         frame > sc_core::SC_ZERO_TIME ? s.packet_time.to_seconds() / frame.to_seconds() : 0.0}};
  }
  const auto counts = tree.counts();
  out["scene_stats"] = {{"shells", counts.shells},
                        {"shell_packets", counts.shell_packets},
                        {"prims", counts.prims},
                        {"prim_packets", counts.prim_packets}};
  nlohmann::ordered_json g;
  g["pert_count"] = p.perts.size();
  g["broadcast_mode"] = gaudet::mode_name(p.mode);
  g["broadcast_order"] = gaudet::order_name(p.order);
  g["load_time_s"] = p.control->load_time().to_seconds();
  g["words_loaded"] = sum("control", "words_loaded");
  g["shade"] = split_json(totals[0]);
  g["shade"]["backlog_peak"] = backlog_peak;
  g["shell"] = split_json(totals[1]);
  const double shell_rays = static_cast<double>(std::max<std::uint64_t>(totals[1].rays, 1));
  g["shell"]["box_tests_per_ray"] = static_cast<double>(box_tests) / shell_rays;
  g["shell"]["packets_per_ray"] = static_cast<double>(shell_uses) / shell_rays;
  g["shell"]["packets_caught"] = shell_packets;
  g["shell"]["leaf_shells_per_ray"] = static_cast<double>(leaf_shells) / shell_rays;
  g["shell"]["rays_over_list_capacity"] = over_capacity;
  g["shell"]["overflow_peak"] = overflow_peak;
  g["shell"]["records_rejected"] = rejected;
  g["prim"] = split_json(totals[2]);
  const double prim_rays = static_cast<double>(std::max<std::uint64_t>(totals[2].rays, 1));
  g["prim"]["packets_per_ray"] = static_cast<double>(prim_packets) / prim_rays;
  g["prim"]["packets_cancelled"] = cancelled;
  g["prim"]["rays_with_packets"] = rays_with_packets;
  g["prim"]["records_rejected"] = prim_rejected;
  const double fp_mean =
      first_packet_count ? first_packet_total.to_seconds() / static_cast<double>(first_packet_count)
                         : 0.0;
  g["prim"]["first_packet_latency_s"] = fp_mean;
  if (p.broadcasting()) {
    const auto& s = p.buses[2]->stats();
    gaudet::EalInputs in;
    in.n = static_cast<int>(p.perts.size());
    in.p = static_cast<double>(prim_packets);
    in.r = static_cast<double>(rays_with_packets);
    in.mct_s = p.buses[2]->minimum_cycle().to_seconds();
    in.apt_s =
        s.hit_packets ? s.hit_packet_time.to_seconds() / static_cast<double>(s.hit_packets) : 0.0;
    g["prim"]["eal"] = {{"n", in.n},
                        {"p", in.p},
                        {"r", in.r},
                        {"P2", gaudet::eal_two_packet_probability(in)},
                        {"mct_s", in.mct_s},
                        {"apt_s", in.apt_s},
                        {"eal_s", gaudet::expected_average_latency_s(in)}};
  }
  g["buses"] = buses;
  out["gaudet"] = g;
  return out;
}

/// The units of gaudet_stats' numbers (modules/stat_unit.hpp).
modules::UnitSchema gaudet_units() {
  using modules::StatUnit;
  return {{"gaudet.words_loaded", StatUnit::words},
          {"gaudet.buses.*.data_set_words", StatUnit::words},
          {"gaudet.buses.*.utilization", StatUnit::fraction},
          {"gaudet.prim.eal.P2", StatUnit::fraction},
          // Times: the load, each processor kind's split (in all and per ray), the EAL model's.
          {"gaudet.*_s", StatUnit::seconds},
          // Counts, peaks and means per ray (packets, box tests, leaf shells), the EAL's n, p, r.
          {"gaudet.*", StatUnit::count}};
}

}  // namespace

void GaudetPert::declare_params(params::ParamRegistry& r) const {
  // Its twin always searches Gaudet's box-shell hierarchy (render.shells.* shape it) with the
  // triangle kernel, and holds spheres and polygons only.
  declare_common_params(r,
                        {.accel = false, .shells = true, .polygon_kernel = false, .bezier = false});
  // The machine's own: how many PERTs, how the data sets reach them, the words of their
  // records. Every module declares its own below (DESIGN.md "Configuration").
  const modules::ParamDecls machine(r, "", /*per_instance=*/false);
  machine.add(kPertCount);
  machine.add(kProcess);
  machine.add(kMode);
  machine.add(kOrder);
  machine.add(kRandomSeed);
  const modules::ParamDecls words(r, kWords, /*per_instance=*/false);
  for (const auto* w : {&kIdListEntryWords, &kShellWords, &kPrimHeaderWords, &kSphereWords,
                        &kPolygonFixedWords, &kPolygonVertexWords, &kShadeWords})
    words.add(*w);

  // The module tree: the buses (every bus's timing set by broadcast.*, one bus's by its name),
  // the control processor and the PERTs (pert.* sets every PERT's, pert3.* one's).
  r.declare_family({.cls = kBroadcast, .members = {"shade_bus", "shell_bus", "prim_bus"}});
  gaudet::BroadcastProcessor::declare_params(machine.sub(kBroadcast));
  gaudet::ControlProcessor::declare_params(machine.sub(kControl));
  r.declare_family({.cls = kPert, .count_param = kPertCount.name()});
  gaudet::Pert::declare_params(machine.sub(kPert));
}

FunctionalTwin GaudetPert::make_twin(scenes::Scene& scene, const params::ParamRegistry& r) const {
  // Spheres and polygons only (§4.3.6, L634-L636).
  std::size_t other = 0;
  std::uint32_t first_line = 0;
  for (const auto& p : scene.primitives) {
    if (p.kind == scenes::PrimitiveKind::Sphere || p.kind == scenes::PrimitiveKind::Polygon)
      continue;
    if (other++ == 0) first_line = p.source_line;
  }
  if (other > 0)
    throw InputError(scene.name, first_line,
                     "gaudet-pert holds spheres and polygons only (seed 001 L634-L636); this "
                     "scene has " +
                         std::to_string(other) +
                         " cone/patch primitive(s). Use another machine (`rtsim list machines`)");
  auto settings = functional::read_render_settings(r);
  settings.accel = functional::AccelKind::Shells;  // the PERT's search is Gaudet's
  settings.polygon_kernel = functional::PolygonKernel::Triangle;
  settings.shell_boxes_as_stored = true;  // what the ShellProcessors read out of their packets
  settings.prims_as_stored = true;        // what the PrimProcessors read out of theirs
  FunctionalTwin twin = make_functional_twin(scene, settings);
  // Nothing left to broadcast: the PERT's data sets would be empty (no shell tree, no root
  // packet to ask for).
  require_surviving_primitives(name(), scene, twin, "its data sets would be empty");
  return twin;
}

RunResult GaudetPert::run(scenes::Scene& scene, FunctionalTwin& twin,
                          const params::ParamRegistry& r, const RunOptions& opts) const {
  MachineRun run(name(), scene, twin, r, opts);
  functional::FrameState& frame = run.frame();
  MachineTrace& trace = run.trace();
  const int w = run.width(), h = run.height();
  PertPlatform p;
  const modules::ModuleParams machine(r, "");
  p.mode = gaudet::broadcast_mode(machine.get(kMode));
  p.order = gaudet::broadcast_order(machine.get(kOrder));
  const int pert_count = static_cast<int>(machine.get(kPertCount));
  const bool on_queue = machine.get(kProcess) == "queue";
  const auto order_seed = static_cast<std::uint64_t>(machine.get(kRandomSeed));
  const auto* search = dynamic_cast<const functional::ShellSearch*>(twin.tracer.get());
  if (!search) throw std::logic_error("gaudet-pert: the twin's tracer is not a shell search");
  const accel::ShellTree& tree = search->tree();
  gaudet::PertDataSets sets;
  const accel::RecordWords words = read_words(r);
  try {
    sets = gaudet::make_pert_data_sets(tree, *twin.geometry, scene, words, p.order, order_seed);
  } catch (const std::invalid_argument& e) {
    throw InputError(scene.name, 0, std::string("gaudet-pert: ") + e.what());
  }
  const gaudet::DataSetImage* set_of[] = {&sets.shade, &sets.shell, &sets.prim};
  // The PrimProcessor's own test of each primitive (make_pert_data_sets accepted only these).
  std::vector<Cost> test_cost;
  for (const auto& shape : twin.geometry->shapes)
    test_cost.push_back(std::holds_alternative<kernels::SphereKernel>(shape.shape)
                            ? tasks::kPertSphereTestCost
                            : tasks::kPertTriangleTestCost);

  shading::PinholeCamera camera(scene.camera, w, h);
  gaudet::FrameProgress progress(frame.detailed_pixels() * static_cast<std::uint64_t>(frame.spp()),
                                 opts);

  // --latency-probe: every ray's journey around its ring (ray_probe.hpp).
  gaudet::RayProbe probe(run.probe());
  if (p.broadcasting()) {
    const sc_core::sc_time load_word_time =
        gaudet::ControlProcessor::load_word_time(modules::ModuleParams(r, kControl));
    for (int b = 0; b < 3; ++b) {
      const std::string bus_name = std::string(kKinds[b]) + "_bus";
      auto bp = std::make_unique<gaudet::BroadcastProcessor>(
          bus_name.c_str(), modules::ModuleParams(r, bus_name), set_of[b]->memory.size(),
          load_word_time, p.mode == BroadcastMode::kAdaptive, on_queue);
      bp->on_packet = [&trace, bus_name](std::uint32_t id, sc_core::sc_time start,
                                         sc_core::sc_time dur, std::size_t captures) {
        trace.slice(bus_name, "packet", start, dur, {{"id", id}, {"captures", captures}});
      };
      p.buses.push_back(std::move(bp));
    }
  }
  gaudet::PertContext context{.run = run,
                              .pert_count = pert_count,
                              .camera = camera,
                              .tree = tree,
                              .words = words,
                              .sets = sets,
                              .test_cost = test_cost,
                              .buses = {},
                              .progress = progress,
                              .probe = probe,
                              .on_queue = on_queue};
  for (auto& bp : p.buses) context.buses.push_back(bp.get());
  for (int i = 0; i < pert_count; ++i)
    p.perts.push_back(
        std::make_unique<gaudet::Pert>((kPert + std::to_string(i)).c_str(), i, context));
  const std::vector<const gaudet::DataSetImage*> loaded(std::begin(set_of), std::end(set_of));
  std::vector<gaudet::ShadeProcessor*> shade_ptrs;
  for (auto& pert : p.perts) shade_ptrs.push_back(pert->shade.get());
  // Globals for spawning rays (L928): the camera (eye, look, up, angle, resolution: 12 words),
  // and per light its position and intensity (6 words).
  const std::uint64_t globals = 12 + 6 * scene.lights.size();
  p.control = std::make_unique<gaudet::ControlProcessor>(kControl, r, context.buses, loaded,
                                                         globals, shade_ptrs);
  // The Shell and Prim processors test the SHELL and PRIM records their packets carry: a fault
  // in those buses' memories reaches the image. (The SHADE records are not yet read from their
  // words.)
  std::vector<modules::Memory*> memories;
  if (p.broadcasting()) memories = {&p.buses[1]->memory, &p.buses[2]->memory};
  inject_faults(name(), opts.faults, memories);
  for (auto& pert : p.perts) {
    pert->shell->set_frame_start(p.control->frame_start());
    pert->prim->set_frame_start(p.control->frame_start());
  }
  // process = queue: the buses' and the processors' programs on one event queue, started with
  // the frame, the buses first (SystemC started them first: their start events are notified
  // first).
  if (on_queue) {
    p.queue = std::make_unique<modules::WakeQueue>("machine_queue", p.control->frame_start());
    for (auto& bus : p.buses) bus->join(*p.queue);
    for (auto& pert : p.perts) pert->join(*p.queue);
  }

  run.simulate();
  // The simulation ends when nothing is left to happen. With every ray answered that is the end
  // of the frame; otherwise some processor waits for a packet that never comes (a corrupted
  // memory: an ID list entry pointing at no packet) and the image is not a frame.
  if (!progress.complete()) {
    const std::string what =
        "gaudet-pert stopped with work outstanding: " + std::to_string(progress.done()) + " of " +
        std::to_string(progress.total()) +
        " initial rays answered; a processor waits for a packet its bus never broadcasts";
    // With a fault injected that is the experiment's outcome (an ID list entry corrupted);
    // without one it is a fault of the model.
    if (!opts.faults.empty()) throw InputError("--fault", 0, what + " (the injected fault)");
    throw std::logic_error(what);
  }

  const sc_core::sc_time frame_time = p.control->frame_time();
  run.stats_over(p.control->load_time(), frame_time);
  run.machine_stats() = gaudet_stats(tree, sets, p, frame_time);
  run.machine_units() = gaudet_units();
  progress.report();
  return run.finish(progress.latency(), memories);
}

namespace {

const RegisterMachine<GaudetPert> kRegistered(
    {.name = "gaudet-pert",
     .description =
         "Gaudet's multi-PERT machine: N rings of Shade/Shell/Prim processors fed by three "
         "broadcast buses (seed 001, SFU 1985)",
     .sample_scene = "builtin:npp-412",
     .test_runs = {"--scene builtin:npp-412 -p pert_count=2",
                   "--scene builtin:npp-208 -p pert_count=3 -p broadcast.mode=non-adaptive",
                   "--scene builtin:npp-412 -p pert_count=2 -p broadcast.mode=direct"},
     .benchmark_runs = {"--scene builtin:npp-412 -p pert_count=8",
                        "--scene builtin:npp-208 -p pert_count=8",
                        "--scene builtin:default -p pert_count=8"}});

}  // namespace
}  // namespace rtsim::platform
