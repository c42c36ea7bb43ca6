#pragma once
// builtin:ullner-sheets-N — Ullner's hypothetical scene for Fig. 2-18 read literally (seed 000
// L654): n_p polygons whose total area a_t = 2 is "enough surface area to stretch through the
// modeling space twice", and rays that "travel through about half of the modeling space" before
// they hit (d_r = 1/2). Two sheets cross the unit modelling cube, each cut into k x k
// quadrilaterals (k = round(sqrt(N/2)), so the scene has 2k^2 ~ N polygons); the first lies at
// y ~ 1/2, the second at y ~ 4/5, both slightly tilted so no polygon lies on a grid plane. The
// eye looks along +y from outside the cube with a narrow view, so every primary ray enters the
// modelling space at y = 0 and travels about half of it to the first sheet.
//
// builtin:ullner-sheets-lit-N adds one light at the eye: every primary ray hits the first sheet
// and casts one shadow ray that nothing occludes, the "doubling this figure for shadowing" of
// the ray-tracing pipeline's estimate (L743).
//
// Compare builtin:ullner-random-N: the same n_p and a_t as many small randomly oriented squares,
// which break the model's assumption about occupied subvolumes (L642).
#include <cstddef>
#include <optional>
#include <string_view>

#include "firmware/scene.hpp"

namespace rtsim::scenes {

inline constexpr std::string_view kUllnerSheetsPrefix = "ullner-sheets-";
inline constexpr std::string_view kUllnerSheetsLitPrefix = "ullner-sheets-lit-";
inline constexpr std::size_t kUllnerSheetsMinPolygons = 2;
inline constexpr std::size_t kUllnerSheetsMaxPolygons = 2'000'000;

/// The scene for about `polygon_count` polygons (exactly 2 k^2, k = round(sqrt(N / 2))); `lit`:
/// with one light at the eye.
Scene make_ullner_sheets(std::size_t polygon_count, bool lit = false);

/// N of "ullner-sheets-N" or "ullner-sheets-lit-N" (canonical decimal), or nothing; `lit` (if
/// given) says which.
std::optional<std::size_t> parse_ullner_sheets_name(std::string_view name, bool* lit = nullptr);

}  // namespace rtsim::scenes
