#pragma once
// A merging processor of the tree (seed 000 §3.3.3, L1354-L1519): two input queues ("short
// queues on the inputs", L1519), one segment held from each, the six-step algorithm
// (firmware/scanline/merging.hpp) on what they hold, and each output segment sent over its
// bit-serial link into the queue above it. A pass takes the stages of Fig. 3-22 its case needs
// (L1457, L1519: 3 us a stage; 3 us apart, 6 us overlapping, 15 us intersecting).
#include <tlm_utils/simple_initiator_socket.h>

#include <systemc>

#include "firmware/scanline/merging.hpp"
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

class MergingNode : public modules::Processor {
 public:
  static constexpr const char* kClass = "mp";
  static void declare_params(const modules::ParamDecls& mp);
  /// The depth of a merging processor's input queues (the scan converters' links feed them).
  static std::size_t queue_depth(const params::ParamRegistry& registry);

  SC_HAS_PROCESS(MergingNode);
  /// `parent`: the queue its link feeds.
  MergingNode(sc_core::sc_module_name name, MachineRun& run,
              const modules::TimedFifo<SegmentMessage>& parent, const ProbeStages& stages);

  modules::MessageQueue<SegmentMessage> in0, in1;
  tlm_utils::simple_initiator_socket<MergingNode> out;
  modules::Link link;

  /// Its passes by case (scanline::MergeCase).
  const modules::CounterArray& passes() const { return passes_; }

 private:
  void run();

  modules::ModuleParams params_;
  const modules::TimedFifo<SegmentMessage>& parent_;
  sc_core::sc_time stage_time_;
  scanline::MergingProcessor mp_;
  modules::LatencyProbe& probe_;
  ProbeStages stages_;
  /// When each input's held segment was taken from its queue (a part kept across passes keeps
  /// its segment's time).
  sc_core::sc_time taken_at_[2];
  modules::CounterArray passes_;
  modules::Counter segments_{*this, "segments_out", "segments sent (the dummy not counted)"};
};

}  // namespace rtsim::platform::ullner_scanline_tree
