#pragma once
// A PixelFlow node assigned as a shader (seed 004 L23-L35, L160): it receives one of every s
// region-samples from the composition network (the static interleave of L23), deferred-shades
// the appearance records it received with the maps its own table memory holds (Fig. 7), and
// sends the 8-bit colours (L110) back onto the network: to the frame buffer, or, in the
// reflection pass, to every node's table memory. Its time for a region comes from what the
// region holds (ShadingCosts: Fig. 9's parts or Fig. 6's instructions, and the lookups of L148).
#include <tlm_utils/simple_initiator_socket.h>

#include <memory>
#include <systemc>
#include <vector>

#include "firmware/deferred/deferred_shader.hpp"
#include "firmware/trace_counters.hpp"
#include "modules/message_channel.hpp"
#include "modules/module_params.hpp"
#include "modules/processor.hpp"
#include "platform/machines/pixelflow/frame_setup.hpp"
#include "platform/machines/pixelflow/pass_plan.hpp"
#include "platform/machines/pixelflow/region_messages.hpp"
#include "platform/machines/pixelflow/shading_costs.hpp"
#include "platform/machines/pixelflow/table_memory.hpp"

namespace rtsim::platform {
class MachineRun;
}

namespace rtsim::platform::pixelflow {

class ShadingNode : public modules::Processor {
 public:
  static void declare_params(const modules::ParamDecls& shader);

  SC_HAS_PROCESS(ShadingNode);
  /// Node `index` of `count` shaders.
  ShadingNode(sc_core::sc_module_name name, MachineRun& run, const FrameSetup& frame,
              const PassPlan& plan, int index, int count, const ProbeStages& stages);

  /// Elaboration: the network's queue its `out` socket feeds (it waits there for room).
  void feeds(const modules::TimedFifo<ShadedRegion>& queue) { out_queue_ = &queue; }

  /// The region-samples it shaded in each pass (by plan index).
  const std::vector<std::uint64_t>& regions_by_pass() const { return regions_by_pass_; }
  /// Its busy time in each pass.
  const std::vector<sc_core::sc_time>& busy_by_pass() const { return busy_by_pass_; }
  /// The work of its most expensive region-sample and that region-sample's time.
  const deferred::RegionWork& worst_work() const { return worst_work_; }
  sc_core::sc_time worst_time() const { return worst_time_; }
  /// The region-sample whose shading parts (lookups aside) took longest, and that time.
  const deferred::RegionWork& worst_shading_work() const { return worst_shading_work_; }
  sc_core::sc_time worst_shading() const { return worst_shading_; }
  const ShadingCosts& costs() const { return costs_; }

 private:
  modules::ModuleParams params_;

 public:
  modules::MessageQueue<RasterRegion> in;  ///< composited region-samples from the network
  tlm_utils::simple_initiator_socket<ShadingNode> out;
  TableMemory table;  ///< its table-lookup memory

 private:
  void run();
  /// Waits until its table memory holds what pass `p` looks up.
  void await_maps(const Pass& p);
  /// Adds a camera region-sample's samples, shadow tests and lookups to the frame's counts.
  void count_samples(const deferred::RegionWork& work, const raster::RegionSampleGrid& at);

  const FrameSetup& frame_;
  const PassPlan& plan_;
  int index_, count_;
  ShadingCosts costs_;
  const modules::TimedFifo<ShadedRegion>* out_queue_ = nullptr;
  std::vector<std::uint64_t> regions_by_pass_;
  std::vector<sc_core::sc_time> busy_by_pass_;
  deferred::RegionWork worst_work_{};
  modules::LatencyProbe& probe_;
  ProbeStages stages_;
  TraceCounters& counters_;
  sc_core::sc_time worst_time_ = sc_core::SC_ZERO_TIME;
  deferred::RegionWork worst_shading_work_{};
  sc_core::sc_time worst_shading_ = sc_core::SC_ZERO_TIME;
  modules::Counter regions_{*this, "regions", "region-samples shaded"};
  modules::Counter pixels_shaded_{*this, "pixels_shaded", "pixels a shading function ran for"};
  modules::Counter lookups_{*this, "lookup_pixels", "pixels that read a table (all lookups)"};
};

}  // namespace rtsim::platform::pixelflow
