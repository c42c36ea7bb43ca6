#pragma once
// What travels between PixelFlow's nodes (seed 004 L21-L29, L120, L122): a rasterizer's
// region-sample to the composition network (appearance records, or depth words in a shadow
// pass), the composited region to its shader (or, a map's, to every shader's table memory), and
// a shaded region (8-bit colour, L110) to the frame buffer or, a reflection map's, to every
// table memory. The data is held by pointer: a message is a whole region of the SIMD array
// (278,528 bytes of records), and a broadcast hands every receiver the same bytes.
#include <array>
#include <cstdint>
#include <memory>
#include <systemc>
#include <vector>

#include "firmware/raster/region_samples.hpp"
#include "modules/latency_probe.hpp"

namespace rtsim::platform::pixelflow {

/// One 8-bit RGB colour a pixel (L110: 8 bits a channel in the bowling simulation).
using ColourBytes = std::array<std::uint8_t, 3>;
inline constexpr int kColourBytes = 3;

/// The stages of a camera region-sample's journey (--latency-probe), named in the order it
/// meets them: from the first rasterizer beginning it to the frame buffer taking its colours.
struct ProbeStages {
  int rasterizer = 0, from_rasterizer = 0, network = 0, link = 0, shader_in = 0, shader = 0,
      from_shader = 0, frame_buffer_in = 0;
};

/// A region-sample of records or depths (pass `pass`, its `index`-th region-sample).
struct RasterRegion {
  int pass = 0;
  int index = 0;
  std::shared_ptr<raster::RegionSamples> samples;  ///< appearance records (not a shadow pass)
  std::shared_ptr<raster::RegionDepths> depths;    ///< depth words (a shadow pass)
  /// When its rasterizer began and finished it (one rasterizer's part); once composited, the
  /// region-sample's journey and when it reached its shader.
  sc_core::sc_time begun = sc_core::SC_ZERO_TIME, finished = sc_core::SC_ZERO_TIME;
  modules::LatencyProbe::Journey journey = modules::LatencyProbe::kNoJourney;
  sc_core::sc_time arrived = sc_core::SC_ZERO_TIME;
};

/// A shaded region-sample: a colour for each pixel processor, kRegionWidth a row.
struct ShadedRegion {
  int pass = 0;
  int index = 0;
  raster::RegionSampleGrid at{};
  std::shared_ptr<const std::vector<ColourBytes>> colours;
  /// Its journey (a camera region-sample's), when its shader sent it and when it reached the
  /// frame buffer.
  modules::LatencyProbe::Journey journey = modules::LatencyProbe::kNoJourney;
  sc_core::sc_time sent = sc_core::SC_ZERO_TIME, arrived = sc_core::SC_ZERO_TIME;
};

/// A region of a map on its way into every shader's table memory.
struct TableRegion {
  int pass = 0;
  raster::RegionSampleGrid at{};
  std::shared_ptr<const raster::RegionDepths> depths;       ///< a shadow map's
  std::shared_ptr<const std::vector<ColourBytes>> colours;  ///< the reflection map's
};

/// A shader's colours as the 8-bit words it sends (rounded, clamped to [0, 1]).
inline std::shared_ptr<const std::vector<ColourBytes>> colour_bytes(const std::vector<Color>& c) {
  auto bytes = std::make_shared<std::vector<ColourBytes>>(c.size());
  for (std::size_t i = 0; i < c.size(); ++i)
    (*bytes)[i] = {raster::colour_byte(c[i].r), raster::colour_byte(c[i].g),
                   raster::colour_byte(c[i].b)};
  return bytes;
}

/// Bits a region of the SIMD array sends when each pixel processor sends `bytes`: the whole
/// array, 8K processors (L148), whatever part of it the screen covers.
inline std::uint64_t region_bits(int bytes) {
  return static_cast<std::uint64_t>(raster::kRegionPixels) * static_cast<std::uint64_t>(bytes) * 8u;
}

}  // namespace rtsim::platform::pixelflow
