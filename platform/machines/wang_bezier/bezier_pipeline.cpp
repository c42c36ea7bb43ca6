#include "platform/machines/wang_bezier/bezier_pipeline.hpp"

#include <algorithm>
#include <optional>

#include "common/input_error.hpp"
#include "firmware/kernels/culler_network.hpp"
#include "modules/sim_time.hpp"

namespace rtsim::platform::wang_bezier {

using modules::plus;
using modules::times;

namespace {

// The pipeline's parameters (pipeline.*), each named once.
const modules::TimeParam kCycleTime({.name = "cycle_time",
                                     .default_value = "6 ns",
                                     .description = "Clock period of the TMS320C6701 DSPs",
                                     .source = "seed 002 L436"});

/// A loop substage's pool of DSPs (Table 4): NAME.dsps and NAME.cycles, and the calls a job
/// makes of it.
struct Pool {
  modules::CountParam dsps, cycles;
  std::uint64_t units;
  std::string name() const { return dsps.name().substr(0, dsps.name().find('.')); }
};

Pool pool(const std::string& name, const char* dsps, const char* cycles, std::uint64_t units,
          const std::string& what, const char* source) {
  return {modules::CountParam({.name = name + ".dsps",
                               .default_value = dsps,
                               .min = "1",
                               .max = "100000",
                               .unit = "DSPs",
                               .description = "DSPs of the " + what + " substage",
                               .source = source}),
          modules::CountParam({.name = name + ".cycles",
                               .default_value = cycles,
                               .min = "1",
                               .max = "1000000000",
                               .unit = "cycles",
                               .description = "DSP cycles of one call in the " + what + " substage",
                               .source = source}),
          units};
}

// A loop stage (Table 4): 4 patches split in u, their 8 halves in v, 16 subpatches x 2 planes
// classified, 16 centres and distances, then the Culler.
const Pool kSplitU = pool("split_u", "4", "182", 4, "SplitInHalf (u: 4 patches into 8 halves)",
                          "seed 002 L437 (Table 4, substage 1)");
const Pool kSplitV = pool("split_v", "8", "182", 8, "SplitInHalf (v: 8 halves into 16 subpatches)",
                          "seed 002 L438 (Table 4, substage 2)");
const Pool kHull = pool("hull", "32", "112", 32, "HullClassification (16 subpatches x 2 planes)",
                        "seed 002 L439, L430 (112 cycles on one plane)");
const Pool kCenterDistance =
    pool("center_distance", "16", "130", 16, "PatchCenter + PatchDistance (16 subpatches)",
         "seed 002 L440 (102 + 28 cycles, Table 3)");

const modules::ChoiceParam kCullerKind(
    {.name = "culler.kind",
     .default_value = "asic",
     .allowed = {"asic", "software"},
     .description = "The Culler: the bitonic-network ASIC, or the software routine on one DSP "
                    "(the implementation without custom hardware)",
     .source = "seed 002 L302-L318, L432"});
const modules::TimeParam kCullerDelay(
    {.name = "culler.delay",
     .default_value = "800 ns",
     .description = "Delay of the Culler ASIC's 10-stage sorting network (not pipelined)",
     .source = "seed 002 L318"});
const modules::FlagParam kCullerPipelined(
    {.name = "culler.pipelined",
     .default_value = "false",
     .description = "Pipeline the Culler ASIC's 10 compare stages: it takes a job every "
                    "culler.delay / 10 and answers culler.delay later (spanning as many pipeline "
                    "cycles as that needs); false: a job occupies it for the whole delay",
     .source = "seed 002 L318: \"at most 800ns without any intra-stage pipelining\" (the "
               "pipelined network is a what-if)"});
const modules::CountParam kCullerSoftwareCycles({.name = "culler.software_cycles",
                                                 .default_value = "3081",
                                                 .min = "1",
                                                 .max = "1000000000",
                                                 .unit = "cycles",
                                                 .description = "DSP cycles of the software Culler",
                                                 .source = "seed 002 L432 (Table 3)"});
const modules::ChoiceParam kStage0Mapping(
    {.name = "stage0.mapping",
     .default_value = "split",
     .allowed = {"split", "subdivider"},
     .description = "Stage 0: SplitInHalf in u on 1 DSP then in v on 2, PlaneGenerator alongside "
                    "(split), or PlaneGenerator and PatchSubdivider on one DSP (subdivider, 243 + "
                    "36 cycles: the bottleneck)",
     .source = "assumption: the paper gives no stage-0 mapping (note 002 §4.5); split keeps it "
               "off the critical path"});
const modules::CountParam kSubdividerCycles(
    {.name = "stage0.subdivider_cycles",
     .default_value = "243",
     .min = "1",
     .max = "1000000000",
     .unit = "cycles",
     .description = "DSP cycles of PatchSubdivider (Table 2's last step; the earlier ones: 11478, "
                    "9018, 7803, 1284, 1257, 317)",
     .source = "seed 002 L415-L427"});
const modules::CountParam kPlaneCycles({.name = "stage0.plane_cycles",
                                        .default_value = "36",
                                        .min = "1",
                                        .max = "1000000000",
                                        .unit = "cycles",
                                        .description = "DSP cycles of PlaneGenerator",
                                        .source = "seed 002 L429 (Table 3)"});

const modules::ChoiceParam kAdvance(
    {.name = "advance",
     .default_value = "cycle",
     .allowed = {"cycle", "when_done"},
     .description = "How a job moves on: every substage holds it for whole pipeline cycles, the "
                    "slowest substage's time (cycle: a lock-step pipeline, a job leaves after "
                    "(stage 0's substages + 5 N) cycles), or as soon as the substage is done and "
                    "the next buffer has room (when_done: self-timed, its latency the sum of "
                    "the substages' times)",
     .source = "seed 002 L437 (\"pipeline cycle\"); note 002 L341: the paper does not say how "
               "substages hand on (the two latencies it allows)"});
const modules::CountParam kBufferDepth(
    {.name = "buffer_depth",
     .default_value = "1",
     .min = "1",
     .max = "1024",
     .unit = "jobs",
     .description = "Jobs the buffer in front of each substage holds: a finished job waits in "
                    "its substage until the next one's buffer has room",
     .source = "assumption: the paper gives no buffering (note 002 L306: depth 1)"});
const modules::IntParam kDeadStage(
    {.name = "fault.dead_stage",
     .default_value = "0",
     .min = "0",
     .max = "30",
     .unit = "loop stage",
     .description = "A fault: this loop stage is dead and passes every job on unchanged (no "
                    "split, no hull test, no cull; its timing stays); 0 for none",
     .source = "fault model: a dead stage of the unrolled pipeline",
     .affects_image = true});
const modules::ChoiceParam kInterconnect(
    {.name = "interconnect",
     .default_value = "none",
     .allowed = {"none", "link"},
     .description = "Between substages: none (a job is in the next buffer the moment it is "
                    "handed on: Table 4's assumption) or a kit link each (pipeline.link.*) "
                    "carrying the job's words (up to 847 after PatchCenter + PatchDistance)",
     .source = "assumption: the paper gives no interconnect (note 002 §4)"});
constexpr const char* kLink = "link";
const modules::Link::Defaults kLinkDefaults{
    .latency = "0 s",
    .lanes = "32",
    .bit_rate = "",
    .bit_time = "6 ns",
    .source = "assumption: a 32-bit word a DSP cycle (6 ns, L436); the paper gives none"};

}  // namespace

void BezierPipeline::declare_params(const modules::ParamDecls& p) {
  p.add(kCycleTime);
  for (const Pool* pool : {&kSplitU, &kSplitV, &kHull, &kCenterDistance}) {
    p.add(pool->dsps);
    p.add(pool->cycles);
  }
  p.add(kCullerKind);
  p.add(kCullerDelay);
  p.add(kCullerPipelined);
  p.add(kCullerSoftwareCycles);
  p.add(kStage0Mapping);
  p.add(kSubdividerCycles);
  p.add(kPlaneCycles);
  p.add(kAdvance);
  p.add(kBufferDepth);
  p.add(kInterconnect);
  p.add(kDeadStage);
  modules::Link::declare_params(p.sub(kLink), kLinkDefaults);
}

namespace {

/// A DSP pool's substage: `units` calls of `cycles` on `dsps` DSPs, ceil(units / dsps) rounds.
SubstageSpec pool_spec(std::string name, SubstageWork work, unsigned dsps, std::uint64_t units,
                       std::uint64_t cycles, const sc_core::sc_time& cycle_time) {
  const sc_core::sc_time t = times(cycle_time, ((units + dsps - 1) / dsps) * cycles);
  return {std::move(name), work, {dsps, units, cycles}, {t, t, t}};
}

}  // namespace

BezierPipeline::BezierPipeline(sc_core::sc_module_name name, const params::ParamRegistry& r,
                               int loop_stages, int culler_key_bits,
                               const kernels::WangArithmetic& arithmetic)
    : sc_core::sc_module(name),
      modules::StatGroup(sc_core::sc_module::name()),
      input("input", 1),
      result_out("result_out"),
      arithmetic_(arithmetic) {
  const modules::ModuleParams p(r, this->name());
  const sc_core::sc_time t = p.get(kCycleTime);
  const auto loop_pool = [&](const Pool& pool, SubstageWork work) {
    return pool_spec(pool.name(), work, static_cast<unsigned>(p.get(pool.dsps)), pool.units,
                     p.get(pool.cycles), t);
  };
  std::vector<SubstageSpec> loop = {loop_pool(kSplitU, SubstageWork::kSplitU),
                                    loop_pool(kSplitV, SubstageWork::kSplitV),
                                    loop_pool(kHull, SubstageWork::kHull),
                                    loop_pool(kCenterDistance, SubstageWork::kCenterDistance)};
  kernels::CullerConfig culler;
  culler.key_bits = culler_key_bits;
  // Read whichever Culler and stage-0 mapping is chosen (so a misspelt name is always caught).
  const std::uint64_t software_cycles = p.get(kCullerSoftwareCycles);
  const std::uint64_t subdivider_cycles = p.get(kSubdividerCycles);
  if (p.get(kCullerKind) == "asic") {
    culler.network = true;  // the bitonic network (L310); the software sorts (Culler::select)
    const sc_core::sc_time delay = p.get(kCullerDelay);
    // Pipelined: a new job every compare stage, the answer still a whole delay later.
    const sc_core::sc_time issue =
        p.get(kCullerPipelined) ? delay / static_cast<double>(kernels::CullerNetwork::kStages)
                                : delay;
    loop.push_back({"culler", SubstageWork::kCull, {}, {delay, issue, delay}});
  } else {
    loop.push_back(pool_spec("culler", SubstageWork::kCull, 1, 1, software_cycles, t));
  }
  // Stage 0 (L284): the first split and the planes.
  std::vector<SubstageSpec> stage0;
  const std::uint64_t plane = p.get(kPlaneCycles);
  if (p.get(kStage0Mapping) == "split") {
    // SplitInHalf in u on one DSP, PlaneGenerator on another alongside; then v on two.
    const std::uint64_t half = p.get(kSplitU.cycles);
    stage0 = {pool_spec("split_u", SubstageWork::kPlanesSplitU, 2, 2, std::max(half, plane), t),
              pool_spec("split_v", SubstageWork::kSplitVOutput, 2, 2, half, t)};
  } else {
    stage0 = {
        pool_spec("subdivider", SubstageWork::kSubdivider, 1, 1, subdivider_cycles + plane, t)};
  }
  // The pipeline cycle: the slowest substage's issue interval (L437). Advancing by it, every
  // substage holds a job whole cycles.
  sc_core::sc_time cycle = sc_core::SC_ZERO_TIME;
  for (const auto* specs : {&stage0, &loop})
    for (const SubstageSpec& s : *specs) cycle = std::max(cycle, s.timing.issue);
  if (p.get(kAdvance) == "cycle")
    for (auto* specs : {&stage0, &loop})
      for (SubstageSpec& s : *specs) {
        std::uint64_t slots = 1;
        while (times(cycle, slots) < s.timing.latency) ++slots;
        s.timing.issue = cycle;
        s.timing.latency = times(cycle, slots);
      }
  std::optional<modules::ModuleParams> link;
  if (p.get(kInterconnect) == "link") {
    link.emplace(r, std::string(this->name()) + "." + kLink);
  } else {
    // Read (and so checked) whatever the interconnect: a link parameter set without it is
    // harmless, not a misspelling.
    const modules::ModuleParams unused(r, std::string(this->name()) + "." + kLink);
    (void)unused.get_time("latency");
    (void)unused.get_count("lanes");
    (void)unused.get_time("bit_time");
  }
  const Substage::Shared shared{.buffer_depth = p.get(kBufferDepth),
                                .culler = culler,
                                .arithmetic = arithmetic,
                                .link = link ? &*link : nullptr};
  stage0_ = std::make_unique<PipelineStage>("stage0", stage0, shared);
  for (int s = 1; s <= loop_stages; ++s)
    loops_.push_back(
        std::make_unique<PipelineStage>(("loop" + std::to_string(s)).c_str(), loop, shared));
  if (const std::int64_t dead = p.get(kDeadStage); dead > 0) {
    if (dead > loop_stages)
      throw InputError(p.path_of(kDeadStage.name()), 0,
                       "the pipeline has loop stages 1 to " + std::to_string(loop_stages) +
                           " (bezier.iterations)");
    for (const auto& sub : loops_[static_cast<std::size_t>(dead - 1)]->substages())
      sub->set_dead(true);
  }
  // Wire the chain: input -> stage 0 -> loop 1 -> ... -> loop N -> output.
  for (const auto& sub : stage0_->substages()) chain_.push_back(sub.get());
  for (const auto& stage : loops_)
    for (const auto& sub : stage->substages()) chain_.push_back(sub.get());
  entry_.bind(chain_.front()->in);
  for (std::size_t k = 0; k + 1 < chain_.size(); ++k) {
    chain_[k]->out.bind(chain_[k + 1]->in);
    chain_[k]->set_next(chain_[k + 1]);
  }
  chain_.back()->out.bind(exit_);
  exit_.register_b_transport(this, &BezierPipeline::leave);
  SC_THREAD(run);
}

void BezierPipeline::set_faults(std::vector<JobFault> faults) {
  faults_ = std::move(faults);
  for (JobFault& f : faults_)
    if (f.stage > 0)
      loops_[static_cast<std::size_t>(f.stage - 1)]->substages().front()->add_fault(f);
}

void BezierPipeline::run() {
  Substage& first = *chain_.front();
  for (;;) {
    modules::wait_for_item(input.fifo, clock_);
    // Stage 0 takes the job once its first substage is free.
    sc_core::sc_time accepted;
    JobInFlight& f = flight_;  // one job in the chain at a time: its payload reused
    f.job = input.fifo.get(std::max(clock_.now(), first.free()), accepted);
    for (JobFault& fault : faults_)
      if (fault.stage == 0) fault.apply(f.job);  // as it arrived over the host's link
    clock_.catch_up(accepted);
    f.accepted = accepted;
    f.waited = accepted > f.job.arrived;
    ++jobs_;
    modules::send_message(entry_, f, accepted, PatchJob::kWireBits);
    busy_.record(accepted, first.free() - accepted);
  }
}

void BezierPipeline::leave(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  JobInFlight& f = *gp.get_extension<modules::MessageExtension<JobInFlight>>()->message();
  const sc_core::sc_time left = modules::sim_now() + delay;
  // Jobs leave in the order they entered: one that waited to enter left a cycle of the full
  // pipeline after the one before it.
  if (f.waited && jobs_.value() > 1) {
    ++kept_full_;
    kept_full_time_ += left - last_left_;
  }
  last_left_ = left;
  const sc_core::sc_time transit = left - f.accepted;
  transit_.add(transit);
  if (shortest_transit_ == sc_core::SC_ZERO_TIME || transit < shortest_transit_)
    shortest_transit_ = transit;
  leaving_.erase(std::remove_if(leaving_.begin(), leaving_.end(),
                                [&](const sc_core::sc_time& l) { return l <= f.accepted; }),
                 leaving_.end());
  leaving_.push_back(left);
  in_flight_peak_.note(leaving_.size());

  JobResult res;
  res.ray = f.job.ray;
  res.slot = f.job.slot;
  res.sent = f.job.sent;
  res.accepted = f.accepted;
  res.left = left;
  // What left the last stage, its words as the host reads them (a single's value is exact in
  // double).
  if (arithmetic_.wide()) {
    res.result = kernels::wang_output(f.wide, loop_stages(), counters_);
  } else {
    const kernels::WangResult<float> r = kernels::wang_output(f.w, loop_stages(), counters_);
    res.result = {.hit = r.hit,
                  .point = Vec3T<double>(r.point),
                  .u = r.u,
                  .v = r.v,
                  .level = r.level,
                  .survivors = r.survivors};
  }
  if (res.result.hit) ++hits_;
  modules::send_message(result_out, res, left, JobResult::kWireBits);
  delay = sc_core::SC_ZERO_TIME;
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
}

}  // namespace rtsim::platform::wang_bezier
