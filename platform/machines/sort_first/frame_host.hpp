#pragma once
// Sort-first's host and frame buffer (seed 004 L497-L499: "an application host computer working
// with a graphics computer subsystem"; L505: finished pixels go to the frame buffer), one node on
// the interconnect. Each frame it sends every region renderer the frame's view, gathers their
// tallies of the records they sent and tells each renderer how many to expect (the frame's
// redistribution is then known to be complete without a message between every pair), and takes
// the renderers' finished pixels into the frame buffer. The next frame starts when the last
// region of this one is in (frames are not overlapped: an assumption, so that a frame's time is
// its own). The image is the last frame's pixels as they arrived.
//
// Sort-last (L515): no tallies; it depth-composites every renderer's partial image tile by tile
// (`composite_time` a sample) and, on the last frame, shades the composited records into the
// image (the time of shading is the renderers', charged where a sort-last machine shades).
#include <optional>
#include <vector>

#include "firmware/sortfirst/region_store.hpp"
#include "modules/module_params.hpp"
#include "platform/machines/sort_first/frame_data.hpp"
#include "platform/machines/sort_first/interconnect.hpp"

namespace rtsim::platform {
class MachineRun;
}

namespace rtsim::platform::sort_first {

class FrameHost : public InterconnectNode {
 public:
  static constexpr const char* kName = "host";
  static void declare_params(const modules::ParamDecls& host);

  SC_HAS_PROCESS(FrameHost);
  /// Node `node` (after the renderers 0 .. regions - 1); the views of the frames.
  FrameHost(sc_core::sc_module_name name, MachineRun& run, Interconnect& net, const FrameData& data,
            sortfirst::Sort sort, int node, int regions, std::vector<raster::ViewTransform> views,
            const ProbeStages& stages);

  /// When each frame began (its views sent) and ended (its last region in).
  const std::vector<sc_core::sc_time>& began() const { return began_; }
  const std::vector<sc_core::sc_time>& ended() const { return ended_; }

 private:
  void run();
  /// Sends every renderer its expected count once all tallies of frame `f` are in.
  void take_tally(const Message& m, int f);
  /// A region's pixels or a partial tile of frame `f`; true when that completes a region or
  /// (sort-last) a renderer's partial image.
  bool take_result(Message m, int f, bool last_frame);

  functional::FrameState& frame_;
  const FrameData& data_;
  sortfirst::Sort sort_;
  modules::LatencyProbe& probe_;
  ProbeStages stages_;
  int regions_;
  std::vector<raster::ViewTransform> views_;
  sc_core::sc_time composite_time_;
  std::vector<sc_core::sc_time> began_, ended_;
  // This frame's state.
  std::vector<std::uint32_t> expected_;
  int tallies_ = 0;
  std::vector<std::optional<raster::RegionSamples>> composite_;  ///< sort-last, by tile
  std::vector<int> tiles_in_;                                    ///< partial tiles in, by tile
  std::vector<int> renderer_tiles_;                              ///< partial tiles in, by renderer
  modules::Counter pixels_{*this, "pixels", "finished pixels taken into the frame buffer"};
  modules::Counter composited_{*this, "samples_composited",
                               "sort-last: partial images' samples depth-composited"};
};

}  // namespace rtsim::platform::sort_first
