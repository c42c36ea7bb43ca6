#include "platform/machines/ullner_array/frame_buffer_readout.hpp"

#include "modules/activations.hpp"
#include "modules/sim_time.hpp"
#include "platform/machines/ullner_array/array_node.hpp"

namespace rtsim::platform::ullner_array {

namespace {
const modules::TimeParam kPixelTime(
    {.name = "pixel_time",
     .default_value = "666.667 ns",
     .description = "Time to shift one pixel out of the distributed frame buffer in scan-line "
                    "order (L781)",
     .source = "assumption: 24 bits of colour, two 16-bit transfers at the memory cycle"});
}  // namespace

void FrameBufferReadout::declare_params(const modules::ParamDecls& readout) {
  readout.add(kPixelTime);
}

FrameBufferReadout::FrameBufferReadout(sc_core::sc_module_name name,
                                       const params::ParamRegistry& registry,
                                       std::vector<const ArrayNode*> nodes,
                                       const modules::MeshTopology& topology,
                                       functional::FrameState& frame,
                                       const sc_core::sc_event& frame_done)
    : sc_core::sc_module(name),
      modules::StatGroup(sc_core::sc_module::name()),
      nodes_(std::move(nodes)),
      topology_(topology),
      frame_(frame),
      frame_done_(frame_done),
      pixel_time_(modules::ModuleParams(registry, kName).get(kPixelTime)) {
  SC_THREAD(run);
}

void FrameBufferReadout::run() {
  modules::sim_wait(frame_done_);
  const int w = frame_.width(), h = frame_.height();
  const sc_core::sc_time start = modules::sim_now();
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      // The pixel's processor (the block its position in the array holds, L781).
      const ArrayNode& node = *nodes_[static_cast<std::size_t>(
          topology_.index(pixel_processor(x, y, w, h, topology_)))];
      const auto& words = node.frame_buffer.contents();
      const std::size_t o = node.block().offset(x, y);
      std::array<std::int64_t, 3> sums{};
      for (std::size_t k = 0; k < 3; ++k)
        sums[k] = static_cast<std::int64_t>(
            words[o + 2 * k] | (static_cast<std::uint64_t>(words[o + 2 * k + 1]) << 32));
      frame_.fb().read_out(static_cast<std::uint32_t>(y * w + x), sums);
    }
    // A row's pixels shifted out one after the other.
    modules::sim_wait(modules::times(pixel_time_, static_cast<std::uint64_t>(w)));
  }
  pixels_ += static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h);
  busy_.record(start, modules::sim_now() - start);
  done_ = modules::sim_now();
}

}  // namespace rtsim::platform::ullner_array
