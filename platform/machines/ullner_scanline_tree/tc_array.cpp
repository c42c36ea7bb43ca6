#include "platform/machines/ullner_scanline_tree/tc_array.hpp"

#include <algorithm>

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
}  // namespace

void TcArray::declare_params(const modules::ParamDecls& tc) { tc.add(kInstructionTime); }

TcArray::TcArray(sc_core::sc_module_name name, MachineRun& run, const scanline::TcFrame& frame,
                 std::size_t leaves)
    : modules::Processor(name, run.trace()),
      params_(run.registry(), this->name()),
      run_(run),
      frame_(frame),
      program_(scanline::build_tc_program(frame.literals)),
      instruction_time_(params_.get(kInstructionTime)),
      leaves_(std::max(leaves, frame.polygons.size())) {
  // An idle scan converter (no polygon) gets no edge list: its stream is the dummy alone.
  for (std::size_t k = 0; k < leaves_; ++k)
    to_scp.push_back(std::make_unique<tlm_utils::simple_initiator_socket<TcArray>>(
        ("to_scp" + std::to_string(k)).c_str()));
  SC_THREAD(run);
}

void TcArray::run() {
  // The processors' memories, loaded by the bus (27 words a polygon, L1272), hear the program
  // in lockstep.
  std::uint64_t executed = 0;
  std::vector<ChainsMessage> out(leaves_);
  const auto chains = scanline::transform_and_clip(program_, frame_.polygons, &executed);
  for (std::size_t k = 0; k < chains.size(); ++k) {
    out[k].chains = chains[k];
    if (!chains[k].empty()) ++polygons_out_;
  }
  executed_ += executed;
  instructions_ += program_.total();
  // The frame's counts in the terms every machine reports (stats.json `rays`): a vertex's light
  // term (Fig. 3-11: n.p, no shadow) is the light's work, as a shadow ray is a ray tracer's.
  if (frame_.literals.point_light)
    run_.frame().counters().rays[static_cast<std::size_t>(RayKind::Shadow)] +=
        4 * frame_.polygons.size();
  // Lockstep: the program's length at the instruction time, whatever the number of processors.
  compute_for(instruction_time_ * static_cast<double>(program_.total()), "broadcast",
              {{"instructions", program_.total()}});
  done_ = clock_.now();
  for (std::size_t k = 0; k < out.size(); ++k)
    modules::send_message(*to_scp[k], out[k], clock_.now(), out[k].bits());
  clock_.sync();
}

}  // namespace rtsim::platform::ullner_scanline_tree
