#include "platform/machines/pixelflow/frame_buffer_node.hpp"

#include "platform/machines/machine_run.hpp"

namespace rtsim::platform::pixelflow {

void add_into(functional::FrameState& frame, const ShadedRegion& r) {
  const auto& g = r.at;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const ColourBytes& c = (*r.colours)[static_cast<std::size_t>(y * raster::kRegionWidth + x)];
      frame.fb().add(static_cast<std::uint32_t>((g.y0 + y) * frame.width() + g.x0 + x),
                     Color(c[0], c[1], c[2]) / 255.0);
    }
}

FrameBufferNode::FrameBufferNode(sc_core::sc_module_name name, MachineRun& run, int region_samples,
                                 int probe_stage)
    : modules::Processor(name, run.trace()),
      // One region-sample at a time (assumption: the node adds it as it arrives).
      in("in", 1),
      frame_(run.frame()),
      expected_(region_samples),
      probe_(run.probe()),
      stage_(probe_stage) {
  SC_THREAD(run);
}

void FrameBufferNode::run() {
  for (int n = 0; n < expected_; ++n) {
    const sc_core::sc_time since = clock_.now();
    modules::wait_for_item(in.fifo, clock_);
    sc_core::sc_time taken;
    const ShadedRegion r = in.fifo.get(clock_.now(), taken);
    clock_.catch_up(taken);
    waited_since(since, Wait::kWork);
    probe_.add(r.journey, stage_, modules::LatencyPart::kQueueing, clock_.now() - r.arrived);
    probe_.end(r.journey, clock_.now());
    add_into(frame_, r);
    ++regions_;
    frame_end_ = clock_.now();
  }
  clock_.sync();
}

}  // namespace rtsim::platform::pixelflow
