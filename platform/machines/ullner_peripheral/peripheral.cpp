#include "platform/machines/ullner_peripheral/peripheral.hpp"

#include "common/input_error.hpp"
#include "firmware/tasks/ray_tree.hpp"
#include "modules/sim_time.hpp"
#include "platform/functional/scene_tracer.hpp"

namespace rtsim::platform::ullner {

using modules::times;

namespace {

// The peripheral's parameters (peripheral.*), each named once.
const modules::TimeParam kIntersectInterval(
    {.name = "intersect_interval",
     .default_value = "333.333 ns",
     .min = "1 ps",
     .description = "Issue interval (= stage time) of the intersection pipeline: one ray/polygon "
                    "intersection per interval",
     .source = "seed 000 L584, L588 (three results every microsecond)"});
const modules::CountParam kAdderStages(
    {.name = "adder_stages",
     .default_value = "1",
     .min = "1",
     .max = "3",
     .unit = "stages",
     .description = "Pipeline stages of one floating-point addition (1 or 3); sets the physical "
                    "depth 17 or 33 and the latency 5.6 or 11 us",
     .source = "seed 000 L572-L578 (Fig. 2-17), L588"});
const modules::IntParam kFetchStages(
    {.name = "fetch_stages",
     .default_value = "1",
     .min = "0",
     .max = "16",
     .unit = "stages",
     .description = "Stages of polygon fetch from the 20 parameter memories",
     .source = "assumption: one memory cycle reads a whole polygon (seed 000 L544)"});
const modules::IntParam kSelectStages(
    {.name = "select_stages",
     .default_value = "1",
     .min = "0",
     .max = "16",
     .unit = "stages",
     .description = "Stages of the closest-intersection selection (Fig. 2-11 stage 3)",
     .source = "assumption: one compare-and-keep stage (seed 000 L484)"});
const modules::CountParam kRayQueueDepth(
    {.name = "ray_queue_depth",
     .default_value = "16",
     .min = "1",
     .max = "1000000",
     .unit = "rays",
     .description = "Depth of the ray queue from the host to the peripheral",
     .source = "assumption: queue depths are not given (seed 000 L476)"});
const modules::FlagParam kShadowEarlyExit(
    {.name = "shadow_early_exit",
     .default_value = "false",
     .description = "Brute force: stop streaming polygons at a shadow ray's first hit",
     .source = "assumption: the thesis does not say how the shadow-ray saving is realised "
               "without subdivision (seed 000 L472; note §7.6)"});
const modules::CountParam kGridDivisions(
    {.name = "grid.divisions",
     .default_value = "0",
     .min = "0",
     .max = "512",
     .unit = "per axis",
     .description = "Subvolumes per axis of the grid auxiliary processor; 0 = none (brute "
                    "force); at most 512 (512^3 subvolumes is the grid's limit, kMaxGridCells = "
                    "2^27)",
     .source = "seed 000 L592-L606 (optimum 11 for 1000 polygons, L654)",
     .affects_image = true});
const modules::ChoiceParam kGridDda(
    {.name = "grid.dda",
     .default_value = "corrected",
     .allowed = {"corrected", "as-printed"},
     .description = "Subvolume stepping: the corrected 3-D DDA, or Appendix B exactly as printed "
                    "(wrong; for fidelity experiments)",
     .source = "seed 000 L2112-L2171; errata in note 000 §4.6",
     .affects_image = true});
const modules::TimeParam kStepTime({.name = "grid.step_time",
                                    .default_value = "1 us",
                                    .description = "t_d: time to step to the next subvolume",
                                    .source = "seed 000 L654"});
const modules::CountParam kIndirectionStages(
    {.name = "grid.indirection_stages",
     .default_value = "1",
     .min = "0",
     .max = "16",
     .unit = "stages",
     .description = "Extra pipeline stage(s) of the subvolume address indirection",
     .source = "seed 000 L596 (\"yet another pipeline stage\")"});
const modules::FlagParam kLighting(
    {.name = "lighting.enabled",
     .default_value = "true",
     .description = "Lighting extension: the host's vector arithmetic runs on the inner-product "
                    "and reciprocal-square-root devices",
     .source = "seed 000 L548-L566"});
const modules::CountParam kRsqrtStages(
    {.name = "lighting.rsqrt_stages",
     .default_value = "2",
     .min = "1",
     .max = "16",
     .unit = "stages",
     .description = "Stages of the reciprocal-square-root device",
     .source = "assumption: as the square root of Fig. 2-17 (seed 000 L576)"});
const modules::CountParam kMemoryPolygons(
    {.name = "memory.polygons",
     .default_value = "1048576",
     .min = "1",
     .max = "100000000",
     .unit = "polygons",
     .description = "Capacity of the 20 parameter memories",
     .source = "assumption: a million polygons (seed 000 note §7.5 S7)",
     .affects_image = true});
const modules::TimeParam kLoadWordTime(
    {.name = "memory.load_word_time",
     .default_value = "1 us",
     .description = "Time to load one 32-bit parameter word through the dual-ported load path "
                    "(before the frame; not part of the frame time)",
     .source = "assumption: \"the port need not be fast\" (seed 000 L544)"});
/// Its result link's parameters, under the peripheral's.
constexpr const char* kResultLink = "result_link";

}  // namespace

void Peripheral::declare_params(const modules::ParamDecls& peripheral) {
  peripheral.add(kIntersectInterval);
  peripheral.add(kAdderStages);
  peripheral.add(kFetchStages);
  peripheral.add(kSelectStages);
  peripheral.add(kRayQueueDepth);
  peripheral.add(kShadowEarlyExit);
  peripheral.add(kGridDivisions);
  peripheral.add(kGridDda);
  peripheral.add(kStepTime);
  peripheral.add(kIndirectionStages);
  peripheral.add(kLighting);
  peripheral.add(kRsqrtStages);
  peripheral.add(kMemoryPolygons);
  peripheral.add(kLoadWordTime);
  modules::Link::declare_params(
      peripheral.sub(kResultLink),
      {.latency = "0 s",
       .lanes = "32",
       .bit_rate = "3 Mbit/s",
       .source = "assumption: the thesis gives no path for queue 2 (seed 000 L474-L476); a "
                 "word-wide path at the pipeline's stage rate, one word per 1/3 us (L584)"});
}

PeripheralSettings Peripheral::read_settings(const modules::ModuleParams& p) {
  PeripheralSettings c = read_search_settings(p);
  c.intersect_interval = p.get(kIntersectInterval);
  c.adder_stages = static_cast<unsigned>(p.get(kAdderStages));
  if (c.adder_stages != 1 && c.adder_stages != 3)
    throw InputError(p.where_set(kAdderStages.name()), 0,
                     p.path_of(kAdderStages.name()) +
                         " must be 1 or 3 (Fig. 2-17, seed 000 L572-L578), got " +
                         std::to_string(c.adder_stages));
  c.pipeline_stages = PeripheralSettings::stages_for_adder(c.adder_stages);
  c.fetch_stages = static_cast<unsigned>(p.get(kFetchStages));
  c.select_stages = static_cast<unsigned>(p.get(kSelectStages));
  c.ray_queue_depth = p.get(kRayQueueDepth);
  c.shadow_early_exit = p.get(kShadowEarlyExit);
  c.step_time = p.get(kStepTime);
  c.indirection_stages = static_cast<unsigned>(p.get(kIndirectionStages));
  c.lighting = p.get(kLighting);
  c.rsqrt_stages = static_cast<unsigned>(p.get(kRsqrtStages));
  c.load_word_time = p.get(kLoadWordTime);
  return c;
}

PeripheralSettings Peripheral::read_search_settings(const modules::ModuleParams& p) {
  PeripheralSettings c;
  c.grid_divisions = static_cast<int>(p.get(kGridDivisions));
  c.dda_as_printed = p.get(kGridDda) == "as-printed";
  c.memory_polygons = p.get(kMemoryPolygons);
  c.memory_polygons_name = p.path_of(kMemoryPolygons.name());
  return c;
}

Peripheral::Peripheral(sc_core::sc_module_name name, MachineRun& run, const tasks::ShadeTask& shade,
                       const PeripheralSettings& config)
    : sc_core::sc_module(name),
      rays("ray_queue", config.ray_queue_depth),
      parameters("parameter_memories",
                 run.twin().geometry->shapes.size() * kernels::kUllnerStoredWords,
                 kernels::kUllnerStoredWords, config.load_word_time, config.intersect_interval),
      result_out("result_out"),
      memory_test_(parameters, *run.twin().geometry),
      search_(
          functional::make_tracer_sharing(*run.twin().tracer, *run.twin().geometry, &memory_test_)),
      shade_(shade),
      polygons_(run.twin().geometry->shapes.size()),
      config_(config),
      counters_(run.frame().counters()),
      trace_(run.trace()),
      pipe_(std::string(this->name()) + ".pipeline", config.intersect_interval,
            config.pipeline_stages, "intersections"),
      probe_(run.probe()),
      result_link_(
          modules::ModuleParams(run.registry(), std::string(this->name()) + "." + kResultLink)),
      served_(this->name()) {
  modules::LatencyProbe& probe = run.probe();
  // Stages named by their stats.json module names, in the order a ray meets them.
  probe_ray_queue_ = probe.stage(rays.name());
  if (config.grid_divisions > 0) {
    aux_.emplace(std::string(this->name()) + ".aux");
    probe_aux_ = probe.stage(aux_->stat_path());
  }
  probe_memories_ = probe.stage(parameters.name());
  probe_pipeline_ = probe.stage(std::string(this->name()) + ".pipeline");
  probe_result_link_ = probe.stage(result_link_.name());
  result_link_.trace_to(trace_);
  SC_THREAD(run);
}

void Peripheral::run() {
  const sc_core::sc_time stage = config_.intersect_interval;
  const bool grid = config_.grid_divisions > 0;
  for (;;) {
    modules::wait_for_item(rays.fifo, clock_);
    sc_core::sc_time taken;
    RayRequest req = rays.fifo.get(clock_.now(), taken);
    clock_.catch_up(taken);
    ++served_.rays;
    const auto journey = req.journey;
    using modules::LatencyPart;
    probe_.add(journey, probe_ray_queue_, LatencyPart::kQueueing, taken - req.arrived);

    // The answer (firmware), and what it took.
    TraceCounters before = counters_;
    RayResult res;
    res.request = req;
    res.found = tasks::trace_one(*search_, shade_, req.ray, res.hit, counters_);
    const std::uint64_t tests = counters_.intersection_tests - before.intersection_tests;
    const std::uint64_t cells = counters_.cells_visited - before.cells_visited;
    const std::uint64_t steps = counters_.dda_steps - before.dda_steps;
    double t_enter = 0.0, t_exit = 0.0;
    if (req.ray.kind == RayKind::Primary && res.found &&
        config_.modelling_space.intersect(req.ray.ray, 0.0, kInfinity, t_enter, t_exit)) {
      served_.primary_travel += res.hit.surface.t - t_enter;
      ++served_.primary_hits;
    }

    // The time.
    sc_core::sc_time start = clock_.now();
    sc_core::sc_time done;
    if (!grid) {
      // Every polygon streams through, fetched from the parameter memories (L544).
      const bool early = config_.shadow_early_exit && req.ray.kind == RayKind::Shadow;
      const std::uint64_t n = early ? tests : polygons_;
      const auto batch = pipe_.issue(n, start + times(stage, config_.fetch_stages));
      start = batch.first_issue - times(stage, config_.fetch_stages);
      // Fetch: one polygon a cycle, in step with the pipe, a fetch stage ahead of it.
      parameters.account_line_reads(n, start);
      done = batch.done + times(stage, config_.select_stages);
      // Latency: waiting for the pipe (none: this thread takes a ray only when the pipe can
      // accept its first polygon), the fetch stage(s) ahead of the first issue, then the
      // polygons, the pipe's depth and the closest-hit selection.
      probe_.add(journey, probe_pipeline_, LatencyPart::kQueueing, start - taken);
      probe_.add(journey, probe_memories_, LatencyPart::kService,
                 times(stage, config_.fetch_stages));
      probe_.add(journey, probe_pipeline_, LatencyPart::kService, done - batch.first_issue);
      trace_.slice("peripheral.pipeline", "ray", batch.first_issue,
                   batch.next_free - batch.first_issue, {{"ray", req.id}, {"polygons", n}});
      trace_.hop("peripheral.pipeline", "ray", req.id, batch.first_issue);
      clock_.catch_up(batch.next_free - times(stage, config_.fetch_stages));
    } else {
      // Auxiliary processor (L594-L596): it walks the n_d subvolumes along the ray at t_d each
      // (L654) and feeds the polygon addresses of each, through the indirection stage, into
      // the pipe at one per interval; it starts the next ray when it has fed the last address.
      // Its occupancy per ray is n_d t_d + n_i t_i, and the answer leaves the pipe t_l later:
      // Ullner's t_r (L648).
      start = std::max(start, aux_free_);
      const sc_core::sc_time walk = times(config_.step_time, cells);
      const sc_core::sc_time feed = times(stage, config_.indirection_stages + config_.fetch_stages);
      const auto batch = pipe_.issue(tests, start + walk + feed);
      // Fetch: in step with the pipe, a fetch stage ahead of it.
      parameters.account_line_reads(tests, batch.first_issue - times(stage, config_.fetch_stages));
      done = batch.done + times(stage, config_.select_stages);
      // Latency: waiting for the auxiliary processor, its walk and address indirection, the
      // fetch stage(s), waiting for the pipe, then the polygons, the pipe's depth and the
      // closest-hit selection.
      const sc_core::sc_time fed = start + walk + feed;
      probe_.add(journey, probe_aux_, LatencyPart::kQueueing, start - taken);
      probe_.add(journey, probe_aux_, LatencyPart::kService,
                 walk + times(stage, config_.indirection_stages));
      probe_.add(journey, probe_memories_, LatencyPart::kService,
                 times(stage, config_.fetch_stages));
      probe_.add(journey, probe_pipeline_, LatencyPart::kQueueing, batch.first_issue - fed);
      probe_.add(journey, probe_pipeline_, LatencyPart::kService, done - batch.first_issue);
      aux_free_ = std::max(start + walk, batch.next_free - feed);
      aux_->busy.record(start, aux_free_ - start);
      // The aux's busy interval (its busy signal), and the walk nested in it.
      if (aux_free_ > start) {
        trace_.slice("peripheral.aux", "ray", start, aux_free_ - start,
                     {{"ray", req.id}, {"subvolumes", cells}, {"polygons", tests}});
        trace_.hop("peripheral.aux", "ray", req.id, start);
      }
      if (walk > sc_core::SC_ZERO_TIME)
        trace_.slice("peripheral.aux", "walk", start, walk,
                     {{"ray", req.id}, {"subvolumes", cells}});
      if (tests > 0) {
        trace_.slice("peripheral.pipeline", "ray", batch.first_issue,
                     batch.next_free - batch.first_issue, {{"ray", req.id}, {"polygons", tests}});
        trace_.hop("peripheral.pipeline", "ray", req.id, batch.first_issue);
      }
      clock_.catch_up(aux_free_);
      aux_->dda_steps += steps;
      aux_->subvolumes_visited += cells;
    }
    served_.service += done - start;
    res.service_start = start;
    res.answered = done;
    // The answer crosses the result link into the host's result queue.
    res.arrived =
        result_link_.transfer(RayResult::kWireBits, done, done, {"result", "ray", req.id});
    probe_.add(journey, probe_result_link_, LatencyPart::kTransfer, res.arrived - done);
    modules::send_message(result_out, res, res.arrived, RayResult::kWireBits);
  }
}

}  // namespace rtsim::platform::ullner
