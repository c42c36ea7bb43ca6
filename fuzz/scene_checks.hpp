#pragma once
// What every scene a reader returns must satisfy, whatever the input was: the renderer and the
// machines index and compute with it without checking again. A scene that breaks one of these
// is a finding like a crash (the reader accepted input it should have refused, or built the
// scene wrongly), so the check aborts with the reason and libFuzzer saves the input.
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>

#include "firmware/scene.hpp"

namespace rtsim::fuzz {

[[noreturn]] inline void scene_defect(const char* what) {
  std::fprintf(stderr, "fuzz: the reader returned a scene that %s\n", what);
  std::abort();
}

inline bool finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

inline void check_scene(const scenes::Scene& s) {
  using scenes::PrimitiveKind;
  if (s.primitives.empty()) scene_defect("has no primitive");
  for (const auto& p : s.primitives) {
    std::size_t count = 0;
    switch (p.kind) {
      case PrimitiveKind::Sphere:
        count = s.spheres.size();
        break;
      case PrimitiveKind::Polygon:
        count = s.polygons.size();
        break;
      case PrimitiveKind::Cone:
        count = s.cones.size();
        break;
      case PrimitiveKind::Patch:
        count = s.patches.size();
        break;
      default:
        scene_defect("has a primitive of no known kind");
    }
    if (p.index >= count) scene_defect("has a primitive whose index is out of range");
    if (p.material >= s.materials.size())
      scene_defect("has a primitive whose material is out of range");
  }
  for (const auto& sp : s.spheres)
    if (!finite(sp.center) || !(sp.radius > 0.0) || !std::isfinite(sp.radius))
      scene_defect("has a sphere with a non-finite centre or a radius not > 0");
  for (const auto& poly : s.polygons) {
    if (poly.vertices.size() < 3) scene_defect("has a polygon with fewer than 3 vertices");
    if (!poly.normals.empty() && poly.normals.size() != poly.vertices.size())
      scene_defect("has a polygon whose normals do not match its vertices");
    for (const auto& v : poly.vertices)
      if (!finite(v)) scene_defect("has a non-finite polygon vertex");
    for (const auto& n : poly.normals)
      if (!finite(n)) scene_defect("has a non-finite polygon normal");
  }
  for (const auto& c : s.cones)
    if (!finite(c.base) || !finite(c.apex) || !std::isfinite(c.base_radius) ||
        !std::isfinite(c.apex_radius))
      scene_defect("has a non-finite cone");
  for (const auto& patch : s.patches)
    for (const auto& v : patch.control)
      if (!finite(v)) scene_defect("has a non-finite patch control point");
  for (const auto& l : s.lights)
    if (!finite(l.position) || !finite(l.color)) scene_defect("has a non-finite light");
  for (const auto& m : s.materials)
    if (!finite(m.color) || !std::isfinite(m.kd) || !std::isfinite(m.ks) ||
        !std::isfinite(m.shine) || !std::isfinite(m.transmittance) || !std::isfinite(m.ior))
      scene_defect("has a non-finite material");
  if (!finite(s.background)) scene_defect("has a non-finite background");
  if (s.has_camera) {
    const auto& c = s.camera;
    if (!finite(c.from) || !finite(c.at) || !finite(c.up) || !std::isfinite(c.angle_deg) ||
        !std::isfinite(c.hither))
      scene_defect("has a non-finite camera");
    if (c.width < 1 || c.height < 1) scene_defect("has a camera with an empty image");
  }
}

}  // namespace rtsim::fuzz
