#include "firmware/hiddenline/screen_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "firmware/geometry/triangulate.hpp"

namespace rtsim::hiddenline {

namespace {

/// The clip planes in eye space, each keeping dot(p, n) >= 0: the near plane and the guard
/// band's four sides (one screen beyond each edge of the view).
std::array<glm::dvec4, 5> clip_planes(const raster::ViewTransform& v) {
  // screen_x = cx + ex / (ez pixel) >= -w  <=>  ex + (cx + w) pixel ez >= 0, and so on.
  const double w = v.width, h = v.height, px = v.pixel;
  return {glm::dvec4(0, 0, 1, -v.near), glm::dvec4(1, 0, (v.centre_x + w) * px, 0),
          glm::dvec4(-1, 0, (2 * w - v.centre_x) * px, 0),
          glm::dvec4(0, -1, (v.centre_y + h) * px, 0),
          glm::dvec4(0, 1, (2 * h - v.centre_y) * px, 0)};
}

double side(const glm::dvec4& pl, const Vec3& p) {
  return pl.x * p.x + pl.y * p.y + pl.z * p.z + pl.w;
}

/// Sutherland-Hodgman: the polygon (eye space) inside every plane.
std::vector<Vec3> clip_polygon(std::vector<Vec3> poly, const std::array<glm::dvec4, 5>& planes) {
  for (const auto& pl : planes) {
    std::vector<Vec3> out;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vec3& a = poly[i];
      const Vec3& b = poly[(i + 1) % poly.size()];
      const double sa = side(pl, a), sb = side(pl, b);
      if (sa >= 0) out.push_back(a);
      if ((sa >= 0) != (sb >= 0)) out.push_back(a + (b - a) * (sa / (sa - sb)));
    }
    poly = std::move(out);
    if (poly.empty()) break;
  }
  return poly;
}

/// The segment (eye space) inside every plane; false if none of it is.
bool clip_segment(Vec3& a, Vec3& b, const std::array<glm::dvec4, 5>& planes) {
  double t0 = 0.0, t1 = 1.0;
  for (const auto& pl : planes) {
    const double sa = side(pl, a), sb = side(pl, b);
    if (sa < 0 && sb < 0) return false;
    if (sa < 0) t0 = std::max(t0, sa / (sa - sb));
    if (sb < 0) t1 = std::min(t1, sa / (sa - sb));
  }
  if (t0 > t1) return false;
  const Vec3 a0 = a, d = b - a;
  a = a0 + d * t0;
  b = a0 + d * t1;
  return true;
}

struct Projection {
  const raster::ViewTransform& view;
  double units_per_pixel;
  double near, far;  ///< the depths mapped to 0 and 2^16 - 1
  ScreenPoint operator()(const Vec3& eye) const {
    const auto unit = [](double v) {
      return static_cast<std::int32_t>(
          std::clamp(std::lround(v), 0L, static_cast<long>(kScreenUnits - 1)));
    };
    const double sx = view.screen_x(eye), sy = view.screen_y(eye);
    // Projective depth: 1/z between 1/near (0) and 1/far (2^16 - 1).
    const double inv = 1.0 / std::max(eye.z, near);
    const double depth = (1.0 / near - inv) / (1.0 / near - 1.0 / far);
    return {unit((sx + view.width) * units_per_pixel), unit((sy + view.height) * units_per_pixel),
            unit(depth * (kScreenUnits - 1))};
  }
};

/// A planar polygon is convex if every corner turns the way its Newell normal says.
bool convex(const std::vector<Vec3>& p) {
  Vec3 normal{0.0};
  for (std::size_t i = 0; i < p.size(); ++i) normal += glm::cross(p[i], p[(i + 1) % p.size()]);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3 turn =
        glm::cross(p[(i + 1) % p.size()] - p[i], p[(i + 2) % p.size()] - p[(i + 1) % p.size()]);
    if (glm::dot(turn, normal) < 0.0) return false;
  }
  return true;
}

}  // namespace

ScreenScene to_screen(const scenes::Scene& scene, const raster::RasterMesh& mesh,
                      const raster::ViewTransform& view) {
  ScreenScene out;
  // The guard band, three screens a side, onto 2^16 units.
  out.units_per_pixel = std::floor((kScreenUnits - 1) / (3.0 * std::max(view.width, view.height)));
  out.origin_x = -view.width;
  out.origin_y = -view.height;
  const auto planes = clip_planes(view);
  // Everything is clipped in eye space first; the depths kept then set the depth's range, so
  // the 16 bits cover the scene's own depth and not the view's whole near-far range.
  std::vector<std::vector<Vec3>> eye_polygons;
  std::vector<std::pair<Vec3, Vec3>> eye_segments;
  double z_min = std::numeric_limits<double>::infinity(), z_max = 0.0;
  const auto depth_range = [&](const Vec3& p) {
    z_min = std::min(z_min, p.z);
    z_max = std::max(z_max, p.z);
  };
  // A hiding polygon (world space), clipped.
  const auto add_polygon = [&](const std::vector<Vec3>& world) {
    std::vector<Vec3> eye;
    for (const Vec3& p : world) eye.push_back(view.to_eye(p));
    std::vector<Vec3> kept = clip_polygon(eye, planes);
    if (kept.size() < 3) {
      ++out.culled;
      return;
    }
    if (kept.size() != eye.size()) ++out.clipped;
    for (const Vec3& p : kept) depth_range(p);
    eye_polygons.push_back(std::move(kept));
  };
  // A segment (world space): clipped and projected; shared edges once.
  std::map<std::pair<std::array<double, 3>, std::array<double, 3>>, bool> seen;
  const auto add_segment = [&](const Vec3& wa, const Vec3& wb) {
    std::array<double, 3> ka{wa.x, wa.y, wa.z}, kb{wb.x, wb.y, wb.z};
    if (kb < ka) std::swap(ka, kb);
    if (!seen.emplace(std::make_pair(ka, kb), true).second) return;
    Vec3 a = view.to_eye(wa), b = view.to_eye(wb);
    if (!clip_segment(a, b, planes)) return;
    depth_range(a);
    depth_range(b);
    eye_segments.emplace_back(a, b);
  };
  std::vector<bool> is_polygon(scene.primitives.size(), false);
  for (std::size_t k = 0; k < scene.primitives.size(); ++k) {
    const scenes::Primitive& prim = scene.primitives[k];
    if (prim.kind != scenes::PrimitiveKind::Polygon) continue;
    is_polygon[k] = true;
    const std::vector<Vec3>& v = scene.polygons[prim.index].vertices;
    if (v.size() < 3) continue;
    for (std::size_t i = 0; i < v.size(); ++i) add_segment(v[i], v[(i + 1) % v.size()]);
    // Convex: one hiding polygon; else its triangles (L1898).
    if (convex(v)) {
      add_polygon(v);
      continue;
    }
    ++out.concave_split;
    const geometry::TriangulationResult tri = geometry::triangulate_polygon(v);
    for (const auto& t : tri.triangles) add_polygon({v[t[0]], v[t[1]], v[t[2]]});
  }
  // The other primitives: their tessellation's triangles and edges.
  for (const raster::RasterTriangle& t : mesh.triangles) {
    if (t.primitive < is_polygon.size() && is_polygon[t.primitive]) continue;
    add_polygon({t.v[0].position, t.v[1].position, t.v[2].position});
    for (int i = 0; i < 3; ++i)
      add_segment(t.v[static_cast<std::size_t>(i)].position,
                  t.v[static_cast<std::size_t>((i + 1) % 3)].position);
  }
  // Projected: 1/z over the depths kept (a flat scene gets a range of its own depth to twice it).
  if (!(z_max > z_min)) {
    z_min = std::isfinite(z_min) ? z_min : view.near;
    z_max = 2.0 * z_min;
  }
  const Projection project{view, out.units_per_pixel, z_min, z_max};
  for (const std::vector<Vec3>& kept : eye_polygons) {
    std::vector<ScreenPoint> screen;
    for (const Vec3& p : kept) {
      const ScreenPoint s = project(p);
      if (screen.empty() || s != screen.back()) screen.push_back(s);
    }
    while (screen.size() > 1 && screen.front() == screen.back()) screen.pop_back();
    if (screen.size() >= 3) out.polygons.push_back(std::move(screen));
  }
  for (const auto& [a, b] : eye_segments) {
    const ScreenPoint sa = project(a), sb = project(b);
    if (sa == sb) continue;
    out.segments.push_back({sa, sb, static_cast<std::uint32_t>(out.segments.size())});
  }
  return out;
}

}  // namespace rtsim::hiddenline
