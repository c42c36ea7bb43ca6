#include "scenes/generators/plb_head.hpp"

#include <algorithm>
#include <cmath>

namespace rtsim::scenes {

namespace {

/// A bump of height `h` and angular radius `r` centred on direction `c` (unit), at unit
/// direction `d`: a smooth cosine cap.
double bump(const Vec3& d, const Vec3& c, double h, double r) {
  const double a = std::acos(std::clamp(glm::dot(d, c), -1.0, 1.0));
  if (a >= r) return 0.0;
  return h * 0.5 * (1.0 + std::cos(kPi * a / r));
}

/// The head's surface at polar angle `theta` (0 at the crown) and azimuth `phi` (0 facing +z,
/// the viewer): an ellipsoid displaced along its direction by the features.
Vec3 surface(double theta, double phi) {
  const Vec3 d(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
  double s = 1.0;
  s += bump(d, glm::normalize(Vec3(0.0, -0.05, 1.0)), 0.22, 0.28);  // nose
  s += bump(d, glm::normalize(Vec3(0.0, 0.35, 1.0)), 0.06, 0.55);   // brow
  s += bump(d, glm::normalize(Vec3(1.0, 0.0, -0.1)), 0.12, 0.30);   // ears
  s += bump(d, glm::normalize(Vec3(-1.0, 0.0, -0.1)), 0.12, 0.30);
  s += bump(d, glm::normalize(Vec3(0.0, -0.8, 0.6)), 0.08, 0.45);   // chin
  s -= bump(d, glm::normalize(Vec3(0.35, 0.15, 1.0)), 0.05, 0.18);  // eye sockets
  s -= bump(d, glm::normalize(Vec3(-0.35, 0.15, 1.0)), 0.05, 0.18);
  return Vec3(0.75 * d.x, 1.0 * d.y, 0.85 * d.z) * s;
}

Vec3 normal_at(double theta, double phi) {
  // The cross product of the surface's derivatives, by central differences, pointing out.
  constexpr double e = 1e-4;
  const double t = std::clamp(theta, e, kPi - e);
  const Vec3 dt = surface(t + e, phi) - surface(t - e, phi);
  const Vec3 dp = surface(t, phi + e) - surface(t, phi - e);
  Vec3 n = glm::cross(dp, dt);
  if (glm::dot(n, surface(t, phi)) < 0.0) n = -n;
  const double len = glm::length(n);
  return len > 0.0 ? n / len : glm::normalize(surface(t, phi));
}

}  // namespace

Scene make_plb_head() {
  Scene scene;
  scene.name = "builtin:plb-head";
  scene.has_camera = true;
  // In the centre of a square screen, its height about two thirds of the view's (L572).
  scene.camera.from = Vec3(0.0, 0.0, 4.5);
  scene.camera.at = Vec3(0.0);
  scene.camera.up = Vec3(0.0, 1.0, 0.0);
  scene.camera.angle_deg = 38.0;
  scene.camera.hither = 1e-3;
  scene.camera.width = 512;
  scene.camera.height = 512;
  scene.background = Color(0.08, 0.08, 0.12);
  scene.lights.push_back(Light{Vec3(3.0, 4.0, 6.0), Color(1.0)});
  scene.materials.push_back(Material{Color(0.85, 0.65, 0.55), 0.8, 0.2, 20.0, 0.0, 1.0});
  // A closed surface: its back faces are hidden and a rasterizer culls them.
  scene.surface_shading = {{"phong", true}};
  const int segs = kPlbHeadSegments, rings = kPlbHeadRings;
  // Vertex (i, j): ring i = 0 .. rings (0 and rings the poles), segment j.
  const auto theta = [&](int i) { return kPi * i / rings; };
  const auto phi = [&](int j) { return 2.0 * kPi * j / segs; };
  const auto add = [&](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& na, const Vec3& nb,
                       const Vec3& nc) {
    Polygon p;
    p.vertices = {a, b, c};
    p.normals = {na, nb, nc};
    scene.primitives.push_back(
        Primitive{PrimitiveKind::Polygon, static_cast<std::uint32_t>(scene.polygons.size()), 0, 0});
    scene.polygons.push_back(std::move(p));
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segs; ++j) {
      const double t0 = theta(i), t1 = theta(i + 1), p0 = phi(j), p1 = phi(j + 1);
      const Vec3 a = surface(t0, p0), b = surface(t1, p0), c = surface(t1, p1), d = surface(t0, p1);
      const Vec3 na = normal_at(t0, p0), nb = normal_at(t1, p0), nc = normal_at(t1, p1),
                 nd = normal_at(t0, p1);
      // Counter-clockwise seen from outside; a pole's quad is one triangle.
      if (i > 0) add(a, b, d, na, nb, nd);
      if (i < rings - 1) add(d, b, c, nd, nb, nc);
    }
  Bounds box;
  for (const auto& p : scene.polygons)
    for (const auto& v : p.vertices) box.extend(v);
  scene.modelling_space = box;
  return scene;
}

}  // namespace rtsim::scenes
