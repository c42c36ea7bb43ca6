#pragma once
// SPD's teapot scene, built in: the Newell teapot's 32 Bezier patches (builtin:teapot) cut into
// triangles with vertex normals, on a 2 x 2 checkerboard, with the view, lights, background and
// materials of Eric Haines' Standard Procedural Databases teapot generator (the header of
// shared/scenes/teapot-s2.nff). It is a polygon object in empty space whose screen coverage
// follows the eye's distance: what pxpl5-raytrace's rows-against-squares figure needs (VOL2 Fig.
// 9, seed 004 L369), with no path to shared/.
#include "firmware/scene.hpp"

namespace rtsim::scenes {

/// builtin:spd-teapot: each patch evaluated on a `steps` x `steps` grid of (u, v); triangles
/// with no area (at the lid's and bottom's poles) are left out.
Scene make_spd_teapot(int steps = 4);

/// builtin:spd-teapot-patches: the same scene with the teapot kept as its 32 Bezier patches
/// (as SPD's generator can also write it): patches beside polygons, for Wang's pipeline, whose
/// host intersects the checkerboard itself.
Scene make_spd_teapot_patches();

}  // namespace rtsim::scenes
