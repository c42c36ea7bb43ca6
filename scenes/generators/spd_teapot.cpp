#include "scenes/generators/spd_teapot.hpp"

#include <cmath>

#include "scenes/generators/newell_teapot.hpp"

namespace rtsim::scenes {

namespace {

/// Bernstein weights of a cubic at t, and of its derivative.
void bernstein(double t, double b[4], double d[4]) {
  const double s = 1.0 - t;
  b[0] = s * s * s;
  b[1] = 3 * t * s * s;
  b[2] = 3 * t * t * s;
  b[3] = t * t * t;
  d[0] = -3 * s * s;
  d[1] = 3 * s * s - 6 * t * s;
  d[2] = 6 * t * s - 3 * t * t;
  d[3] = 3 * t * t;
}

struct SurfacePoint {
  Vec3 p, n;
};

/// The patch's point at (u, v) and its normal. At a pole (a row of the net collapsed to a point)
/// the derivatives vanish; the normal is then taken a little way inside the patch.
SurfacePoint evaluate(const BezierPatch& patch, double u, double v) {
  SurfacePoint out;
  for (double inset = 0.0; inset <= 0.01; inset += 0.001) {
    const double uu = std::clamp(u, inset, 1.0 - inset), vv = std::clamp(v, inset, 1.0 - inset);
    double bu[4], du[4], bv[4], dv[4];
    bernstein(uu, bu, du);
    bernstein(vv, bv, dv);
    Vec3 p{0.0}, pu{0.0}, pv{0.0};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        const Vec3& c = patch.at(i, j);  // row i: v, column j: u
        p += c * (bv[i] * bu[j]);
        pu += c * (bv[i] * du[j]);
        pv += c * (dv[i] * bu[j]);
      }
    if (inset == 0.0) out.p = p;
    const Vec3 n = glm::cross(pu, pv);
    if (glm::length(n) > 1e-9) {
      out.n = glm::normalize(n);
      return out;
    }
  }
  out.n = Vec3(0.0, 0.0, 1.0);
  return out;
}

void add_polygon(Scene& s, std::vector<Vec3> vertices, std::vector<Vec3> normals,
                 std::uint32_t material) {
  s.primitives.push_back(
      {PrimitiveKind::Polygon, static_cast<std::uint32_t>(s.polygons.size()), material, 0});
  s.polygons.push_back({std::move(vertices), std::move(normals), {}});
}

/// SPD's teapot scene without its teapot: the view, lights, background, materials (the teapot's
/// is 2) and the checkerboard.
Scene spd_teapot_setting(const char* name) {
  Scene s;
  s.name = name;
  // SPD teapot's view, lights and background (teapot-s2.nff lines 1-10).
  s.has_camera = true;
  s.camera.from = Vec3(4.86, 7.2, 5.4);
  s.camera.at = Vec3(0.0);
  s.camera.up = Vec3(0.0, 0.0, 1.0);
  s.camera.angle_deg = 45.0;
  s.camera.hither = 1.0;
  s.camera.width = 512;
  s.camera.height = 512;
  s.background = Color(0.078, 0.361, 0.753);
  s.lights.push_back({Vec3(-3.1, 9.8, 12.1), Color(1.0)});
  s.lights.push_back({Vec3(11.3, 5.1, 8.8), Color(1.0)});
  // The checkerboard: two white and two grey squares of side 4 (lines 11-32).
  s.materials.push_back({Color(1.0), 0.5, 0.5, 4.81884, 0.0, 0.0});
  s.materials.push_back({Color(0.5), 0.5, 0.5, 4.81884, 0.0, 0.0});
  s.materials.push_back({Color(1.0, 0.5, 0.1), 0.75, 0.25, 3.0827, 0.0, 0.0});
  const auto square = [&](double x, double y, std::uint32_t m) {
    add_polygon(s, {Vec3(x, y, 0), Vec3(x + 4, y, 0), Vec3(x + 4, y + 4, 0), Vec3(x, y + 4, 0)}, {},
                m);
  };
  square(-4, 0, 0);
  square(0, -4, 0);
  square(-4, -4, 1);
  square(0, 0, 1);
  return s;
}

}  // namespace

Scene make_spd_teapot(int steps) {
  const Scene patches = make_newell_teapot();
  Scene s = spd_teapot_setting("builtin:spd-teapot");
  // The teapot: each patch on a steps x steps grid, two triangles a cell.
  for (const BezierPatch& patch : patches.patches) {
    std::vector<SurfacePoint> grid;
    for (int b = 0; b <= steps; ++b)
      for (int a = 0; a <= steps; ++a)
        grid.push_back(
            evaluate(patch, static_cast<double>(a) / steps, static_cast<double>(b) / steps));
    const auto at = [&](int a, int b) -> const SurfacePoint& {
      return grid[static_cast<std::size_t>(b * (steps + 1) + a)];
    };
    for (int b = 0; b < steps; ++b)
      for (int a = 0; a < steps; ++a) {
        const SurfacePoint* tri[2][3] = {{&at(a, b), &at(a + 1, b), &at(a + 1, b + 1)},
                                         {&at(a + 1, b + 1), &at(a, b + 1), &at(a, b)}};
        for (const auto& t : tri) {
          const Vec3 area = glm::cross(t[1]->p - t[0]->p, t[2]->p - t[0]->p);
          if (glm::length(area) < 1e-12) continue;  // a pole: two corners coincide
          add_polygon(s, {t[0]->p, t[1]->p, t[2]->p}, {t[0]->n, t[1]->n, t[2]->n}, 2);
        }
      }
  }
  return s;
}

Scene make_spd_teapot_patches() {
  const Scene teapot = make_newell_teapot();
  Scene s = spd_teapot_setting("builtin:spd-teapot-patches");
  for (const BezierPatch& patch : teapot.patches) {
    s.primitives.push_back(
        {PrimitiveKind::Patch, static_cast<std::uint32_t>(s.patches.size()), 2, 0});
    s.patches.push_back(patch);
  }
  return s;
}

}  // namespace rtsim::scenes
