#pragma once
// The array's frame-buffer readout (seed 000 L781: "additional hardware allows pixel values to be
// shifted out of the frame buffer in scan line order"): once the termination detector holds all
// the credit, it shifts the image out of the processors' blocks (ArrayNode::frame_buffer), row
// after row, one pixel each readout.pixel_time, into the frame the run writes. The image is what
// it reads out of those memories; the frame ends when it has.
#include <optional>
#include <systemc>
#include <vector>

#include "modules/mesh_topology.hpp"
#include "modules/module_params.hpp"
#include "modules/statistics.hpp"
#include "platform/functional/frame_state.hpp"

namespace rtsim::platform::ullner_array {

class ArrayNode;

class FrameBufferReadout : public sc_core::sc_module, public modules::StatGroup {
 public:
  static constexpr const char* kName = "readout";
  static void declare_params(const modules::ParamDecls& readout);

  SC_HAS_PROCESS(FrameBufferReadout);
  /// `nodes` by topology index; it starts at `frame_done`.
  FrameBufferReadout(sc_core::sc_module_name name, const params::ParamRegistry& registry,
                     std::vector<const ArrayNode*> nodes, const modules::MeshTopology& topology,
                     functional::FrameState& frame, const sc_core::sc_event& frame_done);

  /// When the last pixel was out (empty until then).
  const std::optional<sc_core::sc_time>& done() const { return done_; }

 private:
  void run();

  std::vector<const ArrayNode*> nodes_;
  const modules::MeshTopology& topology_;
  functional::FrameState& frame_;
  const sc_core::sc_event& frame_done_;
  sc_core::sc_time pixel_time_;
  std::optional<sc_core::sc_time> done_;
  modules::Busy busy_{*this, "time shifting pixels out (its utilisation)"};
  modules::Counter pixels_{*this, "pixels", "pixels shifted out"};
};

}  // namespace rtsim::platform::ullner_array
