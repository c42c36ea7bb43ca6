#pragma once
// The host at the hidden-line pipe's input (seed 000 L1723-L1737): it loads the scene's boundary
// planes down the plane path (five wires of their own, L1906, double-buffered: the next scene
// loads while this one runs) and sends the scene's polygon edges as segment messages, then the
// end of the stream, into the first processor over its link. A kit processor: it is blocked
// while its link or the first processor's register is not free, and then waits for the divider
// to be done with the stream (the frame's end).
#include <tlm_utils/simple_initiator_socket.h>

#include <cstdint>
#include <systemc>
#include <vector>

#include "firmware/hiddenline/messages.hpp"
#include "modules/latency_probe.hpp"
#include "modules/link.hpp"
#include "modules/processor.hpp"
#include "modules/statistics.hpp"
#include "platform/machines/ullner_hidden_line/hidden_line_pipe.hpp"
#include "platform/machines/ullner_hidden_line/in_flight.hpp"

namespace rtsim::platform {
class MachineRun;
}

namespace rtsim::platform::ullner_hidden_line {

class PipeHost : public modules::Processor {
 public:
  static constexpr const char* kName = "host";

  tlm_utils::simple_initiator_socket<PipeHost> out{"out"};

  SC_HAS_PROCESS(PipeHost);
  /// Sends `stream` (segments, then the end) into `pipe`, after loading its `planes` planes.
  PipeHost(sc_core::sc_module_name name, MachineRun& run, HiddenLinePipe& pipe,
           std::vector<hiddenline::Message> stream, std::size_t planes);

  /// When the last plane was in place (the load this scene's planes took on the plane path).
  const sc_core::sc_time& planes_loaded() const { return planes_loaded_; }
  /// When the host handed each segment to its link (by edge number).
  const std::vector<sc_core::sc_time>& handed() const { return handed_; }
  /// The frame's end: the divider done with the stream.
  const sc_core::sc_time& frame_end() const { return frame_end_; }

  /// Latency probe: follow every segment from the host to the divider.
  void follow(std::vector<modules::LatencyProbe::Journey>* journeys, int link_stage) {
    journeys_ = journeys;
    probe_link_ = link_stage;
  }

 private:
  void run();

  MachineRun& run_;
  HiddenLinePipe& pipe_;
  std::vector<hiddenline::Message> stream_;
  std::size_t planes_;
  modules::Link link_;
  modules::Link plane_link_;
  std::uint64_t word_bits_;
  std::vector<sc_core::sc_time> handed_;
  sc_core::sc_time planes_loaded_ = sc_core::SC_ZERO_TIME, frame_end_ = sc_core::SC_ZERO_TIME;
  std::vector<modules::LatencyProbe::Journey>* journeys_ = nullptr;
  int probe_link_ = -1;
  modules::Counter segments_{*this, "segments", "segments sent into the pipe"};
  modules::Counter planes_sent_{*this, "planes", "planes loaded on the plane path"};
};

}  // namespace rtsim::platform::ullner_hidden_line
