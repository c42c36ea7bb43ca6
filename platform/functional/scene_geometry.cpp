#include "platform/functional/scene_geometry.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/geometry/convex_quads.hpp"
#include "firmware/geometry/triangulate.hpp"

namespace rtsim::functional {

namespace {

/// `v` rounded to the nearest singles, as a machine's 32-bit records hold it.
Vec3 as_single(const Vec3& v) {
  return Vec3(static_cast<double>(static_cast<float>(v.x)),
              static_cast<double>(static_cast<float>(v.y)),
              static_cast<double>(static_cast<float>(v.z)));
}

/// Ullner's machines store convex quadrilaterals: split the polygon into convex quads (and
/// triangles given as quads with two equal vertices) and precompute each one's 20 parameters.
template <class Add, class Note>
void add_ullner_quads(const scenes::Polygon& poly, std::size_t id, const scenes::Primitive& p,
                      Add&& add, Note&& note, ConversionReport& report) {
  geometry::ConvexQuadReport quad_report;
  const auto quads = geometry::convert_polygon(poly.vertices, poly.normals, quad_report);
  std::size_t made = 0;
  for (const auto& q : quads) {
    // Same repair as for triangles: corner normals on the side of the quad's own normal.
    std::array<Vec3, 4> normals = q.normals;
    const Vec3 ng = glm::cross(q.corners[1] - q.corners[0], q.corners[3] - q.corners[0]);
    for (auto& n : normals)
      if (glm::dot(n, ng) < 0.0) n = -n;
    kernels::QuadRejection why{};
    if (auto k =
            kernels::UllnerQuadKernel::from(q.corners[0], q.corners[1], q.corners[2], q.corners[3],
                                            q.has_normals ? normals.data() : nullptr, why)) {
      add(*k, id, p.material);
      ++made;
    }
  }
  report.quads += made;
  if (made == 0) note(id, p, "polygon skipped: " + quad_report.summary());
}

}  // namespace

double scene_extent(const Bounds& b) {
  if (b.empty()) return 1.0;
  const Vec3 e = b.extent();
  const double m = std::max(e.x, std::max(e.y, e.z));
  return m > 0.0 && std::isfinite(m) ? m : 1.0;
}

SceneGeometry convert_scene(const scenes::Scene& scene, const RenderSettings& settings) {
  SceneGeometry g;
  ConversionReport& report = g.report;
  auto add = [&g](Shape shape, std::size_t prim_id, std::uint32_t material) {
    const Bounds b = std::visit([](const auto& s) { return s.bounds(); }, shape);
    g.shapes.push_back(ShapeRecord{std::move(shape), static_cast<std::int32_t>(prim_id), material});
    g.bounds.push_back(b);
    g.scene_bounds.extend(b);
  };
  auto note = [&report](std::size_t prim_id, const scenes::Primitive& p, const std::string& what) {
    ++report.rejected;
    if (report.messages.size() < kMaxConversionMessages) {
      std::string msg = "primitive " + std::to_string(prim_id);
      if (p.source_line > 0) msg += " (line " + std::to_string(p.source_line) + ")";
      report.messages.push_back(msg + ": " + what);
    }
  };

  for (std::size_t id = 0; id < scene.primitives.size(); ++id) {
    const scenes::Primitive& p = scene.primitives[id];
    switch (p.kind) {
      case scenes::PrimitiveKind::Sphere: {
        std::string why;
        scenes::Sphere sphere = scene.spheres[p.index];
        if (settings.prims_as_stored) {
          sphere.center = as_single(sphere.center);
          sphere.radius = static_cast<double>(static_cast<float>(sphere.radius));
        }
        if (auto k = kernels::SphereKernel::from(sphere, &why)) {
          add(*k, id, p.material);
          ++report.spheres;
        } else {
          note(id, p, "sphere skipped: " + why);
        }
        break;
      }
      case scenes::PrimitiveKind::Cone: {
        std::string why;
        if (auto k = kernels::ConeKernel::from(scene.cones[p.index], &why)) {
          add(*k, id, p.material);
          ++report.cones;
        } else {
          note(id, p, "cone skipped: " + why);
        }
        break;
      }
      case scenes::PrimitiveKind::Polygon: {
        const scenes::Polygon& poly = scene.polygons[p.index];
        if (settings.polygon_kernel == PolygonKernel::UllnerQuad) {
          add_ullner_quads(poly, id, p, add, note, report);
          break;
        }
        const auto tri = geometry::triangulate_polygon(poly.vertices);
        if (tri.rejected) {
          note(id, p, "polygon skipped: " + tri.reason);
          break;
        }
        const bool has_normals = poly.normals.size() == poly.vertices.size();
        std::size_t made = 0;
        for (const auto& t : tri.triangles) {
          Vec3 n[3];
          if (has_normals) {
            // Repair: vertex normals are put on the side of the triangle's own normal, so the
            // interpolation never blends opposite orientations (SPD's teapot writes some rim
            // normals inward and some outward); the shader then faces the result to the ray.
            const Vec3 ng = glm::cross(poly.vertices[t[1]] - poly.vertices[t[0]],
                                       poly.vertices[t[2]] - poly.vertices[t[0]]);
            for (int c = 0; c < 3; ++c) {
              n[c] = poly.normals[t[static_cast<std::size_t>(c)]];
              if (glm::dot(n[c], ng) < 0.0) n[c] = -n[c];
            }
          }
          const auto vertex = [&](int c) {
            const Vec3& q = poly.vertices[t[static_cast<std::size_t>(c)]];
            return settings.prims_as_stored ? as_single(q) : q;
          };
          const Vec3 v[3] = {vertex(0), vertex(1), vertex(2)};
          if (auto k = kernels::TriangleKernel::from(v[0], v[1], v[2], has_normals ? n : nullptr)) {
            add(*k, id, p.material);
            ++made;
          }
        }
        report.triangles += made;
        if (made == 0) note(id, p, "polygon skipped: no non-degenerate triangle");
        break;
      }
      case scenes::PrimitiveKind::Patch:
        add(PatchShape{std::make_unique<const kernels::BezierPatchKernel>(
                kernels::BezierPatchKernel::from(scene.patches[p.index], settings.bezier_iterations,
                                                 settings.bezier_culler_key_bits,
                                                 settings.bezier_arithmetic))},
            id, p.material);
        ++report.patches;
        break;
    }
  }
  return g;
}

}  // namespace rtsim::functional
