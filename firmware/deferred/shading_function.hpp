#pragma once
// PixelFlow's shading functions (seed 004 L97, L112): the bowling example's three, split into the
// parts of Fig. 7 (L37-L53) — pre-light (shader-specific), the common light loop run once for
// every pixel that needs it, post-light (shader-specific) — and a plain Phong function for
// scenes that name none (NFF scenes run with one shader, the requirement).
//
// Each function's table lookups (L148-L152): a pin pixel makes four (the mip-mapped label and
// dirt, the bump-mapped scuffs, the shadow map), an alley pixel three (the mip-mapped wood, the
// shadow map, the reflection map), a ball or Phong pixel one (the shadow map), a shadow lookup
// for every light that casts shadows.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace rtsim::deferred {

enum class ShadingFunction : std::uint8_t { Phong, Pin, Alley, Ball };
inline constexpr int kShadingFunctions = 4;

/// The functions by name (scenes::SurfaceShading::shader), as scenes and stats.json spell them.
inline constexpr std::array<std::string_view, kShadingFunctions> kShadingFunctionNames = {
    "phong", "pin", "alley", "ball"};

inline std::string_view name_of(ShadingFunction f) {
  return kShadingFunctionNames[static_cast<std::size_t>(f)];
}
inline std::optional<ShadingFunction> shading_function_named(std::string_view name) {
  for (std::size_t i = 0; i < kShadingFunctionNames.size(); ++i)
    if (kShadingFunctionNames[i] == name) return static_cast<ShadingFunction>(i);
  return std::nullopt;
}

/// The table lookups a shading node makes (L148), by what they read.
enum class Lookup : std::uint8_t { Label, Dirt, Scuffs, Wood, Shadow, Reflection };
inline constexpr int kLookups = 6;
inline constexpr std::array<std::string_view, kLookups> kLookupNames = {
    "label", "dirt", "scuffs", "wood", "shadow", "reflection"};

}  // namespace rtsim::deferred
