#pragma once
// The T&C processors on their shared bus (seed 000 §3.3.1, L1096-L1336): one processor a
// polygon, the program broadcast from the bus's end and executed in lockstep (SIMD, L1100-
// L1102), so the array takes the program's length times the instruction time (6-7 us, L1276,
// L1334) whatever its size. It then hands each processor's edge chains (what its `send`s
// wrote) to that processor's scan conversion processor.
#include <tlm_utils/simple_initiator_socket.h>

#include <memory>
#include <systemc>
#include <vector>

#include "firmware/scanline/tc_frame.hpp"
#include "firmware/scanline/tc_program.hpp"
#include "modules/message_channel.hpp"
#include "modules/module_params.hpp"
#include "modules/processor.hpp"
#include "platform/machines/ullner_scanline_tree/tree_messages.hpp"

namespace rtsim::platform {
class MachineRun;
}

namespace rtsim::platform::ullner_scanline_tree {

class TcArray : public modules::Processor {
 public:
  static constexpr const char* kName = "tc";
  static void declare_params(const modules::ParamDecls& tc);

  SC_HAS_PROCESS(TcArray);
  /// `leaves` (at least the frame's polygons): the scan converters, idle ones past the last
  /// polygon (a split tree's, or a scene without polygons).
  TcArray(sc_core::sc_module_name name, MachineRun& run, const scanline::TcFrame& frame,
          std::size_t leaves);

  /// Scan converter k's queue (bound before the simulation): polygon k's, or an idle one's.
  std::vector<std::unique_ptr<tlm_utils::simple_initiator_socket<TcArray>>> to_scp;

  /// When the broadcast ended and the edge lists went to the scan converters.
  sc_core::sc_time done() const { return done_; }
  const scanline::BroadcastProgram& program() const { return program_; }
  sc_core::sc_time instruction_time() const { return instruction_time_; }

 private:
  void run();

  modules::ModuleParams params_;
  MachineRun& run_;
  const scanline::TcFrame& frame_;
  scanline::BroadcastProgram program_;
  sc_core::sc_time instruction_time_;
  sc_core::sc_time done_ = sc_core::SC_ZERO_TIME;
  std::size_t leaves_;
  modules::Counter instructions_{*this, "instructions", "instructions broadcast"};
  modules::Counter executed_{*this, "executed",
                             "instructions the processors executed (not shut down), summed"};
  modules::Counter polygons_out_{*this, "polygons_out",
                                 "polygons left with an edge list after clipping"};
};

}  // namespace rtsim::platform::ullner_scanline_tree
