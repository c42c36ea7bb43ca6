#pragma once
// A PixelFlow node assigned as a rasterizer (seed 004 L25-L29, L132, L160): it holds its share of
// the primitives and, region-sample by region-sample in every pass, scan-converts those whose
// box meets the region into its own buffer — the appearance records of Fig. 8, or depth only in
// a shadow pass (L118) — and hands the buffer to the composition network. Each triangle it sets
// up for a region costs `triangle_time` (0.85 us with all appearance parameters, L132), or
// `depth_triangle_time` for depth only; it holds `buffered_regions` finished regions the network
// has not taken (L128: a pass's rasterization starts when buffer space is free).
#include <tlm_utils/simple_initiator_socket.h>

#include <systemc>
#include <vector>

#include "modules/message_channel.hpp"
#include "modules/module_params.hpp"
#include "modules/processor.hpp"
#include "platform/machines/pixelflow/pass_plan.hpp"
#include "platform/machines/pixelflow/region_messages.hpp"

namespace rtsim::platform {
class MachineRun;
}

namespace rtsim::platform::pixelflow {

class RasterizerNode : public modules::Processor {
 public:
  static void declare_params(const modules::ParamDecls& rasterizer);
  /// Its output buffer's depth (the network's queue from it is that deep).
  static std::size_t buffered_regions(const modules::ModuleParams& rasterizer);

  SC_HAS_PROCESS(RasterizerNode);
  /// Rasterizer `index` of the plan's; `out_queue` the network's queue its `out` feeds.
  RasterizerNode(sc_core::sc_module_name name, MachineRun& run, const PassPlan& plan, int index,
                 const modules::TimedFifo<RasterRegion>& out_queue);

  tlm_utils::simple_initiator_socket<RasterizerNode> out;

  /// Its busy time and triangles set up in each pass (by plan index).
  const std::vector<sc_core::sc_time>& busy_by_pass() const { return busy_by_pass_; }
  const std::vector<std::uint64_t>& triangles_by_pass() const { return triangles_by_pass_; }
  /// When it began each pass's first region-sample.
  const std::vector<sc_core::sc_time>& began_pass() const { return began_pass_; }

 private:
  void run();

  modules::ModuleParams params_;
  const PassPlan& plan_;
  int index_;
  const modules::TimedFifo<RasterRegion>& out_queue_;
  sc_core::sc_time triangle_time_, depth_triangle_time_;
  std::vector<sc_core::sc_time> busy_by_pass_;
  std::vector<std::uint64_t> triangles_by_pass_;
  std::vector<sc_core::sc_time> began_pass_;
  modules::Counter triangles_{*this, "triangles",
                              "triangles set up, once for each region-sample they meet"};
  modules::Counter samples_written_{*this, "samples_written",
                                    "samples a triangle won in its own buffer"};
  modules::Counter regions_{*this, "regions", "region-samples rasterized"};
};

}  // namespace rtsim::platform::pixelflow
