#pragma once
// PixelFlow's appearance parameters (seed 004 Fig. 8, L99-L110): what a rasterizer node sends a
// shading node for each sample over the image-composition network, 34 bytes:
//
//   depth 4 | shader id 1 | intrinsic colour 1 x 3 | normal 2 x 3 | u, v 2 x 2 |
//   texture gradients 2 x 2 | dP/dx, dP/dy 2 x 6
//
// The seed gives the sizes, not the encodings; those below are this model's (each an assumption
// named here, with its reason):
// - depth: linear eye depth over the view's [near, far] (ViewTransform::depth_word);
// - shader id: 0 for no surface (the background), else the scene material's index + 1, which
//   selects the shading function and its uniform parameters (L110);
// - colour: 8 bits a channel, as the bowling simulation used (L110);
// - normal: the unit shading normal, each component times 32767;
// - u, v: the texture coordinates' fractions, times 65536 (textures repeat);
// - gradients: the texture-space footprint of one pixel in u and in v, times 65536, saturating
//   at 65535 (the mip-map level's input);
// - dP/dx, dP/dy: the directions in which the surface point moves with the screen's x and y,
//   unit vectors times 32767 (the bump map's tangent frame needs only their directions).
//
// A record travels as its 34 bytes (pack/unpack, little-endian); the composition network and
// the faults act on those bytes.
#include <array>
#include <cstdint>
#include <cstring>

#include "firmware/math.hpp"

namespace rtsim::raster {

inline constexpr int kAppearanceBytes = 34;  ///< seed 004 L110
using AppearanceWord = std::array<std::uint8_t, kAppearanceBytes>;

struct Appearance {
  std::uint32_t depth = 0xFFFFFFFFu;
  std::uint8_t shader = 0;
  std::array<std::uint8_t, 3> colour{};
  std::array<std::int16_t, 3> normal{};
  std::uint16_t u = 0, v = 0;
  std::uint16_t footprint_u = 0, footprint_v = 0;
  std::array<std::int16_t, 3> dp_dx{}, dp_dy{};

  bool covered() const { return shader != 0; }
  Vec3 shading_normal() const;
  Vec3 tangent_x() const;
  double tex_u() const { return u / 65536.0; }
  double tex_v() const { return v / 65536.0; }
  Color intrinsic_colour() const { return Color(colour[0], colour[1], colour[2]) / 255.0; }
};

AppearanceWord pack(const Appearance& a);
Appearance unpack(const AppearanceWord& w);

/// Quantizers of the encodings above.
std::int16_t unit_component(double c);
std::uint16_t texture_fraction(double t);
std::uint16_t footprint_word(double f);
std::uint8_t colour_byte(double c);

/// The depth word of a packed record (its first 4 bytes, little-endian).
inline std::uint32_t depth_word(const AppearanceWord& w) {
  return static_cast<std::uint32_t>(w[0]) | (static_cast<std::uint32_t>(w[1]) << 8) |
         (static_cast<std::uint32_t>(w[2]) << 16) | (static_cast<std::uint32_t>(w[3]) << 24);
}

/// The z-compositing order of two packed records: nearer depth first; at equal depth words the
/// lower record, byte by byte. Any order of compositing then keeps the same sample, so the
/// image does not depend on how primitives are divided among rasterizers or in which order they
/// arrive (an assumption: the seed says only that depths are compared, L120).
inline bool nearer(const AppearanceWord& a, const AppearanceWord& b) {
  const std::uint32_t da = depth_word(a), db = depth_word(b);
  if (da != db) return da < db;
  return std::memcmp(a.data() + 4, b.data() + 4, kAppearanceBytes - 4) < 0;
}

/// The record of a sample no surface covers.
AppearanceWord background_word();

}  // namespace rtsim::raster
