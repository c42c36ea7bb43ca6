// Stress tests for the intersection kernels: watertightness of triangulated polygons and of a
// closed mesh (rays exactly through shared edges and vertices), grazing and edge-on rays, scenes
// scaled by 1e-6 and 1e6, a sphere seen from 1e6 away, and float-vs-double triangle agreement.
// Every reported hit, anywhere, must be finite with unit normals.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "firmware/geometry/triangulate.hpp"
#include "firmware/kernels/cone.hpp"
#include "firmware/kernels/sphere.hpp"
#include "firmware/kernels/triangle.hpp"
#include "tests/kernel_test_support.hpp"

namespace rtsim::kernels {
namespace {

using testing::hit_is_sane;
using testing::RandomGeometry;
using LV = glm::vec<3, long double, glm::defaultp>;
using Tri = std::array<std::uint32_t, 3>;

// ---------------------------------------------------------------------------------------------
// A triangle mesh and the claims a ray gets from it.

template <typename Kernel>
struct Mesh {
  std::vector<Vec3> verts;  // as stored by the kernels (rounded to the kernel's precision)
  std::vector<Tri> tris;
  std::vector<Kernel> kernels;

  Mesh(const std::vector<Vec3>& v, const std::vector<Tri>& t) : tris(t) {
    using T = typename Kernel::Scalar;
    for (const Vec3& p : v) verts.push_back(Vec3(Vec3T<T>(p)));
    for (const Tri& k : tris) {
      auto kern = Kernel::from(verts[k[0]], verts[k[1]], verts[k[2]], nullptr);
      EXPECT_TRUE(kern);
      if (kern) kernels.push_back(*kern);
    }
  }

  /// Unique edges (a < b) with the number of triangles using them.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges() const {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> e;
    for (const Tri& t : tris) {
      for (int i = 0; i < 3; ++i) {
        std::uint32_t a = t[static_cast<std::size_t>(i)],
                      b = t[static_cast<std::size_t>((i + 1) % 3)];
        if (a > b) std::swap(a, b);
        ++e[{a, b}];
      }
    }
    return e;
  }
};

struct ClaimStats {
  long rays = 0, cracks = 0, multiple = 0, insane = 0, t_off = 0;
  double max_t_err = 0;
  void add(const ClaimStats& o) {
    rays += o.rays;
    cracks += o.cracks;
    multiple += o.multiple;
    insane += o.insane;
    t_off += o.t_off;
    max_t_err = std::fmax(max_t_err, o.max_t_err);
  }
  void print(const char* what) const {
    std::printf(
        "%-44s rays %7ld  cracks %ld  multiple claims %ld  bad t %ld (max rel t err %.2g)\n", what,
        rays, cracks, multiple, t_off, max_t_err);
  }
};

/// Casts `ray` at every triangle; records a crack (no claim), multiple claims, and whether the
/// nearest claim is at the expected distance (the ray was aimed at a point of the mesh; NaN for
/// a ray with no known distance).
template <typename Kernel>
void cast(const Mesh<Kernel>& mesh, const Ray& ray, double expected_t, double t_tol,
          ClaimStats& s) {
  int claims = 0;
  double nearest = kInfinity;
  for (const Kernel& k : mesh.kernels) {
    SurfaceHit h;
    if (k.intersect(ray, 0.0, kInfinity, h)) {
      ++claims;
      if (!hit_is_sane(h)) ++s.insane;
      nearest = std::fmin(nearest, h.t);
    }
  }
  ++s.rays;
  if (claims == 0) ++s.cracks;
  if (claims > 1) ++s.multiple;
  if (claims > 0 && !std::isnan(expected_t)) {
    const double err = std::fabs(nearest - expected_t) / expected_t;
    s.max_t_err = std::fmax(s.max_t_err, err);
    if (err > t_tol) ++s.t_off;
  }
}

// ---------------------------------------------------------------------------------------------
// Shapes.

std::vector<std::pair<double, double>> star2d(int points, double inner) {
  std::vector<std::pair<double, double>> s;
  for (int i = 0; i < 2 * points; ++i) {
    const double a = kPi * i / points;
    const double r = (i % 2 == 0) ? 1.0 : inner;
    s.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return s;
}

std::vector<std::pair<double, double>> comb2d(int teeth, double height) {
  std::vector<std::pair<double, double>> s{{0, 0}, {2.0 * teeth - 1, 0}};
  for (int i = teeth - 1; i >= 0; --i) {
    s.emplace_back(2.0 * i + 1, height);
    s.emplace_back(2.0 * i, height);
    if (i > 0) {
      s.emplace_back(2.0 * i, 1);
      s.emplace_back(2.0 * i - 1, 1);
    }
  }
  return s;
}

/// A rotation (orthonormal rows) from a seed; identity for seed 0.
struct Frame {
  Vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  Vec3 offset{0.0};
  Vec3 operator()(const Vec3& p) const { return offset + p.x * x + p.y * y + p.z * z; }
};

Frame random_frame(RandomGeometry& g, double offset) {
  Frame f;
  f.z = g.unit();
  f.x = glm::normalize(glm::cross(f.z, g.unit()));
  f.y = glm::cross(f.z, f.x);
  f.offset = offset * g.unit();
  return f;
}

// ---------------------------------------------------------------------------------------------
// 1. One triangulated polygon: rays exactly through its interior (shared) edges.

template <typename Kernel>
ClaimStats polygon_shared_edges(const std::vector<std::pair<double, double>>& shape,
                                const Frame& frame, bool axis_rays, RandomGeometry& g) {
  std::vector<Vec3> v;
  for (auto [x, y] : shape) v.push_back(frame(Vec3(x, y, 0)));
  const auto tr = geometry::triangulate_polygon(v);
  EXPECT_TRUE(tr.ok() && tr.warnings.empty());
  const Mesh<Kernel> mesh(v, tr.triangles);
  ClaimStats s;
  const double t_tol = std::is_same_v<typename Kernel::Scalar, float> ? 1e-4 : 1e-9;
  for (const auto& [e, count] : mesh.edges()) {
    if (count != 2) continue;  // boundary edge: a ray through it may rightly miss
    const Vec3 a = mesh.verts[e.first], b = mesh.verts[e.second];
    for (int k = 1; k < 64 + 16; ++k) {
      // Dyadic fractions (exact in binary) and random fractions along the edge.
      const double f = (k < 64) ? k / 64.0 : g.uniform(0.001, 0.999);
      const Vec3 p = a + f * (b - a);
      if (axis_rays) {
        // The polygon lies in z = 0 with integer corners: axis rays give exactly zero edge
        // functions, so the tie rule alone decides.
        for (double dz : {-1.0, 1.0}) {
          const Ray ray{p - 3.0 * dz * frame.z, dz * frame.z};
          cast(mesh, ray, 3.0, t_tol, s);
        }
      } else {
        for (int o = 0; o < 4; ++o) {
          // At least ~11 degrees off the plane: the t tolerance below is for the distance, and
          // a grazing ray's distance error grows as 1/sin(angle) (tested separately).
          Vec3 u = g.unit();
          while (std::fabs(glm::dot(u, frame.z)) < 0.2) u = g.unit();
          const Vec3 origin = p + g.uniform(1, 4) * u;
          cast(mesh, RandomGeometry::through(origin, p), glm::length(p - origin), t_tol, s);
        }
      }
    }
  }
  return s;
}

TEST(KernelStress, TriangulatedPolygonHasNoCracksAtSharedEdges) {
  RandomGeometry g(51);
  struct Shape {
    const char* name;
    std::vector<std::pair<double, double>> pts;
  };
  const Shape shapes[] = {
      {"12-star", star2d(12, 0.3)}, {"comb", comb2d(10, 4.0)}, {"64-gon", star2d(32, 1.0)}};
  ClaimStats total_d, total_f;
  for (const Shape& sh : shapes) {
    const Frame f = random_frame(g, 2.0);
    const auto d = polygon_shared_edges<TriangleKernel>(sh.pts, f, false, g);
    const auto fl = polygon_shared_edges<TriangleKernelFloat>(sh.pts, f, false, g);
    d.print((std::string(sh.name) + " double, oblique rays").c_str());
    fl.print((std::string(sh.name) + " float, oblique rays").c_str());
    total_d.add(d);
    total_f.add(fl);
  }
  // Exact ties: comb in the z = 0 plane, integer corners, rays along z.
  const auto ed = polygon_shared_edges<TriangleKernel>(comb2d(10, 4.0), Frame{}, true, g);
  const auto ef = polygon_shared_edges<TriangleKernelFloat>(comb2d(10, 4.0), Frame{}, true, g);
  ed.print("comb z=0 double, axis rays (exact ties)");
  ef.print("comb z=0 float, axis rays (exact ties)");
  for (const ClaimStats* s : {&std::as_const(total_d), &std::as_const(total_f), &ed, &ef}) {
    EXPECT_GT(s->rays, 1000);
    EXPECT_EQ(s->cracks, 0);
    EXPECT_EQ(s->multiple, 0);  // the tie rule: exactly one triangle per ray
    EXPECT_EQ(s->insane, 0);
    EXPECT_EQ(s->t_off, 0);
  }
}

/// A fan of triangles around an interior vertex (a 12-gon with its centre), rays exactly through
/// the centre vertex and through points of the spokes, from random origins on both sides (and
/// along the normal when `axis_rays`: then the centre's ray-space coordinates are exactly 0 and
/// two edge functions of every fan triangle vanish at once).
template <typename Kernel>
ClaimStats fan_vertex_rays(const Frame& frame, bool axis_rays, RandomGeometry& g) {
  std::vector<Vec3> v{frame(Vec3(0, 0, 0))};
  std::vector<Tri> tris;
  const std::uint32_t n = 12;
  for (std::uint32_t i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n + 0.1;
    v.push_back(frame(Vec3(std::cos(a), std::sin(a), 0)));
    tris.push_back({0, 1 + i, 1 + (i + 1) % n});
  }
  const Mesh<Kernel> mesh(v, tris);
  ClaimStats s;
  const double t_tol = std::is_same_v<typename Kernel::Scalar, float> ? 1e-4 : 1e-9;
  std::vector<Vec3> targets{mesh.verts[0]};
  for (std::uint32_t i = 1; i <= n; ++i) {
    for (int k = 1; k < 16; ++k)
      targets.push_back(mesh.verts[0] + (k / 16.0) * (mesh.verts[i] - mesh.verts[0]));
  }
  for (const Vec3& p : targets) {
    if (axis_rays) {
      for (double dz : {-1.0, 1.0})
        cast(mesh, Ray{p - 3.0 * dz * frame.z, dz * frame.z}, 3.0, t_tol, s);
      continue;
    }
    for (int o = 0; o < 40; ++o) {
      Vec3 u = g.unit();
      while (std::fabs(glm::dot(u, frame.z)) < 0.2) u = g.unit();
      const Vec3 origin = p + g.uniform(1, 4) * u;
      cast(mesh, RandomGeometry::through(origin, p), glm::length(p - origin), t_tol, s);
    }
  }
  return s;
}

TEST(KernelStress, FanHasNoCracksAtItsInteriorVertex) {
  RandomGeometry g(58);
  const Frame f = random_frame(g, 2.0);
  const auto d = fan_vertex_rays<TriangleKernel>(f, false, g);
  const auto fl = fan_vertex_rays<TriangleKernelFloat>(f, false, g);
  const auto ed = fan_vertex_rays<TriangleKernel>(Frame{}, true, g);
  const auto ef = fan_vertex_rays<TriangleKernelFloat>(Frame{}, true, g);
  d.print("fan double, oblique rays (vertex + spokes)");
  fl.print("fan float, oblique rays (vertex + spokes)");
  ed.print("fan z=0 double, axis rays (exact ties)");
  ef.print("fan z=0 float, axis rays (exact ties)");
  for (const ClaimStats* s : {&d, &fl, &ed, &ef}) {
    EXPECT_EQ(s->cracks, 0);
    EXPECT_EQ(s->multiple, 0);
    EXPECT_EQ(s->insane, 0);
    EXPECT_EQ(s->t_off, 0);
  }
}

// ---------------------------------------------------------------------------------------------
// 2. A closed mesh: a star prism (top cap by the triangulator, bottom cap a fan around a centre
//    vertex, sides two triangles per quad). Seen from points near its axis it is star-shaped,
//    so every ray from there crosses the surface exactly once -- including rays exactly through
//    every vertex and along every edge.

struct Prism {
  std::vector<Vec3> verts;
  std::vector<Tri> tris;
};

Prism star_prism(int points, double inner) {
  Prism p;
  const auto shape = star2d(points, inner);
  const auto n = static_cast<std::uint32_t>(shape.size());
  for (auto [x, y] : shape) p.verts.emplace_back(x, y, 1.0);   // top: 0..n-1
  for (auto [x, y] : shape) p.verts.emplace_back(x, y, -1.0);  // bottom: n..2n-1
  p.verts.emplace_back(0.0, 0.0, -1.0);                        // bottom centre: 2n
  const std::vector<Vec3> top(p.verts.begin(), p.verts.begin() + n);
  const auto tr = geometry::triangulate_polygon(top);
  EXPECT_TRUE(tr.ok());
  p.tris = tr.triangles;
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    p.tris.push_back({2 * n, n + j, n + i});
    p.tris.push_back({n + i, n + j, j});
    p.tris.push_back({n + i, j, i});
  }
  return p;
}

template <typename Kernel>
ClaimStats closed_mesh_rays(const Prism& prism, const Frame& frame, double scale,
                            RandomGeometry& g) {
  std::vector<Vec3> v;
  for (const Vec3& p : prism.verts) v.push_back(scale * frame(p));
  const Mesh<Kernel> mesh(v, prism.tris);
  ClaimStats s;
  const double t_tol = std::is_same_v<typename Kernel::Scalar, float> ? 1e-4 : 1e-9;
  std::vector<Vec3> origins;
  for (int i = 0; i < 3; ++i) {
    origins.push_back(
        scale * frame(Vec3(g.uniform(-0.05, 0.05), g.uniform(-0.05, 0.05), g.uniform(-0.5, 0.5))));
  }
  auto shoot = [&](const Vec3& target) {
    for (const Vec3& o : origins) {
      cast(mesh, RandomGeometry::through(o, target), glm::length(target - o), t_tol, s);
    }
  };
  for (const Vec3& p : mesh.verts) shoot(p);  // every vertex
  for (const auto& [e, count] : mesh.edges()) {
    EXPECT_EQ(count, 2);  // closed: every edge shared by exactly two triangles
    const Vec3 a = mesh.verts[e.first], b = mesh.verts[e.second];
    for (int k = 1; k < 32; ++k) shoot(a + (k / 32.0) * (b - a));
    for (int k = 0; k < 4; ++k) shoot(a + g.uniform(0, 1) * (b - a));
  }
  // And plenty of rays in random directions.
  for (int k = 0; k < 300; ++k) {
    for (const Vec3& o : origins) cast(mesh, Ray{o, g.unit()}, std::nan(""), 0.0, s);
  }
  return s;
}

TEST(KernelStress, ClosedMeshHasNoCracksThroughVerticesAndEdges) {
  RandomGeometry g(52);
  const Prism prism = star_prism(9, 0.45);
  for (double scale : {1.0, 1e-6, 1e6}) {
    for (int orient = 0; orient < 2; ++orient) {
      const Frame f = orient == 0 ? Frame{} : random_frame(g, 0.0);
      char label[96];
      std::snprintf(label, sizeof label, "prism %s, scale %g, double",
                    orient == 0 ? "axis-aligned" : "rotated", scale);
      const auto d = closed_mesh_rays<TriangleKernel>(prism, f, scale, g);
      d.print(label);
      std::snprintf(label, sizeof label, "prism %s, scale %g, float",
                    orient == 0 ? "axis-aligned" : "rotated", scale);
      const auto fl = closed_mesh_rays<TriangleKernelFloat>(prism, f, scale, g);
      fl.print(label);
      for (const ClaimStats* s : {&d, &fl}) {
        EXPECT_EQ(s->cracks, 0) << label;
        EXPECT_EQ(s->multiple, 0) << label;
        EXPECT_EQ(s->insane, 0) << label;
        EXPECT_EQ(s->t_off, 0) << label;
      }
    }
  }
}

/// Control: the textbook Moller-Trumbore test (not watertight: each triangle rounds its own
/// barycentrics). It must show cracks on the same rays, or the rays above would prove nothing.
template <typename T>
class MollerTrumbore {
 public:
  using Scalar = T;
  static std::optional<MollerTrumbore> from(const Vec3& a, const Vec3& b, const Vec3& c,
                                            const Vec3*) {
    MollerTrumbore m;
    m.p0_ = Vec3T<T>(a);
    m.e1_ = Vec3T<T>(b) - m.p0_;
    m.e2_ = Vec3T<T>(c) - m.p0_;
    return m;
  }
  bool intersect(const Ray& r, double t_min, double t_max, SurfaceHit& h) const {
    const Vec3T<T> d(r.direction);
    const Vec3T<T> pv = glm::cross(d, e2_);
    const T det = glm::dot(e1_, pv);
    if (det == T(0)) return false;
    const T inv = T(1) / det;
    const Vec3T<T> tv = Vec3T<T>(r.origin) - p0_;
    const T u = glm::dot(tv, pv) * inv;
    if (u < T(0) || u > T(1)) return false;
    const Vec3T<T> qv = glm::cross(tv, e1_);
    const T v = glm::dot(d, qv) * inv;
    if (v < T(0) || u + v > T(1)) return false;
    const double t = double(glm::dot(e2_, qv) * inv);
    if (!(t > t_min && t < t_max)) return false;
    h.t = t;
    h.u = double(u);
    h.v = double(v);
    h.geometric_normal = h.shading_normal = glm::normalize(Vec3(glm::cross(e1_, e2_)));
    return true;
  }

 private:
  Vec3T<T> p0_, e1_, e2_;
};

TEST(KernelStress, ControlNonWatertightKernelDoesCrack) {
  RandomGeometry g(57);
  const Prism prism = star_prism(9, 0.45);
  const auto d = closed_mesh_rays<MollerTrumbore<double>>(prism, random_frame(g, 0.0), 1.0, g);
  const auto f = closed_mesh_rays<MollerTrumbore<float>>(prism, random_frame(g, 0.0), 1.0, g);
  d.print("control: Moller-Trumbore double, prism");
  f.print("control: Moller-Trumbore float, prism");
  EXPECT_GT(d.cracks, 0);
  EXPECT_GT(f.cracks, 0);
}

// ---------------------------------------------------------------------------------------------
// 3. Grazing and edge-on rays.

TEST(KernelStress, GrazingAndEdgeOnRays) {
  RandomGeometry g(53);
  int insane = 0, wrong = 0;
  // Triangle: rays through the centroid at shrinking angles to the plane must still hit, at
  // the right distance; rays lying in the plane may hit or miss but must report nothing odd.
  for (int rep = 0; rep < 20; ++rep) {
    const Frame f = random_frame(g, 1.0);
    const Vec3 p0 = f(Vec3(0, 0, 0)), p1 = f(Vec3(1, 0, 0)), p2 = f(Vec3(0, 1, 0));
    const auto tri = TriangleKernel::from(p0, p1, p2, nullptr);
    ASSERT_TRUE(tri);
    const Vec3 c = (p0 + p1 + p2) / 3.0;
    for (int k = 1; k <= 12; ++k) {
      const double theta = std::pow(10.0, -k);
      const Vec3 in_plane = glm::normalize(f.x * std::cos(0.3 * rep) + f.y * std::sin(0.3 * rep));
      const Vec3 dir = glm::normalize(std::cos(theta) * in_plane - std::sin(theta) * f.z);
      const Ray ray{c - 2.0 * dir, dir};
      SurfaceHit h;
      if (!tri->intersect(ray, 0.0, kInfinity, h)) {
        ++wrong;
        continue;
      }
      if (!hit_is_sane(h)) ++insane;
      // Position error along the plane ~ ulp / theta: allow 1e-13 / theta.
      if (std::fabs(h.t - 2.0) > 1e-13 / theta + 1e-12) ++wrong;
    }
    for (int k = 0; k < 20; ++k) {  // edge-on
      const Vec3 dir = glm::normalize(f.x * g.uniform(-1, 1) + f.y * g.uniform(-1, 1));
      SurfaceHit h;
      if (tri->intersect(Ray{c - 2.0 * dir, dir}, 0.0, kInfinity, h) && !hit_is_sane(h)) ++insane;
    }
  }
  // Sphere: rays passing the centre at r (1 -+ eps) hit / miss, from 10 away.
  const auto sph = SphereKernel::from({Vec3(0.3, -0.2, 0.1), 0.7});
  ASSERT_TRUE(sph);
  for (int k = 2; k <= 13; ++k) {
    const double eps = std::pow(10.0, -k);
    for (int rep = 0; rep < 10; ++rep) {
      const Vec3 d = g.unit();
      const Vec3 side = glm::normalize(glm::cross(d, g.unit()));
      for (double sign : {-1.0, 1.0}) {
        const Vec3 pass = sph->center() + (0.7 * (1 + sign * eps)) * side;
        SurfaceHit h;
        const bool hit = sph->intersect(Ray{pass - 10.0 * d, d}, 0.0, kInfinity, h);
        if (hit != (sign < 0)) ++wrong;
        if (hit && !hit_is_sane(h)) ++insane;
      }
    }
  }
  // Cylinder and 45-degree cone: rays perpendicular to the axis passing at rho (1 -+ eps).
  const auto cyl = ConeKernel::from({Vec3(0, 0, 0), 1.0, Vec3(0, 0, 2), 1.0});
  const auto cone = ConeKernel::from({Vec3(0, 0, 0), 1.0, Vec3(0, 0, 1), 0.0});
  ASSERT_TRUE(cyl && cone);
  for (int k = 2; k <= 13; ++k) {
    const double eps = std::pow(10.0, -k);
    for (double sign : {-1.0, 1.0}) {
      SurfaceHit h;
      const bool hc =
          cyl->intersect(Ray{Vec3(-5, 1 + sign * eps, 1), Vec3(1, 0, 0)}, 0.0, kInfinity, h);
      if (hc != (sign < 0)) ++wrong;
      if (hc && !hit_is_sane(h)) ++insane;
      const bool hk = cone->intersect(Ray{Vec3(-5, 0.5 * (1 + sign * eps), 0.5), Vec3(1, 0, 0)},
                                      0.0, kInfinity, h);
      if (hk != (sign < 0)) ++wrong;
      if (hk && !hit_is_sane(h)) ++insane;
    }
  }
  std::printf("grazing/edge-on: wrong answers %d, non-finite hits %d (both expected 0)\n", wrong,
              insane);
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(insane, 0);
}

// ---------------------------------------------------------------------------------------------
// 4. Scale invariance: the same random scene at 1, 1e-6 and 1e6. Hit/miss must agree and
//    t must scale (relative 1e-9; the scales are not powers of two, so rounding differs).

struct ScaleStats {
  long rays = 0, hits = 0, disagree = 0, insane = 0;
  double max_t_err = 0;
};

template <typename Make>
ScaleStats scale_check(double scale, Make make, RandomGeometry& g) {
  ScaleStats s;
  for (int i = 0; i < 300; ++i) {
    const auto [unit, scaled, target] = make(scale, g);
    if (!unit || !scaled) continue;
    for (int j = 0; j < 100; ++j) {
      const Vec3 origin = g.in_box(5);
      const Ray r1 = RandomGeometry::through(origin, target + g.uniform(0, 1.2) * g.unit());
      const Ray rs{scale * r1.origin, r1.direction};
      SurfaceHit h1, hs;
      const bool a = unit->intersect(r1, 0.0, kInfinity, h1);
      const bool b = scaled->intersect(rs, 0.0, kInfinity, hs);
      ++s.rays;
      if ((a && !hit_is_sane(h1)) || (b && !hit_is_sane(hs))) ++s.insane;
      if (a != b) {
        ++s.disagree;
        continue;
      }
      if (!a) continue;
      ++s.hits;
      s.max_t_err = std::fmax(s.max_t_err, std::fabs(hs.t / scale - h1.t) / h1.t);
    }
  }
  return s;
}

TEST(KernelStress, ScaledScenesGiveScaledHits) {
  RandomGeometry g(54);
  auto tri = [](double s, RandomGeometry& r) {
    const Vec3 a = r.in_box(1), b = r.in_box(1), c = r.in_box(1);
    return std::tuple{TriangleKernel::from(a, b, c, nullptr),
                      TriangleKernel::from(s * a, s * b, s * c, nullptr), (a + b + c) / 3.0};
  };
  auto sph = [](double s, RandomGeometry& r) {
    const scenes::Sphere x{r.in_box(1), r.uniform(0.1, 1)};
    return std::tuple{SphereKernel::from(x), SphereKernel::from({s * x.center, s * x.radius}),
                      x.center};
  };
  auto cone = [](double s, RandomGeometry& r) {
    scenes::Cone c{r.in_box(1), r.uniform(0, 1), Vec3(0), r.uniform(0, 1)};
    c.apex = c.base + r.uniform(0.3, 2) * r.unit();
    const scenes::Cone cs{s * c.base, s * c.base_radius, s * c.apex, s * c.apex_radius};
    return std::tuple{ConeKernel::from(c), ConeKernel::from(cs), 0.5 * (c.base + c.apex)};
  };
  for (double scale : {1e-6, 1e6}) {
    const ScaleStats st = scale_check(scale, tri, g);
    const ScaleStats ss = scale_check(scale, sph, g);
    const ScaleStats sc = scale_check(scale, cone, g);
    for (const auto& [name, s] : {std::pair{"triangle", st}, {"sphere", ss}, {"cone", sc}}) {
      std::printf(
          "scale %-6g %-8s rays %ld hits %ld hit/miss disagreements %ld, max rel t err %.2g "
          "(tolerance 1e-9)\n",
          scale, name, s.rays, s.hits, s.disagree, s.max_t_err);
      EXPECT_GT(s.hits, s.rays / 10) << name;
      EXPECT_EQ(s.disagree, 0) << name;
      EXPECT_EQ(s.insane, 0) << name;
      EXPECT_LT(s.max_t_err, 1e-9) << name;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// 5. A sphere seen from 1e6 away. Reference: long double, with the origin first moved along the
//    ray to the point nearest the centre (so the quadratic is well conditioned). The naive
//    double formula (b^2 - c) is evaluated alongside to show what the geometric form avoids.

TEST(KernelStress, SphereFromFarAway) {
  RandomGeometry g(55);
  long rays = 0, clear = 0, disagree = 0, insane = 0, hits = 0, naive_wrong = 0;
  double max_dt = 0, max_n = 0, max_residual = 0, naive_max_dt = 0;
  for (int i = 0; i < 200; ++i) {
    const scenes::Sphere sp{g.in_box(3), g.uniform(0.2, 2)};
    const auto k = SphereKernel::from(sp);
    ASSERT_TRUE(k);
    for (int j = 0; j < 50; ++j) {
      const Vec3 origin = sp.center + 1e6 * g.unit();
      const Ray ray = RandomGeometry::through(origin, sp.center + 1.1 * sp.radius * g.unit());
      // Reference.
      const LV o(ray.origin), d(ray.direction), c(sp.center);
      const long double t_near = glm::dot(c - o, d);
      const LV f = o + t_near * d - c;  // centre -> closest point
      const long double r = sp.radius;
      const long double disc = r * r - glm::dot(f, f);
      ++rays;
      SurfaceHit h;
      const bool got = k->intersect(ray, 0.0, kInfinity, h);
      if (got && !hit_is_sane(h)) ++insane;
      // Backward error: the reported point must lie on the sphere to ~100 ulps of 1e6.
      if (got) {
        const LV p = o + (long double)h.t * d;
        max_residual = std::fmax(max_residual, double(std::fabs(glm::length(p - c) - r)));
      }
      if (std::fabs(disc) < 1e-6L * r * r) continue;  // tangent within 1e-6: not clear
      ++clear;
      const bool ref_hit = disc > 0;
      if (got != ref_hit) {
        ++disagree;
        continue;
      }
      // The naive double formula b^2 - c for comparison.
      const Vec3 oc = ray.origin - sp.center;
      const double b = glm::dot(ray.direction, oc);
      const double naive_disc = b * b - (glm::dot(oc, oc) - sp.radius * sp.radius);
      if ((naive_disc >= 0) != ref_hit) ++naive_wrong;
      if (!got) continue;
      ++hits;
      // Forward error. Near tangency the hit point is ill-conditioned (it moves by
      // (input error) / sin(grazing angle)), so the forward check is for rays that are not
      // within 0.1 r of tangent; the residual above covers all of them.
      if (disc < 0.01L * r * r) continue;
      const long double ref_t = t_near - std::sqrt(disc);
      max_dt = std::fmax(max_dt, double(std::fabs(h.t - ref_t)));
      const LV n_ref = (f - std::sqrt(disc) * d) / r;
      max_n = std::fmax(max_n, double(glm::length(LV(h.geometric_normal) - n_ref)));
      if (naive_disc >= 0) {
        naive_max_dt =
            std::fmax(naive_max_dt, double(std::fabs(-b - std::sqrt(naive_disc) - ref_t)));
      }
    }
  }
  std::printf(
      "sphere from 1e6: %ld rays, %ld clear, %ld hits, disagreements %ld; distance of hit points "
      "from the sphere %.3g (tolerance 1e-8 = ~100 ulps of 1e6); not near tangent: max |t - "
      "t_ref| %.3g (tolerance 1e-8), max normal err %.3g (tolerance 1e-8)\n"
      "  naive b^2-c form on the same rays: %ld wrong hit/miss answers, max |t - t_ref| %.3g\n",
      rays, clear, hits, disagree, max_residual, max_dt, max_n, naive_wrong, naive_max_dt);
  EXPECT_GT(hits, clear / 4);
  EXPECT_EQ(disagree, 0);
  EXPECT_EQ(insane, 0);
  EXPECT_LT(max_residual, 1e-8);
  EXPECT_LT(max_dt, 1e-8);
  EXPECT_LT(max_n, 1e-8);
}

// ---------------------------------------------------------------------------------------------
// 6. Float vs double triangle: how often the 32-bit kernel gives the other hit/miss answer.
//    Only rays within float rounding of an edge can differ; with rays spread over the triangle
//    that is ~1e-6 of them near the origin, more for a scene far from the origin (float's
//    absolute precision falls with magnitude).

TEST(KernelStress, FloatVersusDoubleTriangleDisagreement) {
  RandomGeometry g(56);
  for (double offset : {0.0, 100.0}) {
    long rays = 0, disagree = 0, both = 0, insane = 0;
    double max_t = 0;
    for (int i = 0; i < 3000; ++i) {
      const Vec3 centre = offset * Vec3(1, 1, 1);
      const Vec3 a = centre + g.in_box(1), b = centre + g.in_box(1), c = centre + g.in_box(1);
      const auto kd = TriangleKernel::from(a, b, c, nullptr);
      const auto kf = TriangleKernelFloat::from(a, b, c, nullptr);
      if (!kd || !kf) continue;
      for (int j = 0; j < 100; ++j) {
        const Vec3 target = a + g.uniform(-0.3, 1) * (b - a) + g.uniform(-0.3, 1) * (c - a);
        const Ray ray = RandomGeometry::through(centre + g.in_box(4), target);
        SurfaceHit hd, hf;
        const bool d = kd->intersect(ray, 0.0, kInfinity, hd);
        const bool f = kf->intersect(ray, 0.0, kInfinity, hf);
        ++rays;
        if ((d && !hit_is_sane(hd)) || (f && !hit_is_sane(hf))) ++insane;
        if (d != f) ++disagree;
        if (d && f) {
          ++both;
          max_t = std::fmax(max_t, std::fabs(hf.t - hd.t) / hd.t);
        }
      }
    }
    const double rate = double(disagree) / double(rays);
    std::printf(
        "float vs double, scene at %g: %ld rays, %ld hit/miss disagreements (rate %.3g, bound "
        "%g), max rel t difference on common hits %.3g\n",
        offset, rays, disagree, rate, offset == 0 ? 1e-4 : 1e-2, max_t);
    EXPECT_EQ(insane, 0);
    EXPECT_LT(rate, offset == 0 ? 1e-4 : 1e-2);
  }
}

}  // namespace
}  // namespace rtsim::kernels
