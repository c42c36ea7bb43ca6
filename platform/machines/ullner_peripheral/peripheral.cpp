#include "platform/machines/ullner_peripheral/peripheral.hpp"

#include "firmware/tasks/ray_tree.hpp"
#include "modules/sim_time.hpp"
#include "platform/functional/scene_tracer.hpp"

namespace rtsim::platform::ullner {

using modules::times;
using params::ParamKind;

void Peripheral::declare_params(const modules::ParamDecls& peripheral) {
  peripheral.declare({.name = "intersect_interval",
                      .kind = ParamKind::kTime,
                      .default_value = "333.333 ns",
                      .min = "1 ps",
                      .description =
                          "Issue interval (= stage time) of the intersection pipeline: one "
                          "ray/polygon intersection per interval",
                      .source = "seed 000 L584, L588 (three results every microsecond)"});
  peripheral.count("adder_stages", "1", "1", "3", "stages",
                   "Pipeline stages of one floating-point addition (1 or 3); sets the "
                   "physical depth 17 or 33 and the latency 5.6 or 11 us",
                   "seed 000 L572-L578 (Fig. 2-17), L588");
  peripheral.declare(
      {.name = "fetch_stages",
       .kind = ParamKind::kInt,
       .default_value = "1",
       .min = "0",
       .max = "16",
       .unit = "stages",
       .description = "Stages of polygon fetch from the 20 parameter memories",
       .source = "assumption: one memory cycle reads a whole polygon (seed 000 L544)"});
  peripheral.declare(
      {.name = "select_stages",
       .kind = ParamKind::kInt,
       .default_value = "1",
       .min = "0",
       .max = "16",
       .unit = "stages",
       .description = "Stages of the closest-intersection selection (Fig. 2-11 stage 3)",
       .source = "assumption: one compare-and-keep stage (seed 000 L484)"});
  peripheral.count("ray_queue_depth", "16", "1", "1000000", "rays",
                   "Depth of the ray queue from the host to the peripheral",
                   "assumption: queue depths are not given (seed 000 L476)");
  peripheral.declare(
      {.name = "shadow_early_exit",
       .kind = ParamKind::kBool,
       .default_value = "false",
       .description = "Brute force: stop streaming polygons at a shadow ray's first hit",
       .source = "assumption: the thesis does not say how the shadow-ray saving is "
                 "realised without subdivision (seed 000 L472; note §7.6)"});
  peripheral.count("grid.divisions", "0", "0", "512", "per axis",
                   "Subvolumes per axis of the grid auxiliary processor; 0 = none "
                   "(brute force); at most 512 (512^3 subvolumes is the grid's limit, "
                   "kMaxGridCells = 2^27)",
                   "seed 000 L592-L606 (optimum 11 for 1000 polygons, L654)");
  peripheral.declare({.name = "grid.dda",
                      .kind = ParamKind::kString,
                      .default_value = "corrected",
                      .allowed = {"corrected", "as-printed"},
                      .description =
                          "Subvolume stepping: the corrected 3-D DDA, or Appendix B exactly "
                          "as printed (wrong; for fidelity experiments)",
                      .source = "seed 000 L2112-L2171; errata in note 000 §4.6"});
  peripheral.time("grid.step_time", "1 us", "t_d: time to step to the next subvolume",
                  "seed 000 L654");
  peripheral.count("grid.indirection_stages", "1", "0", "16", "stages",
                   "Extra pipeline stage(s) of the subvolume address indirection",
                   "seed 000 L596 (\"yet another pipeline stage\")");
  peripheral.declare({.name = "lighting.enabled",
                      .kind = ParamKind::kBool,
                      .default_value = "true",
                      .description = "Lighting extension: the host's vector arithmetic runs on the "
                                     "inner-product and reciprocal-square-root devices",
                      .source = "seed 000 L548-L566"});
  peripheral.count("lighting.rsqrt_stages", "2", "1", "16", "stages",
                   "Stages of the reciprocal-square-root device",
                   "assumption: as the square root of Fig. 2-17 (seed 000 L576)");
  peripheral.count("memory.polygons", "1048576", "1", "100000000", "polygons",
                   "Capacity of the 20 parameter memories",
                   "assumption: a million polygons (seed 000 note §7.5 S7)");
  peripheral.time("memory.load_word_time", "1 us",
                  "Time to load one 32-bit parameter word through the dual-ported "
                  "load path (before the frame; not part of the frame time)",
                  "assumption: \"the port need not be fast\" (seed 000 L544)");
  modules::Link::declare_params(
      peripheral.sub("result_link"),
      {.latency = "0 s",
       .lanes = "32",
       .bit_rate = "3 Mbit/s",
       .source = "assumption: the thesis gives no path for queue 2 (seed 000 L474-L476); a "
                 "word-wide path at the pipeline's stage rate, one word per 1/3 us (L584)"});
}

PeripheralSettings Peripheral::read_settings(const modules::ModuleParams& p) {
  PeripheralSettings c;
  c.intersect_interval = p.get_time("intersect_interval");
  c.adder_stages = static_cast<unsigned>(p.get_int("adder_stages"));
  c.pipeline_stages = PeripheralSettings::stages_for_adder(c.adder_stages);
  c.fetch_stages = static_cast<unsigned>(p.get_int("fetch_stages"));
  c.select_stages = static_cast<unsigned>(p.get_int("select_stages"));
  c.ray_queue_depth = p.get_count("ray_queue_depth");
  c.shadow_early_exit = p.get_bool("shadow_early_exit");
  c.grid_divisions = static_cast<int>(p.get_int("grid.divisions"));
  c.step_time = p.get_time("grid.step_time");
  c.indirection_stages = static_cast<unsigned>(p.get_int("grid.indirection_stages"));
  c.lighting = p.get_bool("lighting.enabled");
  c.rsqrt_stages = static_cast<unsigned>(p.get_int("lighting.rsqrt_stages"));
  c.load_word_time = p.get_time("memory.load_word_time");
  return c;
}

Peripheral::Peripheral(sc_core::sc_module_name name, functional::SceneGeometry& geometry,
                       const Tracer& twin_search, const tasks::ShadeTask& shade,
                       std::uint64_t polygons, const PeripheralSettings& config,
                       TraceCounters& counters, MachineTrace& trace, modules::LatencyProbe& probe,
                       const params::ParamRegistry& registry)
    : sc_core::sc_module(name),
      rays("ray_queue", config.ray_queue_depth),
      parameters("parameter_memories", polygons * kernels::kUllnerStoredWords,
                 kernels::kUllnerStoredWords, config.load_word_time, config.intersect_interval),
      result_out("result_out"),
      memory_test_(parameters, geometry),
      search_(functional::make_tracer_sharing(twin_search, geometry, &memory_test_)),
      shade_(shade),
      polygons_(polygons),
      config_(config),
      counters_(counters),
      trace_(trace),
      pipe_(std::string(this->name()) + ".pipeline", config.intersect_interval,
            config.pipeline_stages, "intersections"),
      probe_(probe),
      result_link_(modules::ModuleParams(registry, std::string(this->name()) + ".result_link")) {
  // Stages named by their stats.json module names, in the order a ray meets them.
  probe_ray_queue_ = probe.stage(rays.name());
  if (config.grid_divisions > 0) {
    aux_.emplace(std::string(this->name()) + ".aux");
    probe_aux_ = probe.stage(aux_->stat_path());
  }
  probe_memories_ = probe.stage(parameters.name());
  probe_pipeline_ = probe.stage(std::string(this->name()) + ".pipeline");
  probe_result_link_ = probe.stage(result_link_.name());
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
    ++rays_;
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
      travel_sum_ += res.hit.surface.t - t_enter;
      ++primary_hits_;
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
      if (aux_free_ > start)
        trace_.slice("peripheral.aux", "ray", start, aux_free_ - start,
                     {{"ray", req.id}, {"subvolumes", cells}, {"polygons", tests}});
      if (walk > sc_core::SC_ZERO_TIME)
        trace_.slice("peripheral.aux", "walk", start, walk,
                     {{"ray", req.id}, {"subvolumes", cells}});
      if (tests > 0)
        trace_.slice("peripheral.pipeline", "ray", batch.first_issue,
                     batch.next_free - batch.first_issue, {{"ray", req.id}, {"polygons", tests}});
      clock_.catch_up(aux_free_);
      aux_->dda_steps += steps;
      aux_->subvolumes_visited += cells;
    }
    service_total_ += done - start;
    res.service_start = start;
    res.answered = done;
    // The answer crosses the result link into the host's result queue.
    res.arrived = result_link_.transfer(RayResult::kWireBits, done);
    probe_.add(journey, probe_result_link_, LatencyPart::kTransfer, res.arrived - done);
    modules::send_message(result_out, res, res.arrived, RayResult::kWireBits);
  }
}

}  // namespace rtsim::platform::ullner
