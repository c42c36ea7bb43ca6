#include "firmware/raster/raster_mesh.hpp"

#include <cmath>

#include "firmware/geometry/triangulate.hpp"
#include "firmware/kernels/bezier_patch_math.hpp"

namespace rtsim::raster {

namespace {

Vec3 unit_or(const Vec3& v, const Vec3& fallback) {
  const double len = glm::length(v);
  return len > 1e-300 && std::isfinite(len) ? v / len : fallback;
}

/// Adds triangle (a, b, c) if it has an area; its face normal from the winding, turned to the
/// side of its shading normals.
void add(RasterMesh& mesh, const RasterVertex& a, const RasterVertex& b, const RasterVertex& c,
         std::uint32_t material, std::uint32_t primitive, bool one_sided) {
  const Vec3 n = glm::cross(b.position - a.position, c.position - a.position);
  const double len = glm::length(n);
  if (!(len > 0.0) || !std::isfinite(len)) return;
  RasterTriangle t;
  t.v = {a, b, c};
  t.face_normal = n / len;
  if (glm::dot(t.face_normal, a.normal + b.normal + c.normal) < 0.0) t.face_normal = -t.face_normal;
  t.material = material;
  t.primitive = primitive;
  t.one_sided = one_sided;
  for (const auto& v : t.v) mesh.bounds.extend(v.position);
  mesh.triangles.push_back(t);
}

void add_polygon(RasterMesh& mesh, const scenes::Polygon& poly, std::uint32_t material,
                 std::uint32_t primitive, bool one_sided) {
  const auto tri = geometry::triangulate_polygon(poly.vertices);
  if (!tri.ok()) return;  // zero area: nothing to draw (the twin's conversion counts it)
  const bool normals = poly.normals.size() == poly.vertices.size();
  const bool uvs = poly.uvs.size() == poly.vertices.size();
  const auto vertex = [&](std::uint32_t i) {
    RasterVertex v;
    v.position = poly.vertices[i];
    v.normal = normals ? unit_or(poly.normals[i], tri.normal) : tri.normal;
    v.uv = uvs ? poly.uvs[i] : glm::dvec2(0.0);
    return v;
  };
  for (const auto& t : tri.triangles)
    add(mesh, vertex(t[0]), vertex(t[1]), vertex(t[2]), material, primitive, one_sided);
}

void add_sphere(RasterMesh& mesh, const scenes::Sphere& s, int segments, std::uint32_t material,
                std::uint32_t primitive) {
  const int around = std::max(3, segments), rings = std::max(2, segments / 2);
  const double r = std::fabs(s.radius);
  const auto vertex = [&](int i, int j) {
    const double theta = kPi * i / rings, phi = 2.0 * kPi * j / around;
    const Vec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    return RasterVertex{s.center + r * n, n, glm::dvec2(double(j) / around, double(i) / rings)};
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < around; ++j) {
      const RasterVertex a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1),
                         d = vertex(i, j + 1);
      // Counter-clockwise seen from outside; a pole's quads are triangles (a = d at the north
      // pole, b = c at the south).
      if (i == 0) {
        add(mesh, a, b, c, material, primitive, true);
      } else if (i + 1 == rings) {
        add(mesh, a, b, d, material, primitive, true);
      } else {
        add(mesh, a, b, d, material, primitive, true);
        add(mesh, d, b, c, material, primitive, true);
      }
    }
}

void add_cone(RasterMesh& mesh, const scenes::Cone& c, int segments, std::uint32_t material,
              std::uint32_t primitive) {
  const Vec3 axis = c.apex - c.base;
  const double height = glm::length(axis);
  if (!(height > 0.0)) return;
  const Vec3 w = axis / height;
  const Vec3 u = glm::normalize(
      glm::cross(w, std::fabs(w.x) < 0.9 ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 1.0, 0.0)));
  const Vec3 v = glm::cross(w, u);
  const double r0 = std::fabs(c.base_radius), r1 = std::fabs(c.apex_radius);
  const int around = std::max(3, segments);
  // The side's normal leans along the axis by the radius' change over the height.
  const auto vertex = [&](int j, bool top) {
    const double phi = 2.0 * kPi * j / around;
    const Vec3 radial = std::cos(phi) * u + std::sin(phi) * v;
    const Vec3 n = unit_or(radial * height + w * (r0 - r1), radial);
    return RasterVertex{(top ? c.apex : c.base) + (top ? r1 : r0) * radial, n,
                        glm::dvec2(double(j) / around, top ? 0.999 : 0.0)};
  };
  for (int j = 0; j < around; ++j) {
    const RasterVertex a = vertex(j, false), b = vertex(j + 1, false), c1 = vertex(j + 1, true),
                       d = vertex(j, true);
    // Open: seen from inside too (NFF), so two-sided.
    add(mesh, a, b, c1, material, primitive, false);
    add(mesh, a, c1, d, material, primitive, false);
  }
}

void add_patch(RasterMesh& mesh, const scenes::BezierPatch& patch, int segments,
               std::uint32_t material, std::uint32_t primitive) {
  const auto net = kernels::control_net_from(patch);
  if (!kernels::is_finite_net(net)) return;
  const int n = std::max(1, segments);
  std::vector<RasterVertex> grid(static_cast<std::size_t>((n + 1) * (n + 1)));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double s = double(i) / n, t = double(j) / n;
      Vec3 q, qu, qv;
      kernels::evaluate_with_derivatives(net, s, t, q, qu, qv);
      Vec3 normal;
      if (!kernels::patch_normal(net, s, t, normal)) normal = Vec3(0.0, 0.0, 1.0);
      grid[static_cast<std::size_t>(i * (n + 1) + j)] = {q, normal, glm::dvec2(s, t)};
    }
  const auto at = [&](int i, int j) { return grid[static_cast<std::size_t>(i * (n + 1) + j)]; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      // Patches (the teapot's) are not closed where they meet: two-sided.
      add(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), material, primitive, false);
      add(mesh, at(i, j), at(i + 1, j + 1), at(i, j + 1), material, primitive, false);
    }
}

}  // namespace

const scenes::SurfaceShading& surface_shading(const scenes::Scene& scene, std::uint32_t m) {
  static const scenes::SurfaceShading kPhong{};
  return m < scene.surface_shading.size() ? scene.surface_shading[m] : kPhong;
}

double estimated_triangles(const scenes::Scene& scene, const MeshSettings& settings) {
  double n = 0.0;
  for (const auto& p : scene.primitives) {
    switch (p.kind) {
      case scenes::PrimitiveKind::Polygon:
        n += static_cast<double>(scene.polygons[p.index].vertices.size());
        break;
      case scenes::PrimitiveKind::Sphere:
        n += static_cast<double>(settings.sphere_segments) * settings.sphere_segments;
        break;
      case scenes::PrimitiveKind::Cone:
        n += 2.0 * settings.cone_segments;
        break;
      case scenes::PrimitiveKind::Patch:
        n += 2.0 * settings.patch_segments * settings.patch_segments;
        break;
    }
  }
  return n;
}

RasterMesh build_raster_mesh(const scenes::Scene& scene, const MeshSettings& settings) {
  RasterMesh mesh;
  for (std::uint32_t p = 0; p < scene.primitives.size(); ++p) {
    const auto& prim = scene.primitives[p];
    switch (prim.kind) {
      case scenes::PrimitiveKind::Polygon:
        add_polygon(mesh, scene.polygons[prim.index], prim.material, p,
                    surface_shading(scene, prim.material).one_sided);
        break;
      case scenes::PrimitiveKind::Sphere:
        add_sphere(mesh, scene.spheres[prim.index], settings.sphere_segments, prim.material, p);
        break;
      case scenes::PrimitiveKind::Cone:
        add_cone(mesh, scene.cones[prim.index], settings.cone_segments, prim.material, p);
        break;
      case scenes::PrimitiveKind::Patch:
        add_patch(mesh, scene.patches[prim.index], settings.patch_segments, prim.material, p);
        break;
    }
  }
  return mesh;
}

}  // namespace rtsim::raster
