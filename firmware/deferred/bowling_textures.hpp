#pragma once
// The textures of the bowling example's shaders (seed 004 L97: the pins' mip-mapped label, bump-
// mapped scuffs and mip-mapped dirt, the alley's mip-mapped wood), made procedurally: the paper's
// images are lost and the seed gives no texture, so each stands in for its namesake (an
// assumption; docs/machines.md says what each looks like). Deterministic: the same bytes on
// every run. A shading node holds them all in its table-lookup memory (L57).
#include <cstddef>

#include "firmware/raster/table_maps.hpp"

namespace rtsim::deferred {

/// Texels a side of each texture.
inline constexpr int kBowlingTextureSize = 256;

struct BowlingTextures {
  /// The pin's label: a red band with a white emblem round the pin's neck, white elsewhere (a
  /// multiplier of the pin's colour); u round the pin, v up it.
  raster::MipMap label;
  /// Dirt: greyish smudges thickest near the pin's base (a multiplier).
  raster::MipMap dirt;
  /// Scuffs: a height field of short scratches; its red channel is the height.
  raster::MipMap scuffs;
  /// Wood: maple boards along the alley (u across, v along it).
  raster::MipMap wood;

  std::size_t bytes() const { return label.bytes() + dirt.bytes() + scuffs.bytes() + wood.bytes(); }
};

/// Makes them (a few milliseconds).
BowlingTextures make_bowling_textures();

}  // namespace rtsim::deferred
