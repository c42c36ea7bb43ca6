#pragma once
// A splitting processor of a split root (seed 000 §3.3.5, L1588-L1637, Fig. 3-25): it takes the
// segments of the merging processor below it one at a time, tests each against the screen's
// centre, breaks the ones that straddle it, and copies each part, re-scaled to full-screen
// coordinates (firmware/scanline/splitting.hpp), into the queue of its left or its right
// output. Each output queue (about a scan line of segments, L1633-L1637) drains over its own
// bit-serial link into a merging processor of the next stage: without the queues it could run
// only as fast as one output (L1590). A pass takes the merging processor's stages its work
// needs: the test (stage 1's comparisons) for a segment that goes whole, and the break's
// multiplications (stage 5's) as well for one that straddles.
#include <tlm_utils/simple_initiator_socket.h>

#include <algorithm>
#include <array>
#include <memory>
#include <systemc>

#include "firmware/scanline/splitting.hpp"
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

/// One output of a splitting processor: its queue and the link that drains it.
class SplittingOutput : public modules::Processor {
 public:
  SC_HAS_PROCESS(SplittingOutput);
  /// `parent`: the merging processor's input queue its link feeds.
  SplittingOutput(sc_core::sc_module_name name, MachineRun& run, std::size_t depth,
                  const modules::TimedFifo<SegmentMessage>& parent, const ProbeStages& stages);

  modules::MessageQueue<SegmentMessage> queue;
  tlm_utils::simple_initiator_socket<SplittingOutput> out;
  modules::Link link;

 private:
  void run();

  const modules::TimedFifo<SegmentMessage>& parent_;
  modules::LatencyProbe& probe_;
  ProbeStages stages_;
};

class SplittingNode : public modules::Processor {
 public:
  static constexpr const char* kClass = "sp";
  static void declare_params(const modules::ParamDecls& sp);
  static std::size_t queue_depth(const params::ParamRegistry& registry);
  /// Reads its class's parameters without building one: an unsplit tree has no splitting
  /// processor, but a value set for them is still checked (and counted as read).
  static void check_params(const params::ParamRegistry& registry);

  SC_HAS_PROCESS(SplittingNode);
  /// `left`, `right`: the merging processors' input queues its outputs feed.
  SplittingNode(sc_core::sc_module_name name, MachineRun& run,
                const modules::TimedFifo<SegmentMessage>& left,
                const modules::TimedFifo<SegmentMessage>& right, const ProbeStages& stages);

  /// Its input: the register the merging processor below shifts a segment into.
  modules::MessageQueue<SegmentMessage> in;
  std::array<std::unique_ptr<SplittingOutput>, 2> outputs;  ///< left, right

  /// The most segments its output queues held at once, each.
  int max_queued() const;
  /// The line of the last segment it took.
  int line() const { return line_; }
  /// The most segments one line brought to its input: what a queue must hold so that one
  /// output waits for the other's segments of a line without stopping the input (L1633-L1637).
  std::uint32_t line_segments_max() const { return std::max(line_max_, line_count_); }
  std::uint64_t broken() const { return broken_.value(); }

 private:
  void run();
  void enqueue(int side, SegmentMessage& m);

  modules::ModuleParams params_;
  sc_core::sc_time stage_time_;
  modules::LatencyProbe& probe_;
  ProbeStages stages_;
  std::array<tlm_utils::simple_initiator_socket<SplittingNode>, 2> to_output_{
      tlm_utils::simple_initiator_socket<SplittingNode>("to_left"),
      tlm_utils::simple_initiator_socket<SplittingNode>("to_right")};
  scanline::SplittingProcessor sp_;
  int line_ = -1;
  std::uint32_t line_count_ = 0, line_max_ = 0;
  modules::Counter whole_{*this, "whole", "segments that went whole to one side"};
  modules::Counter broken_{*this, "broken", "segments broken at the centre"};
  modules::Counter marks_{*this, "line_marks",
                          "line marks sent to an output with nothing of a line"};
};

}  // namespace rtsim::platform::ullner_scanline_tree
