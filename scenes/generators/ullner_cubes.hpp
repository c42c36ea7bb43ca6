#pragma once
// Ullner's Fig 2-19 test scene (seed 000 L668; note 000 §7.5 S3): "eighty-three randomly
// oriented cubes distributed uniformly throughout the modeling space". Each cube is six convex
// quadrilateral Polygons, vertices counter-clockwise seen from outside (83 x 6 = 498 quads).
//
// Size, view and resolution are not in the thesis (note 000 §7.5); the choices are named below:
// - modelling space: the unit cube [0,1]^3 (the unit modelling cube of Fig 2-18, seed 000 L654);
// - cube centres uniform over the part of the modelling space where a cube of any orientation
//   stays inside it (a margin of the half diagonal), so a grid over [0,1]^3 holds every vertex;
// - orientations uniform over all rotations (a uniform random unit quaternion);
// - cubes may interpenetrate: "uniformly distributed" is read as independent placement.
#include <cstdint>

#include "firmware/scene.hpp"

namespace rtsim::scenes {

inline constexpr int kUllnerCubeCount = 83;                ///< seed 000 L668
inline constexpr double kUllnerCubeEdge = 0.1;             ///< edge length, modelling-space units
inline constexpr std::uint64_t kUllnerDefaultSeed = 1983;  ///< the thesis year

/// Makes builtin:ullner-cubes. `cube_count` >= 1 (throws std::invalid_argument otherwise).
Scene make_ullner_cubes(std::uint64_t seed = kUllnerDefaultSeed, int cube_count = kUllnerCubeCount);

}  // namespace rtsim::scenes
