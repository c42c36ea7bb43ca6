#pragma once
// builtin:default — a small scene that exercises every shading path of the renderer and looks
// good at a glance: a checkerboard floor of quads, a mirror sphere (Ks high), a glass sphere
// (T high, ior 1.5), diffuse and glossy spheres, two lights, 512 x 512.
#include "firmware/scene.hpp"

namespace rtsim::scenes {

inline constexpr int kDefaultFloorTiles = 8;           ///< checkerboard tiles per side
inline constexpr double kDefaultFloorHalfWidth = 4.0;  ///< floor spans [-4, 4]^2 at z = 0
inline constexpr int kDefaultImageSize = 512;

Scene make_default_scene();

}  // namespace rtsim::scenes
