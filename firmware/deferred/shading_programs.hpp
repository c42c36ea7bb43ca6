#pragma once
// The SIMD programs of the shading functions (seed 004 L37-L53, L69-L71, L134-L146): each part
// of deferred_shader.cpp's Fig. 7 split, written against the instruction stream
// (simd_stream.hpp) in the representations the paper's programmers favour ("whenever possible,
// we use fixed-point or integer representations", L13). Running a program counts the SIMD
// instructions the GP issues for that part, once for all the pixels that need it; at Fig. 6's
// times (L5-L13) that is the part's time, to set beside Fig. 9's measured ones.
//
// Representations (Fig. 8, L99-L110, says how the appearance parameters arrive):
// - short (2 bytes): colours, normals and other unit vectors, cosines, texture coordinates and
//   footprints, blend weights (Fig. 8 holds colour in bytes, normals, u,v and gradients in
//   2-byte words);
// - long (4 bytes): depth (a 4-byte word) and what is built from it: the surface point and its
//   coordinates in a light's or a mirror's view. Directions from a point are narrowed to shorts
//   once the subtraction is done.
// The GP folds uniform transforms (L61): a point in another view is one dot product a row.
#include <array>
#include <cstdint>
#include <string_view>

#include "firmware/deferred/deferred_shader.hpp"
#include "firmware/deferred/shading_function.hpp"
#include "firmware/deferred/simd_stream.hpp"

namespace rtsim::deferred {

/// The parts a shading node runs: Fig. 9's rows, plus the surface point every covered pixel
/// needs first (Fig. 9 lists it in no row).
enum class ShadingPart : std::uint8_t {
  Surface,     ///< the point from the depth word, the direction to the eye (common)
  Crown,       ///< pin, pre-light: the procedural crown
  Label,       ///< pin, pre-light: the mip-mapped label
  Scuffs,      ///< pin, pre-light: the bump-mapped scuffs
  Dirt,        ///< pin, pre-light: the mip-mapped dirt
  PinPhong,    ///< pin, post-light: Phong
  Wood,        ///< alley, pre-light: the mip-mapped wood
  Reflection,  ///< alley, post-light: Phong and the reflection map
  BallPhong,   ///< ball, post-light: Phong
  Phong,       ///< the plain function of scenes that name none, post-light
  Light,       ///< the common loop, once a light: shadow-map test, diffuse, specular
};
inline constexpr int kShadingParts = 11;
inline constexpr std::array<std::string_view, kShadingParts> kShadingPartNames = {
    "surface", "crown",      "label",      "scuffs", "dirt", "pin_phong",
    "wood",    "reflection", "ball_phong", "phong",  "light"};

/// What the programs depend on that is uniform over a frame.
struct ProgramUniforms {
  /// The largest Phong exponent of the frame's materials: the common light loop raises r.v to
  /// it for every pixel (by repeated squaring).
  double max_shine = 1.0;
  /// Levels of the mip-mapped textures (a 256-texel texture has 9).
  int texture_levels = 9;
};

/// Each part's instructions.
struct ShadingPrograms {
  std::array<simd::InstructionMix, kShadingParts> parts{};
  const simd::InstructionMix& of(ShadingPart p) const { return parts[static_cast<std::size_t>(p)]; }
};

/// Runs every part's program on an instruction stream.
ShadingPrograms shading_programs(const ProgramUniforms& uniforms);

/// The parts function `f` runs, pre-light and post-light.
std::array<bool, kShadingParts> parts_of(ShadingFunction f);

/// The instructions a shading node issues for a region-sample whose shading did `work` (Fig. 7:
/// each function present runs its parts once; the light loop runs once a light).
simd::InstructionMix region_instructions(const ShadingPrograms& programs, const RegionWork& work);

}  // namespace rtsim::deferred
