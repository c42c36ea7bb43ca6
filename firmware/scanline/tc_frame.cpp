#include "firmware/scanline/tc_frame.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/shading/whitted_shader.hpp"

namespace rtsim::scanline {

TcFrame tc_frame(const scenes::Scene& scene, const raster::RasterMesh& mesh, int width, int height,
                 const shading::ShadeParams& shade) {
  TcFrame f;
  f.view = raster::ViewTransform::camera(scene.camera, width, height, mesh.bounds);
  // z has 12 bits after the perspective division (L1266, L1340), and z_s = f (e_z - n) /
  // ((f - n) e_z) spends them near the near plane: the near plane sits at the scene's nearest
  // bounding corner, not the camera's hither (at least a thousandth of the far distance, where
  // the eye is inside the bounds; nearer surfaces are clipped).
  {
    raster::ViewTransform& w = f.view;
    double lo = kInfinity;
    if (!mesh.bounds.empty())
      for (int c = 0; c < 8; ++c) {
        const Vec3 p((c & 1) ? mesh.bounds.hi.x : mesh.bounds.lo.x,
                     (c & 2) ? mesh.bounds.hi.y : mesh.bounds.lo.y,
                     (c & 4) ? mesh.bounds.hi.z : mesh.bounds.lo.z);
        lo = std::min(lo, glm::dot(p - w.origin, w.forward));
      }
    w.near = std::max({w.near, 1e-3 * w.far, std::isfinite(lo) ? 0.999 * lo : 0.0});
    if (!(w.near < w.far)) w.near = 1e-3 * w.far;
  }
  const raster::ViewTransform& v = f.view;
  // Clip coordinates from eye coordinates (e = (p - o).(right, up, forward)):
  //   x_c = e_x 2 / (pixel width) + (2 c_x / width - 1) e_z, y_c likewise (y up),
  //   z_c = (e_z - near) far / (far - near), w = e_z.
  const double kx = 2.0 / (v.pixel * width), ky = 2.0 / (v.pixel * height);
  const double ax = 2.0 * v.centre_x / width - 1.0, ay = 1.0 - 2.0 * v.centre_y / height;
  const double zs = v.far / (v.far - v.near);
  const Vec3 cx = kx * v.right + ax * v.forward, cy = ky * v.up + ay * v.forward,
             cz = zs * v.forward, cw = v.forward;
  const Vec3 columns[4] = {cx, cy, cz, cw};
  const double offsets[4] = {-glm::dot(v.origin, cx), -glm::dot(v.origin, cy),
                             -glm::dot(v.origin, cz) - zs * v.near, -glm::dot(v.origin, cw)};
  for (std::size_t c = 0; c < 4; ++c) {
    f.literals.matrix[0][c] = static_cast<float>(columns[c].x);
    f.literals.matrix[1][c] = static_cast<float>(columns[c].y);
    f.literals.matrix[2][c] = static_cast<float>(columns[c].z);
    f.literals.matrix[3][c] = static_cast<float>(offsets[c]);
  }
  for (std::size_t k = 0; k < 3; ++k) f.literals.ambient[k] = static_cast<float>(shade.ambient);
  f.literals.point_light = !scene.lights.empty();
  if (!scene.lights.empty()) {
    const scenes::Light& l = scene.lights.front();
    const Vec3 centre = mesh.bounds.empty() ? Vec3(0.0) : mesh.bounds.center();
    const Vec3 d = l.position - centre;
    const double len = glm::length(d);
    const Vec3 dir = len > 0.0 ? d / len : Vec3(0.0, 0.0, 1.0);
    const double intensity = shading::effective_light_intensity(shade, 1);
    for (std::size_t k = 0; k < 3; ++k) {
      f.literals.point[k] = static_cast<float>(intensity * l.color[static_cast<int>(k)]);
      f.literals.direction[k] = static_cast<float>(dir[static_cast<int>(k)]);
    }
  }
  f.polygons.reserve(mesh.triangles.size());
  f.primitive.reserve(mesh.triangles.size());
  for (const raster::RasterTriangle& t : mesh.triangles) {
    TcPolygon p;
    // The host turns a polygon's normals to the eye's side, as the ray tracers shade both sides
    // (a closed surface's back faces are hidden anyway).
    const double facing = glm::dot(t.face_normal, v.origin - t.v[0].position) < 0.0 ? -1.0 : 1.0;
    for (std::size_t k = 0; k < 4; ++k) {
      const raster::RasterVertex& rv = t.v[std::min<std::size_t>(k, 2)];
      p.vertex[k] = rv.position;
      p.normal[k] = facing * rv.normal;
    }
    const scenes::Material m =
        t.material < scene.materials.size() ? scene.materials[t.material] : scenes::Material{};
    p.colour = m.color * m.kd;
    f.polygons.push_back(p);
    f.primitive.push_back(t.primitive);
  }
  return f;
}

}  // namespace rtsim::scanline
