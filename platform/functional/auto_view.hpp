#pragma once
// A view and lights for scenes whose files have none (.bpt patch files), and other views of a
// scene (view.azimuth_deg, view.elevation_deg).
#include "firmware/bounds.hpp"
#include "firmware/scene.hpp"

namespace rtsim::functional {

/// Field of view of the automatic camera, degrees (assumption: a moderate telephoto that
/// frames the bounding sphere without strong perspective).
inline constexpr double kAutoViewAngleDeg = 40.0;
/// Direction from the scene centre to the eye (z up): from the front-left and above, so a
/// teapot in the SPD orientation shows its spout on the right.
inline constexpr double kAutoViewDir[3] = {0.35, -1.0, 0.55};
/// Resolution of the automatic camera.
inline constexpr int kAutoViewResolution = 512;

/// Sets scene.camera to look at the centre of `bounds` from kAutoViewDir, far enough that the
/// bounding sphere about fills the view; adds two white lights (key and fill) if the scene has
/// none.
void frame_automatically(scenes::Scene& scene, const Bounds& bounds);

/// Turns the camera's eye about the point it looks at: `azimuth_deg` about its up vector
/// (counter-clockwise seen from above), then `elevation_deg` toward up, the elevation kept
/// within 89 degrees of the horizontal. Its distance, field of view and up stay. A camera
/// looking along its up turns about an arbitrary horizontal.
void turn_view(scenes::Camera& camera, double azimuth_deg, double elevation_deg);

}  // namespace rtsim::functional
