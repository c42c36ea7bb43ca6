#pragma once
// What a PixelFlow shading node holds in its table-lookup memory (seed 004 L15: 16 MB a node,
// readable by every pixel processor) and the lookups its shaders make there (L148: one lookup
// for all 8K pixels takes 190 us):
// - MipMap: an 8-bit RGB texture with its mip-map levels (the pins' label and dirt, the alley's
//   wood: "mip-mapped", L97), looked up bilinearly at the level the footprint asks for;
// - DepthMap: a shadow map, the depth words of a view from a light (L116-L120);
// - ColourMap: a reflection map, 8-bit RGB texels of a mirrored view (L128).
// The maps are square images of regions (a 512 x 512 map is 32 regions of 128 x 64, written to
// table memory 4 regions at a time, L122-L126): store() takes one region.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "firmware/math.hpp"
#include "firmware/raster/region_samples.hpp"
#include "firmware/raster/view_transform.hpp"

namespace rtsim::raster {

class MipMap {
 public:
  MipMap() = default;
  /// A `size` x `size` texture (size a power of two), RGB bytes row by row; builds the levels
  /// by 2 x 2 box filtering down to 1 x 1.
  MipMap(int size, std::vector<std::uint8_t> rgb);
  bool empty() const { return levels_.empty(); }
  int size() const { return size_; }
  /// The texture at (u, v) (repeating) for a footprint of (fu, fv) texture units a pixel.
  Color lookup(double u, double v, double fu, double fv) const;
  /// The bytes it takes in table memory (every level).
  std::size_t bytes() const;

 private:
  int size_ = 0;
  std::vector<std::vector<std::uint8_t>> levels_;
  Color texel(int level, int x, int y) const;
};

class DepthMap {
 public:
  explicit DepthMap(const ViewTransform& view)
      : view_(view),
        depth_(static_cast<std::size_t>(view.width) * static_cast<std::size_t>(view.height),
               kBackgroundDepth) {}
  const ViewTransform& view() const { return view_; }
  /// Writes a composited region into the map.
  void store(const RegionDepths& region);
  /// Whether world point `p` with unit normal `n` sees the map's viewpoint: no nearer surface in
  /// its texel, beyond a bias of `bias_texels` texels' size (more where the surface is steep to
  /// the light). Points outside the map are lit.
  bool lit(const Vec3& p, const Vec3& n, double bias_texels) const;
  std::uint32_t at(int x, int y) const {
    return depth_[static_cast<std::size_t>(y) * static_cast<std::size_t>(view_.width) +
                  static_cast<std::size_t>(x)];
  }

 private:
  ViewTransform view_;
  std::vector<std::uint32_t> depth_;
};

class ColourMap {
 public:
  ColourMap(const ViewTransform& view, const Color& background)
      : view_(view),
        rgb_(3 * static_cast<std::size_t>(view.width) * static_cast<std::size_t>(view.height)) {
    for (std::size_t i = 0; i < rgb_.size(); i += 3) {
      rgb_[i] = colour_byte(background.r);
      rgb_[i + 1] = colour_byte(background.g);
      rgb_[i + 2] = colour_byte(background.b);
    }
  }
  const ViewTransform& view() const { return view_; }
  /// Writes texel (x, y) (a shaded region's pixel).
  void set(int x, int y, const Color& c);
  /// The mirrored view's colour where world point `p` is seen (nearest texel); outside the map,
  /// its nearest edge texel.
  Color lookup(const Vec3& p) const;

 private:
  ViewTransform view_;
  std::vector<std::uint8_t> rgb_;
};

}  // namespace rtsim::raster
