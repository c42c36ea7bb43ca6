#pragma once
// builtin:ullner-random-N — the hypothetical scene of Ullner's analytic model of the subdivided
// peripheral (seed 000 L608-L660; note 000 §2.5 "Analytic model", §7.5 S1/S2): n_p = N polygons
// in the unit modelling cube with total surface area a_t = 2 ("enough surface area to stretch
// through the modeling space twice", L654), rays travelling d_r ~ 1/2 of the modelling space
// before a hit (L654), 512 x 512 (L590), "without lighting effects" (L590).
//
// Construction (the thesis describes only the statistics; each choice is named below):
// - N squares (convex quads) of side sqrt(a_t / N), so the areas sum to a_t exactly (up to
//   rounding);
// - each square uniformly randomly oriented (a uniform random unit quaternion, as for
//   ullner-cubes), its centre uniform over the positions where that orientation keeps all four
//   vertices inside [0,1]^3 (per axis, the square's half extent h(|u_i| + |v_i|) from each face);
//   squares may interpenetrate (independent placement);
// - N >= kUllnerRandomMinPolygons: below 4 a square of area 2/N no longer fits the unit cube in
//   every orientation (its half diagonal sqrt(1/N) exceeds 1/2), and for N = 1 no planar polygon
//   of area 2 fits at all (the largest section of the unit cube has area sqrt(2));
// - one white, opaque, non-reflective material (kd 1, ks 0, T 0) and no lights: only primary
//   rays are traced, as in the thesis's frame-time estimates;
// - the view: see kUllnerRandomEye.. in ullner_random.cpp and the measured d_r in
//   tests/scene_ullner_random_test.cpp.
// The vertices of square k are drawn from the generator stream after those of squares 0..k-1,
// so for one seed the scene depends only on N. Vertices are counter-clockwise about the square's
// normal u x v.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "firmware/scene.hpp"

namespace rtsim::scenes {

inline constexpr double kUllnerRandomTotalArea = 2.0;               ///< a_t, seed 000 L654
inline constexpr std::size_t kUllnerRandomMinPolygons = 4;          ///< see above
inline constexpr std::size_t kUllnerRandomMaxPolygons = 2'000'000;  ///< memory bound (~200 MB)
inline constexpr std::size_t kUllnerRandomDefaultPolygons = 1000;   ///< n_p, seed 000 L590, L654
inline constexpr std::uint64_t kUllnerRandomDefaultSeed = 1983;     ///< the thesis year
inline constexpr std::string_view kUllnerRandomPrefix = "ullner-random-";

/// Makes builtin:ullner-random-N. polygon_count outside [kUllnerRandomMinPolygons,
/// kUllnerRandomMaxPolygons] throws std::invalid_argument.
Scene make_ullner_random(std::size_t polygon_count, std::uint64_t seed = kUllnerRandomDefaultSeed);

/// N of a name "ullner-random-N" (N in decimal, no sign, no leading zero); nullopt if the name
/// is not of that form. N may be out of range: the caller reports that.
std::optional<std::size_t> parse_ullner_random_name(std::string_view name);

}  // namespace rtsim::scenes
