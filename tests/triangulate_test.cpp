// Ear-clipping triangulation: shapes are drawn in 2-D, placed in 3-D with a random rotation and
// translation, triangulated, and checked against the 2-D drawing: area (shoelace), orientation,
// containment, and a consistent mesh (interior edges used twice in opposite directions, boundary
// edges once and in the input's order).
#include "firmware/geometry/triangulate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "firmware/geometry/self_crossing.hpp"
#include "tests/kernel_test_support.hpp"

namespace rtsim::geometry {
namespace {

using rtsim::testing::RandomGeometry;

struct V2 {
  double x, y;
};
using Shape = std::vector<V2>;

double shoelace(const Shape& s) {
  double a = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const V2 p = s[i], q = s[(i + 1) % s.size()];
    a += p.x * q.y - p.y * q.x;
  }
  return 0.5 * a;
}

bool strictly_inside(const Shape& s, V2 p) {  // crossing number
  bool in = false;
  for (std::size_t i = 0, j = s.size() - 1; i < s.size(); j = i++) {
    const V2 a = s[i], b = s[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) {
      in = !in;
    }
  }
  return in;
}

struct Placement {
  Vec3 origin, e1, e2, normal;
  double scale = 1;
  Vec3 operator()(V2 p) const { return origin + scale * (p.x * e1 + p.y * e2); }
};

Placement random_placement(RandomGeometry& g, double offset, double scale) {
  Placement pl;
  pl.normal = g.unit();
  pl.e1 = glm::normalize(glm::cross(pl.normal, g.unit()));
  pl.e2 = glm::cross(pl.normal, pl.e1);
  pl.origin = offset * g.unit();
  pl.scale = scale;
  return pl;
}

/// Checks a triangulation of `shape` placed by `pl`; returns the number of failed checks.
void check(const Shape& shape, const Placement& pl, const std::string& name,
           bool expect_warning_free = true, EarChoice choice = EarChoice::Walk) {
  SCOPED_TRACE(name);
  std::vector<Vec3> verts;
  for (V2 p : shape) verts.push_back(pl(p));
  const TriangulationResult r = triangulate_polygon(verts, choice);
  ASSERT_TRUE(r.ok()) << r.reason;
  if (expect_warning_free) {
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    EXPECT_FALSE(r.not_simple);
  }
  const double area2d = shoelace(shape);  // signed: negative for clockwise drawings
  const double scale2 = pl.scale * pl.scale;
  const double expected_area = std::fabs(area2d) * scale2;
  const Vec3 expected_normal = area2d > 0 ? pl.normal : -pl.normal;
  EXPECT_NEAR(glm::dot(r.normal, expected_normal), 1.0, 1e-9);
  EXPECT_NEAR(r.area / expected_area, 1.0, 1e-9);

  // Every triangle: positive area about the polygon normal (not inverted), centroid inside.
  const std::size_t kept = verts.size() - r.removed_duplicates - r.removed_collinear;
  EXPECT_EQ(r.triangles.size(), kept - 2);
  double sum = 0;
  int inverted = 0, outside = 0;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  std::set<std::uint32_t> used;
  for (const auto& t : r.triangles) {
    const Vec3 a = verts[t[0]], b = verts[t[1]], c = verts[t[2]];
    const Vec3 n = glm::cross(b - a, c - a);
    const double area = 0.5 * glm::dot(n, r.normal);
    if (!(area > 0)) ++inverted;
    sum += area;
    const V2 centroid{(shape[t[0]].x + shape[t[1]].x + shape[t[2]].x) / 3,
                      (shape[t[0]].y + shape[t[1]].y + shape[t[2]].y) / 3};
    if (!strictly_inside(shape, centroid)) ++outside;
    for (int e = 0; e < 3; ++e) {
      ++directed[{t[static_cast<std::size_t>(e)], t[static_cast<std::size_t>((e + 1) % 3)]}];
      used.insert(t[static_cast<std::size_t>(e)]);
    }
  }
  EXPECT_EQ(inverted, 0);
  EXPECT_EQ(outside, 0);
  EXPECT_NEAR(sum / expected_area, 1.0, 1e-9) << "sum of triangle areas vs polygon area";
  // Mesh consistency. The next used vertex after i along the input order closes boundary edges.
  auto next_used = [&](std::uint32_t i) {
    for (std::size_t k = 1; k <= verts.size(); ++k) {
      const auto j = static_cast<std::uint32_t>((i + k) % verts.size());
      if (used.count(j)) return j;
    }
    return i;
  };
  int bad_edges = 0;
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    const bool interior = reverse != directed.end();
    if (count != 1) ++bad_edges;                                         // same direction twice
    if (interior && reverse->second != 1) ++bad_edges;                   // shared by >2 triangles
    if (!interior && next_used(edge.first) != edge.second) ++bad_edges;  // boundary, in order
  }
  EXPECT_EQ(bad_edges, 0);
  std::printf(
      "%-22s %5zu vertices -> %5zu triangles, area %.12g (expected %.12g), removed %zu+%zu\n",
      name.c_str(), verts.size(), r.triangles.size(), sum, expected_area, r.removed_duplicates,
      r.removed_collinear);
}

Shape reversed(Shape s) {
  std::reverse(s.begin(), s.end());
  return s;
}

Shape star(int points, double inner) {
  Shape s;
  for (int i = 0; i < 2 * points; ++i) {
    const double a = kPi * i / points;
    const double r = (i % 2 == 0) ? 1.0 : inner;
    s.push_back({r * std::cos(a), r * std::sin(a)});
  }
  return s;
}

Shape circle(int n) {
  Shape s;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n;
    s.push_back({std::cos(a), std::sin(a)});
  }
  return s;
}

Shape comb(int teeth, double height) {
  Shape s{{0, 0}, {2.0 * teeth - 1, 0}};
  for (int i = teeth - 1; i >= 0; --i) {
    s.push_back({2.0 * i + 1, height});
    s.push_back({2.0 * i, height});
    if (i > 0) {
      s.push_back({2.0 * i, 1});
      s.push_back({2.0 * i - 1, 1});
    }
  }
  return s;
}

const Shape kSquare{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
const Shape kL{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
const Shape kU{{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};

TEST(Triangulate, ConvexAndConcaveShapes) {
  RandomGeometry g(41);
  const Placement pl = random_placement(g, 3.0, 1.0);
  check(kSquare, pl, "square");
  check(circle(6), pl, "hexagon");
  check(kL, pl, "L");
  check(kU, pl, "U");
  check(star(5, 0.38), pl, "5-point star");
  check(star(12, 0.2), pl, "12-point star");
  check(comb(8, 5.0), pl, "comb 8 teeth");
  check(comb(40, 20.0), pl, "comb 40 teeth");
  // A spiral-ish concave polygon: a thick "C" made of many vertices.
  Shape c;
  for (int i = 0; i <= 60; ++i) {
    const double a = 0.3 + (2 * kPi - 0.6) * i / 60;
    c.push_back({2 * std::cos(a), 2 * std::sin(a)});
  }
  for (int i = 60; i >= 0; --i) {
    const double a = 0.3 + (2 * kPi - 0.6) * i / 60;
    c.push_back({1.5 * std::cos(a), 1.5 * std::sin(a)});
  }
  check(c, pl, "C ring 122");
}

TEST(Triangulate, ClockwiseInputKeepsItsWinding) {
  RandomGeometry g(42);
  const Placement pl = random_placement(g, 3.0, 1.0);
  check(reversed(kL), pl, "L clockwise");
  check(reversed(kU), pl, "U clockwise");
  check(reversed(star(7, 0.3)), pl, "7-star clockwise");
  check(reversed(comb(10, 4.0)), pl, "comb clockwise");
}

TEST(Triangulate, CollinearDuplicateAndSpikeVertices) {
  RandomGeometry g(43);
  const Placement pl = random_placement(g, 3.0, 1.0);
  const Shape collinear{{0, 0}, {0.5, 0}, {1, 0}, {1, 0.25}, {1, 0.5}, {1, 1}, {0.3, 1}, {0, 1}};
  check(collinear, pl, "square + collinear");
  const Shape dups{{0, 0}, {0, 0}, {2, 0}, {2, 1}, {2, 1}, {2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}};
  check(dups, pl, "L + duplicates");
  const Shape spike{{0, 0}, {1, 0}, {1, 0.5}, {2, 0.5}, {1, 0.5}, {1, 1}, {0, 1}};
  check(spike, pl, "square + spike");
  // Long straight run across the whole U bottom.
  Shape run{{0, 0}};
  for (int i = 1; i < 30; ++i) run.push_back({3.0 * i / 30, 0});
  for (std::size_t i = 1; i < kU.size(); ++i) run.push_back(kU[i]);
  check(run, pl, "U + straight run");
  // Keyhole: a square with a square hole, joined by a two-way bridge (coincident vertices).
  const Shape keyhole{{0, 0}, {4, 0}, {4, 4}, {0, 4}, {0, 2}, {1, 2},
                      {1, 3}, {3, 3}, {3, 1}, {1, 1}, {1, 2}, {0, 2}};
  check(keyhole, pl, "keyhole");
  {
    // Verify the collinear/duplicate counts of the first two.
    std::vector<Vec3> v;
    for (V2 p : collinear) v.push_back(pl(p));
    const auto r = triangulate_polygon(v);
    EXPECT_EQ(r.removed_collinear, 4u);
    EXPECT_EQ(r.removed_duplicates, 0u);
    v.clear();
    for (V2 p : dups) v.push_back(pl(p));
    const auto r2 = triangulate_polygon(v);
    EXPECT_EQ(r2.removed_duplicates, 4u);
  }
}

TEST(Triangulate, BestShapedEarsTileTheSameShapes) {
  // The ear choice of the convex-quad converter: the same checks (exact area, no inverted or
  // outside triangle, consistent mesh). comb(40) has 160 vertices: it starts on the walk and
  // finishes on best-shaped ears below kBestEarVertexLimit.
  RandomGeometry g(46);
  const Placement pl = random_placement(g, 3.0, 1.0);
  const EarChoice best = EarChoice::BestShaped;
  check(kSquare, pl, "square, best-shaped", true, best);
  check(circle(16), pl, "16-gon, best-shaped", true, best);
  check(kL, pl, "L, best-shaped", true, best);
  check(reversed(kU), pl, "U clockwise, best-shaped", true, best);
  check(star(12, 0.2), pl, "12-point star, best-shaped", true, best);
  check(comb(40, 20.0), pl, "comb 40 teeth, best-shaped", true, best);
  const Shape keyhole{{0, 0}, {4, 0}, {4, 4}, {0, 4}, {0, 2}, {1, 2},
                      {1, 3}, {3, 3}, {3, 1}, {1, 1}, {1, 2}, {0, 2}};
  check(keyhole, pl, "keyhole, best-shaped", true, best);
  check(star(9, 0.3), random_placement(g, 1e6, 1.0), "star at 1e6, best-shaped", true, best);
  // A bow tie crosses itself: flagged, whichever ear choice.
  const std::vector<Vec3> bowtie{{0, 0, 0}, {3, 0, 0}, {0, 2, 0}, {1, 3, 0}};
  EXPECT_TRUE(triangulate_polygon(bowtie, best).not_simple);
  EXPECT_TRUE(triangulate_polygon(bowtie).not_simple);
}

TEST(Triangulate, ManyVertexCircles) {
  RandomGeometry g(44);
  const Placement pl = random_placement(g, 3.0, 1.0);
  check(circle(1000), pl, "circle 1000");
  check(circle(4000), pl, "circle 4000");
  check(reversed(star(500, 0.9)), pl, "star 1000 clockwise");
}

// Issue 11, defect 9: a polygon of the reader's largest size (kMaxPolygonVertices) took minutes,
// because every ear was tested against every vertex. Ears are now tested against the vertices a
// grid puts near them; the work (vertices looked at per polygon vertex) is bounded here, so a
// return to quadratic work fails without timing anything.
TEST(Triangulate, EarTestsStayNearLinearOnLongPolygons) {
  constexpr int kVertices = 100000;  // scenes::kMaxPolygonVertices
  RandomGeometry g(46);
  const Placement pl = random_placement(g, 3.0, 1.0);
  // Half the star's corners are reflex. (A comb of long thin teeth still costs ~n/10 tests per
  // vertex: ear clipping stays quadratic at worst, which is why kMaxPolygonVertices is 100,000.)
  const std::vector<std::pair<std::string, Shape>> shapes = {{"circle", circle(kVertices)},
                                                             {"star", star(kVertices / 2, 0.5)}};
  for (const auto& [name, shape] : shapes) {
    std::vector<Vec3> vertices;
    for (const V2 p : shape) vertices.push_back(pl(p));
    const TriangulationResult r = triangulate_polygon(vertices);
    ASSERT_TRUE(r.ok()) << name << ": " << r.reason;
    EXPECT_FALSE(r.not_simple) << name;
    EXPECT_EQ(r.triangles.size(), vertices.size() - 2) << name;
    const double per_vertex =
        static_cast<double>(r.ear_vertex_tests) / static_cast<double>(vertices.size());
    std::printf("%s of %zu vertices: %.3g vertex tests per vertex\n", name.c_str(), vertices.size(),
                per_vertex);
    EXPECT_LT(per_vertex, 1000.0) << name;  // testing every vertex would be ~5e4
  }
}

TEST(Triangulate, FarFromOriginAndTinyOrHuge) {
  RandomGeometry g(45);
  check(star(9, 0.3), random_placement(g, 1e6, 1.0), "star at 1e6");
  check(comb(6, 3.0), random_placement(g, 1e-6, 1e-6), "comb scaled 1e-6");
  check(kU, random_placement(g, 1e6, 1e6), "U scaled 1e6");
}

TEST(Triangulate, RejectsDegeneratePolygonsWithAReason) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(2, 0, 0);
  struct Case {
    std::vector<Vec3> v;
    const char* expect;
  };
  const Case cases[] = {
      {{a, b}, "fewer than 3"},
      {{a, a, a, a}, "fewer than 3 distinct"},
      {{a, b, c}, "zero area"},
      {{a, b, c, b}, "zero area"},
      {{a, b, a, b}, "zero area"},
      // Bow tie: the two lobes cancel, zero net area.
      {{a, Vec3(1, 1, 0), b, Vec3(0, 1, 0)}, "zero area"},
      {{a, b, Vec3(0, std::nan(""), 0)}, "non-finite"},
  };
  for (const Case& k : cases) {
    const auto r = triangulate_polygon(k.v);
    EXPECT_TRUE(r.rejected);
    EXPECT_TRUE(r.triangles.empty());
    EXPECT_NE(r.reason.find(k.expect), std::string::npos) << r.reason << " vs " << k.expect;
  }
  // Nearly degenerate but real: a sliver triangle is kept.
  const auto sliver = triangulate_polygon({a, c, Vec3(1, 1e-6, 0)});
  EXPECT_TRUE(sliver.ok()) << sliver.reason;
  EXPECT_EQ(sliver.triangles.size(), 1u);
}

TEST(Triangulate, SelfCrossingPolygonsAreRejectedWithTheEdgesThatCross) {
  // A pentagram drawn as one self-crossing loop has no one interior: rejected (issue 30 item 6:
  // it was triangulated into triangles covering more than its even-odd interior), flagged
  // not_simple so the convex-quad converter counts it as self-intersecting.
  std::vector<Vec3> v;
  for (int i = 0; i < 5; ++i) {
    const double a = 2 * kPi * (2 * i) / 5;
    v.emplace_back(std::cos(a), std::sin(a), 0.0);
  }
  const auto r = triangulate_polygon(v);
  EXPECT_TRUE(r.rejected);
  EXPECT_TRUE(r.not_simple);
  EXPECT_TRUE(r.triangles.empty());
  EXPECT_NE(r.reason.find("crosses itself"), std::string::npos) << r.reason;
  std::printf("pentagram: %s\n", r.reason.c_str());
  // The bow tie too, with either ear choice.
  const std::vector<Vec3> bowtie{{0, 0, 0}, {3, 0, 0}, {0, 2, 0}, {1, 3, 0}};
  EXPECT_TRUE(triangulate_polygon(bowtie, EarChoice::BestShaped).rejected);
}

TEST(Triangulate, StarsOfManyVerticesAreJudgedInNearLinearTime) {
  // A {n/(n-1)/2} star of 40,001 vertices crosses itself at every edge: found by the sweep at
  // once, where ear clipping took 105 s; the simple 40,000-vertex star next to it is kept, and
  // its ear tests stay a few per vertex.
  constexpr std::size_t n = 40001;
  std::vector<Vec3> crossing, simple;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = 2 * kPi * static_cast<double>(i * (n / 2) % n) / static_cast<double>(n);
    crossing.emplace_back(std::cos(a), std::sin(a), 0.0);
    const double b = 2 * kPi * static_cast<double>(i) / static_cast<double>(n - 1);
    const double radius = i % 2 == 0 ? 1.0 : 0.5;
    if (i + 1 < n) simple.emplace_back(radius * std::cos(b), radius * std::sin(b), 0.0);
  }
  EXPECT_TRUE(triangulate_polygon(crossing).rejected);
  const auto kept = triangulate_polygon(simple);
  ASSERT_TRUE(kept.ok()) << kept.reason;
  EXPECT_EQ(kept.triangles.size(), simple.size() - 2);
  EXPECT_LT(kept.ear_vertex_tests, 128 * simple.size());
}

/// Brute force: do two edges that share no vertex cross, each passing strictly through the
/// other? Exact on the small integer coordinates the test draws.
bool crosses_brute_force(const std::vector<Point2>& p) {
  const std::size_t n = p.size();
  const auto orient = [](Point2 a, Point2 b, Point2 c) {
    const double d = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    return (d > 0) - (d < 0);
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (j == i + 1 || (i == 0 && j == n - 1)) continue;
      const Point2 a = p[i], b = p[(i + 1) % n], c = p[j], d = p[(j + 1) % n];
      if ((a.x == b.x && a.y == b.y) || (c.x == d.x && c.y == d.y)) continue;
      const int o1 = orient(a, b, c), o2 = orient(a, b, d);
      const int o3 = orient(c, d, a), o4 = orient(c, d, b);
      if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    }
  return false;
}

TEST(SelfCrossing, AgreesWithEveryPairTestedOnRandomOutlines) {
  // Random outlines on a small integer grid (so the brute force is exact and snapping keeps
  // every coordinate): many cross, touch, run along each other or repeat a vertex. The sweep
  // must find a crossing exactly when some pair of edges crosses.
  std::uint64_t state = 12345;
  const auto next = [&state](int range) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<int>((state >> 33) % static_cast<std::uint64_t>(range));
  };
  int crossing = 0, simple = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    // The sweep snaps about the vertices' mean, 2^29 steps to the farthest coordinate: outlines
    // whose mean is the origin and whose extent is a power of two keep their integer
    // coordinates exactly. The last vertex makes the mean 0.
    const std::size_t n = 4 + static_cast<std::size_t>(next(9));
    std::vector<Point2> p;
    double cx = 0, cy = 0;
    for (std::size_t i = 0; i + 1 < n; ++i) {
      p.push_back({static_cast<double>(next(7) - 3), static_cast<double>(next(7) - 3)});
      cx += p.back().x;
      cy += p.back().y;
    }
    p.push_back({-cx, -cy});
    double extent = 0;
    for (const auto& q : p) extent = std::max({extent, std::fabs(q.x), std::fabs(q.y)});
    if (extent != 1 && extent != 2 && extent != 4) continue;
    const bool expected = crosses_brute_force(p);
    std::string outline;
    for (const auto& q : p)
      outline += " (" + std::to_string(q.x) + ", " + std::to_string(q.y) + ")";
    ASSERT_EQ(first_self_crossing(p).has_value(), expected) << "trial " << trial << ":" << outline;
    (expected ? crossing : simple)++;
  }
  std::printf("%d crossing and %d non-crossing outlines agreed\n", crossing, simple);
  EXPECT_GT(crossing, 100);
  EXPECT_GT(simple, 100);
}

TEST(Triangulate, NonPlanarPolygonsWarnButTriangulate) {
  std::vector<Vec3> v{{0, 0, 0}, {1, 0, 0}, {1, 1, 0.1}, {0, 1, 0}};
  const auto r = triangulate_polygon(v);
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("not planar"), std::string::npos) << r.warnings[0];
  EXPECT_EQ(r.triangles.size(), 2u);
  std::printf("warp 0.1: plane deviation %.3g of the diameter (tolerance %.3g)\n",
              r.plane_deviation, kNonPlanarRelativeTolerance);
  // Within tolerance (NFF-style rounding noise): no warning.
  v[2].z = 1e-6;
  const auto quiet = triangulate_polygon(v);
  EXPECT_TRUE(quiet.ok() && quiet.warnings.empty());
}

}  // namespace
}  // namespace rtsim::geometry
