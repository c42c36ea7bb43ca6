#include "firmware/accel/primitive_bounds.hpp"

#include <algorithm>
#include <cmath>

namespace rtsim::accel {

Bounds primitive_bounds(const scenes::Scene& scene, const scenes::Primitive& p) {
  Bounds b;
  switch (p.kind) {
    case scenes::PrimitiveKind::Sphere: {
      const scenes::Sphere& s = scene.spheres.at(p.index);
      const double r = std::fabs(s.radius);
      b.extend(s.center - Vec3(r));
      b.extend(s.center + Vec3(r));
      break;
    }
    case scenes::PrimitiveKind::Polygon:
      for (const Vec3& v : scene.polygons.at(p.index).vertices) b.extend(v);
      break;
    case scenes::PrimitiveKind::Cone: {
      const scenes::Cone& c = scene.cones.at(p.index);
      const Vec3 axis = c.apex - c.base;
      const double len = glm::length(axis);
      Vec3 reach(1.0);  // per unit radius; a full box when the axis is undefined
      if (len > 0.0 && std::isfinite(len)) {
        const Vec3 n = axis / len;
        for (int k = 0; k < 3; ++k) reach[k] = std::sqrt(std::max(0.0, 1.0 - n[k] * n[k]));
      }
      b.extend(c.base - reach * std::fabs(c.base_radius));
      b.extend(c.base + reach * std::fabs(c.base_radius));
      b.extend(c.apex - reach * std::fabs(c.apex_radius));
      b.extend(c.apex + reach * std::fabs(c.apex_radius));
      break;
    }
    case scenes::PrimitiveKind::Patch:
      for (const Vec3& v : scene.patches.at(p.index).control) b.extend(v);
      break;
  }
  return b;
}

std::vector<Bounds> primitive_bounds(const scenes::Scene& scene) {
  std::vector<Bounds> out;
  out.reserve(scene.primitives.size());
  for (const scenes::Primitive& p : scene.primitives) out.push_back(primitive_bounds(scene, p));
  return out;
}

}  // namespace rtsim::accel
