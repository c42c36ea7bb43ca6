#pragma once
// --latency-probe on pxpl5-raytrace: each sample's journey from its caster beginning its region
// to the frame buffer displaying its frame, by stage (seed 004 Fig. 1): the caster, the ring, the
// compositor's inbox, the compositor (compositing it, then holding it until its bands have the
// frame), the ring to the renderer of the sample's own display pixel, that renderer (waiting for
// the frame's other bands, then resampling the tile), the ring to the frame buffer and the frame
// buffer (writing the tile's pixels, then waiting for the frame's other tiles). The renderers and
// the frame buffer work on whole tiles and frames: a sample takes its tile's times there.
//
// The compositors hand their samples' journeys on when they send the frame's bands; a renderer
// hands them on when it sends its pixels; the frame buffer ends them when it displays the frame.
#include <map>
#include <systemc>
#include <utility>
#include <vector>

#include "modules/latency_probe.hpp"

namespace rtsim::platform::pxpl5 {

struct SampleJourneys {
  using Journey = modules::LatencyProbe::Journey;

  /// Sent on in a band of frame f by compositor c at `sent`, for renderer r.
  struct InBand {
    Journey journey;
    int compositor;
    sc_core::sc_time sent;
  };
  /// By (frame, renderer): the journeys its band messages carry.
  std::map<std::pair<int, int>, std::vector<InBand>> to_renderer;
  /// By (frame, renderer): the journeys of the tile's pixels, sent to the frame buffer at `sent`.
  struct InPixels {
    std::vector<Journey> journeys;
    sc_core::sc_time sent;
  };
  std::map<std::pair<int, int>, InPixels> to_frame_buffer;
  /// By frame: the journeys the frame buffer has written, with when, waiting for the display.
  std::map<int, std::vector<std::pair<Journey, sc_core::sc_time>>> written;
};

}  // namespace rtsim::platform::pxpl5
