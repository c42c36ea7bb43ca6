#pragma once
// builtin:plb-head — the stand-in for the coherence study's PLB head (seed 004 L570-L572: "a
// scanned model of a human head", 59,592 polygons, "placed in the center of the screen and spun
// ... around a vertical axis through its center"). The scan is not available; this is a closed,
// finely tessellated head-like surface of about as many triangles: an ellipsoid (wider than deep,
// taller than wide) with a nose, brow, ears and chin raised on it, as a latitude-longitude mesh
// of 244 segments and 123 rings (59,536 triangles, the study's count within 0.1%), its vertex
// normals from the surface. What it stands in for, the migration study needs: many small
// primitives spread over a compact closed object at the screen's centre, so that a spin moves
// every one of them across the screen at a rate set by its distance from the axis.
#include "firmware/scene.hpp"

namespace rtsim::scenes {

inline constexpr int kPlbHeadSegments = 244;
inline constexpr int kPlbHeadRings = 123;

Scene make_plb_head();

}  // namespace rtsim::scenes
