#pragma once
// The divider at the hidden-line pipe's end (seed 000 L1765: "the plane processors can save a
// division ... simply by representing the parameter t as a rational number", one divider where
// the pipe ends): it takes the pipe's output stream, one message at a time over the last
// link, divides each hidden part's ends (a marked intersection, t = t_n / t_d) and hands the
// visible pieces of every segment to the display (firmware/hiddenline/pipe.hpp `divide`). It
// holds one message: a message is accepted once the division of the one before is done.
#include <tlm_utils/simple_target_socket.h>

#include <cstdint>
#include <systemc>
#include <vector>

#include "firmware/hiddenline/pipe.hpp"
#include "modules/module_params.hpp"
#include "modules/statistics.hpp"

namespace rtsim::platform::ullner_hidden_line {

class DividerNode : public sc_core::sc_module, public modules::StatGroup {
 public:
  static constexpr const char* kName = "divider";
  static void declare_params(const modules::ParamDecls& divider);

  tlm_utils::simple_target_socket<DividerNode> in;

  DividerNode(sc_core::sc_module_name name, const params::ParamRegistry& registry);

  /// When it last accepted a message (its register was freed then).
  const sc_core::sc_time& register_free() const { return accepted_; }
  /// The stream it received, in order: what it divides.
  const std::vector<hiddenline::Message>& received() const { return received_; }
  /// When each segment (by its edge number) reached it; the stream's end's.
  const std::vector<std::pair<std::uint32_t, sc_core::sc_time>>& segment_arrivals() const {
    return segment_arrivals_;
  }
  /// When it was done with the end of the stream (the frame's end); zero before.
  const sc_core::sc_time& finished() const { return finished_; }
  bool ended() const { return ended_; }

 private:
  void b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay);

  sc_core::sc_time division_time_;
  sc_core::sc_time accepted_ = sc_core::SC_ZERO_TIME, done_ = sc_core::SC_ZERO_TIME,
                   finished_ = sc_core::SC_ZERO_TIME;
  bool ended_ = false;
  std::vector<hiddenline::Message> received_;
  std::vector<std::pair<std::uint32_t, sc_core::sc_time>> segment_arrivals_;
  modules::Counter segments_{*this, "segments", "segments that came out of the pipe"};
  modules::Counter marked_{*this, "divisions",
                           "hidden parts' ends divided (marked intersections, t = t_n / t_d)"};
  modules::Counter unmarked_{*this, "unmarked_intersections",
                             "intersections that came out unmarked (no polygon's hidden part)"};
  modules::Busy busy_{*this, "time dividing"};
};

}  // namespace rtsim::platform::ullner_hidden_line
