#pragma once
// A shading node's table-lookup memory (seed 004 L15, L57-L59, L122-L126): every shader holds
// every map, so each new shadow or reflection map is written into all of them. Its writes are a
// serial resource: the hardware stores 4 values at once, so the node accepts 4 regions of a map
// and then stores them, one table write of `write_time` (8 writes of a 512 x 512 map take 6.08
// ms, L126). The maps it holds are made from the regions it received, nothing else: a region
// corrupted on the composition network is what its shader looks up.
//
// It tells its shader when the maps are there: the shadow maps once the last of their writes
// has begun (L128: the reflection pass's shading starts then), every map once the last write has
// ended (L116: the final image begins when the maps are stored).
#include <optional>
#include <systemc>
#include <vector>

#include "firmware/raster/table_maps.hpp"
#include "modules/message_channel.hpp"
#include "modules/module_params.hpp"
#include "modules/processor.hpp"
#include "platform/machines/pixelflow/functional_passes.hpp"
#include "platform/machines/pixelflow/pass_plan.hpp"
#include "platform/machines/pixelflow/region_messages.hpp"

namespace rtsim::platform {
class MachineRun;
}

namespace rtsim::platform::pixelflow {

class TableMemory : public modules::Processor {
 public:
  static void declare_params(const modules::ParamDecls& table);

  SC_HAS_PROCESS(TableMemory);
  /// Refuses (InputError) a frame whose maps and `textures_bytes` of textures overflow it.
  TableMemory(sc_core::sc_module_name name, MachineRun& run, const PassPlan& plan,
              std::size_t textures_bytes);

  /// The shadow maps (one per light) and the reflection map, as written so far.
  const FrameMaps& maps() const { return maps_; }
  /// Whether the last shadow-map write has begun; whether every map is stored.
  bool shadows_begun() const { return shadows_begun_; }
  bool maps_stored() const { return maps_stored_; }
  /// Notified when either changes.
  const sc_core::sc_event& ready_event() const { return ready_; }
  /// When the last write of each map pass ended (its pass index in the plan).
  const std::vector<std::pair<int, sc_core::sc_time>>& stored_at() const { return stored_at_; }

 private:
  modules::ModuleParams params_;

 public:
  modules::MessageQueue<TableRegion> in;  ///< the map regions, from the composition network

 private:
  void run();

  const PassPlan& plan_;
  sc_core::sc_time write_time_;
  FrameMaps maps_;
  bool shadows_begun_ = false;
  bool maps_stored_ = false;
  sc_core::sc_event ready_;
  std::vector<std::pair<int, sc_core::sc_time>> stored_at_;
  modules::Counter writes_{*this, "writes", "table writes (each up to regions_per_write regions)"};
  modules::Counter regions_{*this, "regions", "map regions stored"};
};

}  // namespace rtsim::platform::pixelflow
