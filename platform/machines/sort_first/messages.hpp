#pragma once
// What travels on sort-first's interconnect (seed 004 Fig. 1, L503-L505), and its size there:
//   view       host -> renderer: the frame's viewing parameters (16 words: eye, right, up and
//              forward vectors, pixel size, screen centre, near and far)
//   records    renderer -> renderer: migrating primitives, a frame word and a count word, then
//              the records (primitive_record.hpp, 120 bytes each)
//   tally      renderer -> host: how many records it sent to each region this frame (a frame
//              word, a count, then a region and count word pair a destination)
//   expected   host -> renderer: how many records it will receive this frame (2 words)
//   pixels     renderer -> frame buffer: its region's finished pixels, 3 bytes each (L505:
//              "finished pixels are sent to one or more frame buffers"), after a frame and
//              region word
//   partial    sort-last renderer -> frame buffer: one tile of its full-screen partial image,
//              Fig. 8's 34-byte appearance record a sample (L515: pixel information, at least
//              colour and depth, sent to be depth-composited), after a frame and tile word
// The sizes are this model's (the seed gives none): the words a 32-bit machine would send.
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "firmware/raster/region_samples.hpp"
#include "firmware/raster/view_transform.hpp"
#include "firmware/sortfirst/primitive_record.hpp"
#include "firmware/sortfirst/region_render.hpp"
#include "modules/latency_probe.hpp"

namespace rtsim::platform::sort_first {

enum class MessageKind : std::uint8_t { kView = 0, kRecords, kTally, kExpected, kPixels, kPartial };
inline constexpr std::size_t kMessageKinds = 6;
/// The traffic classes, in MessageKind order (the ring's bytes.* statistics, stats.json's
/// per-frame bytes).
inline const std::vector<std::string> kTrafficClasses = {"view",     "redistribution", "tally",
                                                         "expected", "pixels",         "partial"};

inline constexpr std::uint64_t kWordBytes = 4;
inline constexpr std::uint64_t kViewBytes = 16 * kWordBytes;
inline constexpr std::uint64_t kPixelBytes = 3;

/// --latency-probe's stages, in the order a region's frame meets them: the view on the
/// interconnect, in the renderer's inbox, the renderer (service: its computing; queueing: waiting
/// for its records), the pixels on the interconnect, in the host's inbox.
struct ProbeStages {
  int net = 0;
  int renderer_in = 0;
  int renderer = 0;
  int host_in = 0;
};

struct Message {
  MessageKind kind = MessageKind::kView;
  int frame = 0;
  int from = 0;                                           ///< the sender's ring node
  raster::ViewTransform view;                             ///< kView
  std::vector<sortfirst::PrimitiveRecord> records;        ///< kRecords
  std::vector<std::pair<int, std::uint32_t>> tally;       ///< kTally: (region, records sent there)
  std::uint32_t count = 0;                                ///< kExpected
  std::shared_ptr<const sortfirst::RegionPixels> pixels;  ///< kPixels
  std::shared_ptr<const raster::RegionSamples> partial;   ///< kPartial (its `at`: the tile)
  /// --latency-probe: the region's frame a view or pixels message belongs to, and when its
  /// sender handed it to the interconnect.
  modules::LatencyProbe::Journey journey = modules::LatencyProbe::kNoJourney;
  sc_core::sc_time sent = sc_core::SC_ZERO_TIME;

  /// Its size on the interconnect.
  std::uint64_t bytes() const {
    switch (kind) {
      case MessageKind::kView:
        return kViewBytes;
      case MessageKind::kRecords:
        return 2 * kWordBytes + records.size() * sortfirst::kRecordBytes;
      case MessageKind::kTally:
        return 2 * kWordBytes + tally.size() * 2 * kWordBytes;
      case MessageKind::kExpected:
        return 2 * kWordBytes;
      case MessageKind::kPixels:
        return 2 * kWordBytes + (pixels ? pixels->pixels.size() * kPixelBytes : 0);
      case MessageKind::kPartial:
        return 2 * kWordBytes + (partial ? static_cast<std::uint64_t>(partial->at.width) *
                                               static_cast<std::uint64_t>(partial->at.height) *
                                               raster::kAppearanceBytes
                                         : 0);
    }
    return 0;
  }
};

}  // namespace rtsim::platform::sort_first
