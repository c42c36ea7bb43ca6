#pragma once
// Writes a Scene back as NFF or .bpt text that parse_nff / parse_bpt read to the same scene:
// numbers are printed with std::to_chars in the shortest form that reads back to the identical
// double. Used to export generated scenes (builtin:...) and for round-trip tests.
#include <string>

#include "firmware/scene.hpp"

namespace rtsim::scenes {

/// NFF text: 'b', the 'v' block when has_camera, lights (always with colour), then primitives in
/// order, with an 'f' line whenever the material changes. Throws std::invalid_argument for a
/// scene with Bezier patches (NFF has no patch entity).
std::string write_nff(const Scene& scene);

/// .bpt text of scene.patches (in primitive order). Throws std::invalid_argument when the scene
/// has primitives other than patches.
std::string write_bpt(const Scene& scene);

}  // namespace rtsim::scenes
