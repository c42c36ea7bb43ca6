#pragma once
// The passes of a PixelFlow frame in the order the machine runs them (seed 004 L114-L128): a
// shadow map from each light (depth only), the reflection map (where a surface has the alley's
// shader), then the camera's image at the frame's samples a pixel. Each pass is a sequence of
// region-samples (L21, L154: region by region, each region once a sample); for each, what every
// rasterizer holds of it: its share of the primitives (L132: divided across the rasterizers,
// here mesh triangle i to rasterizer i mod R) whose bounding box meets the region.
#include <cstdint>
#include <string>
#include <vector>

#include "firmware/raster/region_grid.hpp"
#include "firmware/raster/screen_triangle.hpp"
#include "platform/machines/pixelflow/frame_setup.hpp"

namespace rtsim::platform::pixelflow {

enum class PassKind { Shadow, Reflection, Camera };

struct Pass {
  PassKind kind = PassKind::Camera;
  int light = -1;  ///< a shadow pass's light
  raster::ViewTransform view;
  raster::ViewSetup setup;
  raster::RegionGrid grid;
  int samples = 1;
  /// shares[region][rasterizer]: indices into setup.triangles.
  std::vector<std::vector<std::vector<std::uint32_t>>> shares;

  int region_samples() const { return grid.count() * samples; }
  int region_of(int k) const { return k / samples; }
  int sample_of(int k) const { return k % samples; }
  /// "shadow0", "reflection", "camera": its name in stats.json and the traces.
  std::string name() const;
  bool depth_only() const { return kind == PassKind::Shadow; }
  /// Bytes a pixel processor sends over the composition network: a depth word (L118-L120) or
  /// the appearance record (Fig. 8, L110).
  int bytes_per_pixel() const;
};

struct PassPlan {
  std::vector<Pass> passes;
  int rasterizers = 1;
  /// The passes whose result goes to every shader's table memory (the maps), in order.
  std::vector<int> map_passes() const;
  const Pass* camera() const;
};

PassPlan plan_passes(const FrameSetup& f, int rasterizers);

}  // namespace rtsim::platform::pixelflow
