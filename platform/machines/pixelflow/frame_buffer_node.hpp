#pragma once
// PixelFlow's frame-buffer node (seed 004 L93): it takes the shaded region-samples of the camera
// pass off the composition network and adds each sample's 8-bit colour into its pixel, the
// frame's samples averaged (5 a pixel in the bowling configuration, L93). The image is what
// those colours say. The frame ends when the last region-sample is in.
#include <systemc>

#include "modules/message_channel.hpp"
#include "modules/processor.hpp"
#include "platform/functional/frame_state.hpp"
#include "platform/machines/pixelflow/region_messages.hpp"

namespace rtsim::platform {
class MachineRun;
}

namespace rtsim::platform::pixelflow {

class FrameBufferNode : public modules::Processor {
 public:
  SC_HAS_PROCESS(FrameBufferNode);
  /// Expects `region_samples` shaded region-samples; `probe_stage`: its input queue's stage of
  /// a journey (--latency-probe), where a journey ends.
  FrameBufferNode(sc_core::sc_module_name name, MachineRun& run, int region_samples,
                  int probe_stage);

  modules::MessageQueue<ShadedRegion> in;
  /// When the last region-sample arrived.
  sc_core::sc_time frame_end() const { return frame_end_; }

 private:
  void run();

  functional::FrameState& frame_;
  int expected_;
  modules::LatencyProbe& probe_;
  int stage_;
  sc_core::sc_time frame_end_ = sc_core::SC_ZERO_TIME;
  modules::Counter regions_{*this, "regions", "shaded region-samples added into the image"};
};

/// Adds a shaded region-sample's colours into `frame` (the frame buffer node's and the
/// functional twin's one way of doing it).
void add_into(functional::FrameState& frame, const ShadedRegion& r);

}  // namespace rtsim::platform::pixelflow
