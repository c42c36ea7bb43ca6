#pragma once
// A sort-first region renderer (seed 004 Fig. 1, L503-L505): one a square screen region, a kit
// Processor holding its primitives in a RegionStore from frame to frame. Each frame, on the
// host's view message, it classifies what it holds by screen bounding box (`classify_time` a
// primitive), sends the primitives whose covered regions changed to their new holders as record
// messages (one message a destination), tells the host how many it sent where, and, once the
// host says how many will come and they have, classifies those too, renders its region from
// what it holds (`triangle_time` a triangle set up, `sample_time` a covered sample,
// `shade_time` a shaded pixel) and sends its finished pixels to the frame buffer.
//
// With `sort = middle` it keeps its initial share and sends every primitive to every other
// region it covers, each frame; with `sort = last` it sends nothing, renders its share over the
// whole screen and sends its partial image, tile by tile, to be composited
// (firmware/sortfirst/region_store.hpp's Sort).
#include <cstdint>
#include <map>
#include <vector>

#include "firmware/sortfirst/region_store.hpp"
#include "modules/module_params.hpp"
#include "platform/machines/sort_first/frame_data.hpp"
#include "platform/machines/sort_first/interconnect.hpp"

namespace rtsim::platform {
class MachineRun;
}

namespace rtsim::platform::sort_first {

/// `--fault migration:W:MASK`: word W of the run's migrating records (in the order they are
/// handed to the interconnect, 30 words a record) is XORed with MASK in flight.
struct MigrationFaults {
  static constexpr const char* kFaultPoint = "migration";
  struct Fault {
    std::uint64_t word = 0;
    std::uint32_t xor_mask = 0;
    bool applied = false;
  };
  std::vector<Fault> faults;
  std::uint64_t words_sent = 0;
  /// Applies what falls in `r`, the next record sent.
  void pass(sortfirst::PrimitiveRecord& r);
};

class RegionRenderer : public InterconnectNode {
 public:
  static constexpr const char* kClass = "renderer";
  static void declare_params(const modules::ParamDecls& renderer);

  SC_HAS_PROCESS(RegionRenderer);
  /// Region `region` (its interconnect node too); `host` the host's node; `sort` the layout; its
  /// share of the initial distribution (database indices) loaded from `share`.
  RegionRenderer(sc_core::sc_module_name name, MachineRun& run, Interconnect& net,
                 const FrameData& data, sortfirst::Sort sort, int region, int host, int frames,
                 const std::vector<std::uint32_t>& share, MigrationFaults& faults,
                 const ProbeStages& stages);

  /// Per frame: records it sent, its busy time.
  const std::vector<std::uint64_t>& sent_by_frame() const { return sent_by_frame_; }
  const std::vector<sc_core::sc_time>& busy_by_frame() const { return busy_by_frame_; }

 private:
  void run();
  /// Takes messages until `done()` holds, filing each by kind and frame.
  template <class Done>
  void receive_until(Done done);
  void busy(const sc_core::sc_time& t, std::string_view what, int frame);
  /// Sends this frame's records to their regions, tells the host, and takes what comes.
  void redistribute(int f, const raster::ViewTransform& view,
                    std::vector<sortfirst::Migration>& sends);
  void count_work(const sortfirst::RegionWork& w, std::uint64_t pixels);
  sc_core::sc_time render_time(const sortfirst::RegionWork& w) const;

  modules::ModuleParams params_;
  const FrameData& data_;
  int region_;
  int host_;
  int frames_;
  std::uint32_t primitives_;
  MigrationFaults& faults_;
  modules::LatencyProbe& probe_;
  functional::FrameState& frame_;
  ProbeStages stages_;
  sortfirst::Sort sort_;
  sortfirst::RegionStore store_;
  sc_core::sc_time classify_time_, triangle_time_, sample_time_, shade_time_;
  std::map<int, raster::ViewTransform> views_;
  /// Each frame's journey (its view's) and when the view was taken.
  std::map<int, std::pair<modules::LatencyProbe::Journey, sc_core::sc_time>> journeys_;
  std::map<int, std::uint32_t> expected_;
  std::map<int, std::vector<sortfirst::PrimitiveRecord>> arrived_;
  std::vector<std::uint64_t> sent_by_frame_;
  std::vector<sc_core::sc_time> busy_by_frame_;
  modules::Counter classified_{*this, "classified", "primitives classified by screen box"};
  modules::Counter sent_{*this, "records_sent", "primitive records sent to other regions"};
  modules::Counter received_{*this, "records_received", "primitive records that arrived"};
  modules::Counter refused_{*this, "records_refused",
                            "arrived records not kept: not covering the region, or corrupted"};
  modules::Counter dropped_{*this, "copies_dropped", "copies no longer covering the region"};
  modules::Counter triangles_{*this, "triangles", "triangles set up for the region"};
  modules::Counter samples_{*this, "samples", "samples a triangle covered"};
  modules::Counter shaded_{*this, "pixels_shaded", "covered pixels shaded"};
};

}  // namespace rtsim::platform::sort_first
