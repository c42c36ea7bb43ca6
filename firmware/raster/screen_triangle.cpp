#include "firmware/raster/screen_triangle.hpp"

#include <algorithm>
#include <cmath>

namespace rtsim::raster {

namespace {

struct ClipVertex {
  Vec3 eye{0.0};
  RasterVertex v{};
};

ClipVertex lerp(const ClipVertex& a, const ClipVertex& b, double t) {
  ClipVertex c;
  c.eye = a.eye + t * (b.eye - a.eye);
  c.v.position = a.v.position + t * (b.v.position - a.v.position);
  c.v.normal = a.v.normal + t * (b.v.normal - a.v.normal);
  c.v.uv = a.v.uv + t * (b.v.uv - a.v.uv);
  return c;
}

/// Sutherland-Hodgman against one plane: keeps the vertices where distance(v) >= 0.
template <class Distance>
void clip(std::vector<ClipVertex>& poly, std::vector<ClipVertex>& scratch, Distance distance) {
  scratch.clear();
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const ClipVertex& a = poly[i];
    const ClipVertex& b = poly[(i + 1) % n];
    const double da = distance(a), db = distance(b);
    if (da >= 0.0) scratch.push_back(a);
    if ((da >= 0.0) != (db >= 0.0)) scratch.push_back(lerp(a, b, da / (da - db)));
  }
  poly.swap(scratch);
}

std::int64_t snap(double pixels) {
  return static_cast<std::int64_t>(std::llround(pixels * kSubpixel));
}

/// The lowest pixel whose samples can lie at or after subpixel position s, and the highest at
/// or before it.
int first_pixel(std::int64_t s) {
  return static_cast<int>(std::floor(static_cast<double>(s - (kSubpixel - 1)) / kSubpixel));
}
int last_pixel(std::int64_t s) { return static_cast<int>(std::floor(double(s) / kSubpixel)); }

}  // namespace

ViewSetup set_up_view(const RasterMesh& mesh, const ViewTransform& view,
                      const std::vector<MaterialWord>& materials, const std::vector<bool>& include,
                      const std::optional<ClipPlane>& plane) {
  ViewSetup out;
  out.triangles.reserve(mesh.triangles.size());
  std::vector<ClipVertex> poly, scratch;
  const double guard = kGuardBandPixels * view.pixel;
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const RasterTriangle& tri = mesh.triangles[t];
    if (!include.empty() && (tri.material >= include.size() || !include[tri.material])) continue;
    const double facing = glm::dot(tri.face_normal, view.origin - tri.v[0].position);
    if (tri.one_sided && !(facing > 0.0)) continue;  // a closed surface's back face
    poly.clear();
    for (const auto& v : tri.v) poly.push_back({view.to_eye(v.position), v});
    clip(poly, scratch, [&](const ClipVertex& c) { return c.eye.z - view.near; });
    if (!poly.empty())
      clip(poly, scratch, [&](const ClipVertex& c) { return guard * c.eye.z - c.eye.x; });
    if (!poly.empty())
      clip(poly, scratch, [&](const ClipVertex& c) { return guard * c.eye.z + c.eye.x; });
    if (!poly.empty())
      clip(poly, scratch, [&](const ClipVertex& c) { return guard * c.eye.z - c.eye.y; });
    if (!poly.empty())
      clip(poly, scratch, [&](const ClipVertex& c) { return guard * c.eye.z + c.eye.y; });
    if (plane && !poly.empty())
      clip(poly, scratch, [&](const ClipVertex& c) {
        return glm::dot(plane->normal, c.v.position - plane->point);
      });
    if (poly.size() < 3) continue;  // wholly outside the depth range or the guard band
    ++out.front_facing;
    const MaterialWord word =
        tri.material < materials.size() ? materials[tri.material] : MaterialWord{};
    for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
      ScreenTriangle s;
      const std::array<const ClipVertex*, 3> c = {&poly[0], &poly[k], &poly[k + 1]};
      std::int64_t x_lo = INT64_MAX, x_hi = INT64_MIN, y_lo = INT64_MAX, y_hi = INT64_MIN;
      for (int i = 0; i < 3; ++i) {
        s.x[i] = snap(view.screen_x(c[i]->eye));
        s.y[i] = snap(view.screen_y(c[i]->eye));
        s.inv_z[i] = 1.0 / c[i]->eye.z;
        s.attr[i] = c[i]->v;
        x_lo = std::min(x_lo, s.x[i]);
        x_hi = std::max(x_hi, s.x[i]);
        y_lo = std::min(y_lo, s.y[i]);
        y_hi = std::max(y_hi, s.y[i]);
      }
      s.x_min = std::max(0, first_pixel(x_lo));
      s.x_max = std::min(view.width - 1, last_pixel(x_hi));
      s.y_min = std::max(0, first_pixel(y_lo));
      s.y_max = std::min(view.height - 1, last_pixel(y_hi));
      if (s.x_min > s.x_max || s.y_min > s.y_max) continue;
      s.triangle = t;
      s.material = word;
      s.flip = !tri.one_sided && facing < 0.0;
      out.triangles.push_back(s);
    }
  }
  return out;
}

}  // namespace rtsim::raster
