#pragma once
// A scan conversion processor (seed 000 §3.3.2, L1338-L1352): it takes its T&C processor's edge
// chains, steps its two endpoint trackers down the scan lines and sends a segment a line, in
// raster order, then the dummy, over its bit-serial link — one wire a word, 12 bits a wire
// (L1348) — into the input queue of the merging processor above it. Its computation is trivial
// (L1348: communication dominates), so the link sets its pace.
#include <tlm_utils/simple_initiator_socket.h>

#include <systemc>

#include "modules/latency_probe.hpp"
#include "modules/link.hpp"
#include "modules/message_channel.hpp"
#include "modules/module_params.hpp"
#include "modules/processor.hpp"
#include "platform/machines/ullner_scanline_tree/tree_messages.hpp"

namespace rtsim::platform {
class MachineRun;
}

namespace rtsim::platform::ullner_scanline_tree {

class ScanConverterNode : public modules::Processor {
 public:
  static constexpr const char* kClass = "scp";
  /// Its class's parameters (every scan converter's), under kClass.
  static void declare_params(const modules::ParamDecls& scp);

  SC_HAS_PROCESS(ScanConverterNode);
  /// The scan converter of polygon `polygon`, on a screen of `lines`; `parent`: the queue its
  /// link feeds (it waits there for room).
  ScanConverterNode(sc_core::sc_module_name name, MachineRun& run, std::uint32_t polygon, int lines,
                    const modules::TimedFifo<SegmentMessage>& parent, const ProbeStages& stages);

  modules::MessageQueue<ChainsMessage> in;  ///< from its T&C processor
  tlm_utils::simple_initiator_socket<ScanConverterNode> out;
  modules::Link link;  ///< up to its merging processor

 private:
  void run();

  modules::ModuleParams params_;
  std::uint32_t polygon_;
  int lines_;
  const modules::TimedFifo<SegmentMessage>& parent_;
  sc_core::sc_time segment_time_;
  modules::LatencyProbe& probe_;
  ProbeStages stages_;
  modules::Counter segments_{*this, "segments", "segments sent (the dummy not counted)"};
};

}  // namespace rtsim::platform::ullner_scanline_tree
