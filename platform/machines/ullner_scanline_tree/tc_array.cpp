#include "platform/machines/ullner_scanline_tree/tc_array.hpp"

#include <algorithm>
#include <utility>

#include "firmware/scanline/tree_frame.hpp"
#include "platform/machines/machine_run.hpp"

namespace rtsim::platform::ullner_scanline_tree {

namespace {
const modules::TimeParam kInstructionTime(
    {.name = "instruction_time",
     .default_value = "6.5 us",
     .description = "time of one broadcast instruction (every processor executes it at once)",
     .source = "seed 000 L1276, L1334: \"some six or seven microseconds\" (a 5 us shift-and-add "
               "floating-point operation, L1276)"});
const modules::CountParam kMotion(
    {.name = "motion_instructions",
     .default_value = "0",
     .min = "0",
     .max = "100000000",
     .unit = "instructions",
     .description = "instructions broadcast a frame besides the program: loading the "
                    "transformation matrices of objects that move (a what-if: more than the "
                    "spare ~1000 and the frames' versions come late and are re-scanned)",
     .source = "seed 000 L1336: the nearly 1400 spare instructions \"may be put to good use\" "
               "for independently moving objects"});
}  // namespace

void TcArray::declare_params(const modules::ParamDecls& tc) {
  tc.add(kInstructionTime);
  tc.add(kMotion);
}

sc_core::sc_time TcArray::instruction_time(const params::ParamRegistry& registry) {
  return modules::ModuleParams(registry, kName).get(kInstructionTime);
}

std::uint64_t TcArray::motion_instructions(const params::ParamRegistry& registry) {
  return modules::ModuleParams(registry, kName).get(kMotion);
}

TcArray::TcArray(sc_core::sc_module_name name, MachineRun& run, int versions, Loader load)
    : modules::Processor(name, run.trace()),
      versions(std::string(this->name()) + ".versions", modules::TimedFifo<int>::kUnbounded),
      shown(std::string(this->name()) + ".shown", modules::TimedFifo<int>::kUnbounded),
      params_(run.registry(), this->name()),
      run_(run),
      load_(std::move(load)),
      instruction_time_(params_.get(kInstructionTime)),
      motion_(params_.get(kMotion)),
      chains_(static_cast<std::size_t>(versions)) {
  SC_THREAD(run);
}

void TcArray::run() {
  for (std::size_t v = 0; v < chains_.size(); ++v) {
    if (v > 0) {
      // Version v - 1 is on the screen: the processors' memories are free for version v.
      const sc_core::sc_time since = clock_.now();
      modules::wait_for_item(shown, clock_);
      sc_core::sc_time taken;
      (void)shown.get(clock_.now(), taken);
      clock_.catch_up(taken);
      waited_since(since, Wait::kWork);
    }
    // The processors' memories, loaded by the bus (27 words a polygon, L1272), hear the program
    // in lockstep.
    const scanline::TcFrame& frame = load_(static_cast<int>(v));
    std::uint64_t executed = 0;
    // The view is in the program's literals (Figs. 3-10, 3-11): each version's own broadcast.
    // The first's is the array's program (its counts, Fig. 3-16).
    scanline::BroadcastProgram later;
    (v == 0 ? program_ : later) = scanline::build_tc_program(frame.literals);
    const scanline::BroadcastProgram& program = v == 0 ? program_ : later;
    chains_[v] = scanline::transform_and_clip(program, frame.polygons, &executed);
    for (const auto& c : chains_[v])
      if (!c.empty()) ++polygons_out_;
    executed_ += executed;
    instructions_ += instructions_a_version();
    // The frame's counts in the terms every machine reports (stats.json `rays`): a vertex's
    // light term (Fig. 3-11: n.p, no shadow) is the light's work, as a shadow ray is a ray
    // tracer's.
    if (frame.literals.point_light)
      run_.frame().counters().rays[static_cast<std::size_t>(RayKind::Shadow)] +=
          4 * frame.polygons.size();
    // Lockstep: the program's length at the instruction time, whatever the number of
    // processors.
    compute_for(instruction_time_ * static_cast<double>(instructions_a_version()), "broadcast",
                {{"instructions", instructions_a_version()}, {"version", v}});
    if (v == 0) done_ = clock_.now();
    versions.put(static_cast<int>(v), clock_.now());
  }
  clock_.sync();
}

}  // namespace rtsim::platform::ullner_scanline_tree
