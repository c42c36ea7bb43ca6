#pragma once
// The bowling scene of PixelFlow's worked example (seed 004 L89-L112), a stand-in: the paper's
// model and images are lost, so this is built from what the text says — ten pins, an alley and a
// ball, about 10,700 triangles (L93), three shading functions (pin, alley, ball; L97), an ambient
// light and one shadow-casting point light (L97) — and from a regulation alley's dimensions
// (a pin 15 in tall and 4.766 in across, pins 12 in apart, a 41.5 in lane, an 8.5 in ball: the
// USBC's, an assumption of this model). Moment: the ball has just reached the headpin of the
// "Textbook Strike" (L91), which leans back with the 3 pin behind it.
//
// Every surface is triangles with vertex normals and texture coordinates (u round a pin and v up
// it; u across the lane and v along it), so a rasterizer interpolates both (Fig. 8, L99-L110).
// The materials carry their shading function (scenes::SurfaceShading); the pins and the ball are
// closed (one-sided), the lane's top is seen only from above.
#include "firmware/scene.hpp"

namespace rtsim::scenes {

/// Segments round a pin and rings up its profile; segments round the ball and its rings.
inline constexpr int kBowlingPinSegments = 32;
inline constexpr int kBowlingPinRings = 14;
inline constexpr int kBowlingBallSegments = 40;
inline constexpr int kBowlingBallRings = 21;

/// Makes builtin:bowling, 640 x 512 (the paper's frame, L93).
Scene make_bowling();

}  // namespace rtsim::scenes
