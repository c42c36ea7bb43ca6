#include "platform/machines/wang_bezier/bezier_pipeline.hpp"

#include <algorithm>

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
}

BezierPipeline::BezierPipeline(sc_core::sc_module_name name, const params::ParamRegistry& r,
                               int loop_stages, int culler_key_bits)
    : sc_core::sc_module(name),
      modules::StatGroup(sc_core::sc_module::name()),
      input("input", 1),
      result_out("result_out"),
      loop_stages_(loop_stages) {
  const modules::ModuleParams p(r, this->name());
  const sc_core::sc_time t = p.get(kCycleTime);
  const auto substage = [&](const Pool& pool) {
    Substage s;
    s.name = pool.name();
    s.dsps = static_cast<unsigned>(p.get(pool.dsps));
    s.units = pool.units;
    s.cycles = p.get(pool.cycles);
    s.time = times(t, ((s.units + s.dsps - 1) / s.dsps) * s.cycles);
    return s;
  };
  loop_ = {substage(kSplitU), substage(kSplitV), substage(kHull), substage(kCenterDistance)};
  Substage culler;
  culler.name = "culler";
  const sc_core::sc_time asic_delay = p.get(kCullerDelay);
  const std::uint64_t software_cycles = p.get(kCullerSoftwareCycles);
  culler_.key_bits = culler_key_bits;
  if (p.get(kCullerKind) == "asic") {
    culler_.network = true;  // the bitonic network (L310); the software sorts (Culler::select)
    culler.time = asic_delay;
    if (p.get(kCullerPipelined)) {
      // A new job every compare stage; the answer still a whole delay later.
      culler.time = asic_delay / static_cast<double>(kernels::CullerNetwork::kStages);
      culler_delay_ = asic_delay;
    }
  } else {
    culler.dsps = 1;
    culler.units = 1;
    culler.cycles = software_cycles;
    culler.time = times(t, culler.cycles);
  }
  loop_.push_back(culler);
  // Stage 0 (L284): the first split and the planes.
  const std::uint64_t plane = p.get(kPlaneCycles);
  const std::uint64_t subdivider = p.get(kSubdividerCycles);
  if (p.get(kStage0Mapping) == "split") {
    const std::uint64_t half = p.get(kSplitU.cycles);
    stage0_ = {
        Substage{"stage0.split_u", 1, 1, std::max(half, plane), times(t, std::max(half, plane))},
        Substage{"stage0.split_v", 2, 2, half, times(t, half)}};
  } else {
    const std::uint64_t c = subdivider + plane;
    stage0_ = {Substage{"stage0.subdivider", 1, 1, c, times(t, c)}};
  }
  cycle_ = sc_core::SC_ZERO_TIME;
  for (const auto& s : stage0_) cycle_ = std::max(cycle_, s.time);
  for (const auto& s : loop_) cycle_ = std::max(cycle_, s.time);
  // A job moves one substage a cycle; a pipelined Culler's answer may take several.
  culler_slots_ = 1;
  while (times(cycle_, culler_slots_) < culler_delay_) ++culler_slots_;
  latency_ = times(cycle_, stage0_.size() + (loop_.size() - 1 + culler_slots_) *
                                                static_cast<std::uint64_t>(loop_stages));
  for (const auto& sub : loop_) substages_.push_back(std::make_unique<SubstageStats>(*this, sub));
  SC_THREAD(run);
}

void BezierPipeline::run() {
  sc_core::sc_time next_accept = sc_core::SC_ZERO_TIME;
  const std::uint64_t stage0_slots = stage0_.size();
  for (;;) {
    modules::wait_for_item(input.fifo, clock_);
    // Stage 0 takes the job once the previous one is a cycle in.
    sc_core::sc_time accepted;
    PatchJob job = input.fifo.get(std::max(clock_.now(), next_accept), accepted);
    for (JobFault& f : faults_) f.apply(job);  // as it arrived over the host's link
    clock_.catch_up(accepted);
    next_accept = plus(accepted, cycle_);
    busy_.record(accepted, cycle_);
    for (std::size_t k = 0; k < loop_.size(); ++k)
      substages_[k]->busy.record(plus(accepted, times(cycle_, stage0_slots + k)), loop_[k].time);
    ++jobs_;

    // The data: stage 0, every loop stage, the last stage's output.
    auto w = kernels::wang_stage0(job.net, job.o, job.d, counters_);
    for (int s = 0; s < loop_stages_; ++s) kernels::wang_loop_stage(w, counters_, culler_);
    JobResult res;
    res.ray = job.ray;
    res.slot = job.slot;
    res.sent = job.sent;
    res.accepted = accepted;
    res.result = kernels::wang_output(w, loop_stages_, counters_);
    if (res.result.hit) ++hits_;

    const sc_core::sc_time leaves = plus(accepted, latency_);
    res.left = leaves;
    leaving_.erase(std::remove_if(leaving_.begin(), leaving_.end(),
                                  [&](const sc_core::sc_time& l) { return l <= accepted; }),
                   leaving_.end());
    leaving_.push_back(leaves);
    in_flight_peak_.note(leaving_.size());
    modules::send_message(result_out, res, leaves, JobResult::kWireBits);
  }
}

}  // namespace rtsim::platform::wang_bezier
