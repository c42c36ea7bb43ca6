#pragma once
// Bounds of a scene's primitives, the input of the grid and the shell hierarchy. Slot i is
// scene.primitives[i] (scene-file order).
#include <vector>

#include "firmware/bounds.hpp"
#include "firmware/scene.hpp"

namespace rtsim::accel {

/// Sphere: centre +- |radius|. Polygon: its vertices. Cone/cylinder: the two end circles
/// (a circle of radius r around c with unit axis n spans c_k +- r sqrt(1 - n_k^2) on axis k).
/// Bezier patch: its 16 control points (the convex-hull property). Degenerate primitives get
/// the bounds of what they have (e.g. a cone with coincident ends: a box of its larger radius).
std::vector<Bounds> primitive_bounds(const scenes::Scene& scene);

Bounds primitive_bounds(const scenes::Scene& scene, const scenes::Primitive& p);

}  // namespace rtsim::accel
