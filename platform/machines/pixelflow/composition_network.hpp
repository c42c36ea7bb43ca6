#pragma once
// PixelFlow's image-composition network (seed 004 L21, L27-L29, L65, L120): it collects each
// region-sample's buffers from every rasterizer, z-composites them sample by sample (the nearer
// record wins, appearance.hpp) and delivers the result to the shader the region is assigned to
// (one of every s, L23), or, a shadow map's depths, to every shader's table memory (L120). The
// shaders' colours travel on it too: to the frame buffer, or a reflection map's to every table
// memory. Both directions share one link (`composition.link`), whose bandwidth the seed does not
// give: its default is the rate of L120's depth-only composition, 8K 4-byte depths in 5 us.
//
// It is two processors on that link — the compositor (rasterizers to shaders and tables) and
// the collector (shaders to the frame buffer and tables) — so that a shader waiting for its maps
// never holds up the colours that make them.
#include <tlm_utils/simple_initiator_socket.h>

#include <memory>
#include <systemc>
#include <vector>

#include "modules/link.hpp"
#include "modules/message_channel.hpp"
#include "modules/module_params.hpp"
#include "modules/processor.hpp"
#include "platform/machine.hpp"
#include "platform/machines/pixelflow/pass_plan.hpp"
#include "platform/machines/pixelflow/region_messages.hpp"

namespace rtsim::platform {
class MachineRun;
}

namespace rtsim::platform::pixelflow {

/// `--fault composition:WORD:XOR`: word WORD (32 bits) of the camera pass's composited records,
/// counted over its region-samples in order, 69,632 words each (8K records of 34 bytes), is
/// XORed on its way to its shader.
struct CompositionFault {
  std::uint64_t word = 0;
  std::uint32_t xor_mask = 0;
  bool applied = false;
};

/// Where the network delivers: every shader's input queue and table memory, the frame buffer.
struct NetworkEnds {
  std::vector<const modules::TimedFifo<RasterRegion>*> shaders;
  std::vector<const modules::TimedFifo<TableRegion>*> tables;
  const modules::TimedFifo<ShadedRegion>* frame_buffer = nullptr;
};

class CompositionNetwork : public sc_core::sc_module {
 public:
  static void declare_params(const modules::ParamDecls& network);
  /// The name of its fault point.
  static constexpr const char* kFaultPoint = "composition";
  /// 32-bit words of one region-sample's records (8K records of 34 bytes).
  static constexpr std::uint64_t kWordsPerRegion =
      static_cast<std::uint64_t>(raster::kRegionPixels) * raster::kAppearanceBytes / 4;

  CompositionNetwork(sc_core::sc_module_name name, MachineRun& run, const PassPlan& plan,
                     int shaders, std::size_t rasterizer_buffers, NetworkEnds ends,
                     std::vector<CompositionFault> faults, const ProbeStages& stages);
  ~CompositionNetwork() override;

  /// Its queues from the rasterizers and from the shaders.
  std::vector<std::unique_ptr<modules::MessageQueue<RasterRegion>>> from_rasterizer;
  std::vector<std::unique_ptr<modules::MessageQueue<ShadedRegion>>> from_shader;
  /// Its sockets to the shaders' inputs, to their table memories, to the frame buffer.
  std::vector<std::unique_ptr<tlm_utils::simple_initiator_socket<CompositionNetwork>>> to_shader;
  std::vector<std::unique_ptr<tlm_utils::simple_initiator_socket<CompositionNetwork>>> to_table;
  tlm_utils::simple_initiator_socket<CompositionNetwork> to_frame_buffer;

  modules::ModuleParams params_;
  modules::Link link;

  /// Bytes it carried in each pass (by plan index), both directions.
  const std::vector<std::uint64_t>& bytes_by_pass() const { return bytes_by_pass_; }
  const std::vector<CompositionFault>& faults() const { return faults_; }

 private:
  class Port;
  class Compositor;
  class Collector;

  const PassPlan& plan_;
  int shaders_;
  NetworkEnds ends_;
  std::vector<CompositionFault> faults_;
  std::vector<std::uint64_t> bytes_by_pass_;
  modules::LatencyProbe& probe_;
  ProbeStages stages_;
  std::unique_ptr<Compositor> compositor_;
  std::unique_ptr<Collector> collector_;
};

}  // namespace rtsim::platform::pixelflow
