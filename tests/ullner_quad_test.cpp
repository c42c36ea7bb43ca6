// Correctness of Ullner's ray / convex-quadrilateral intersection (seed 000 section 2.2) and of
// the polygon -> convex quad converter. Stress cases are in ullner_quad_stress_test.cpp.
#include "firmware/kernels/ullner_quad.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <string>

#include "firmware/geometry/convex_quads.hpp"
#include "firmware/kernels/ullner_description_words.hpp"
#include "firmware/kernels/ullner_quad_words.hpp"
#include "tests/ullner_quad_reference.hpp"

namespace rtsim {
namespace {

using kernels::intersect;
using kernels::kUllnerFlagsWord;
using kernels::kUllnerFlagUParallel;
using kernels::kUllnerFlagVParallel;
using kernels::kUllnerParamCount;
using kernels::kUllnerParamNames;
using kernels::kUllnerStoredWords;
using kernels::load_words;
using kernels::QuadFamily;
using kernels::QuadParam;
using kernels::QuadRejection;
using kernels::store_words;
using kernels::UllnerQuadKernel;
using kernels::UllnerQuadParams;
using quadtest::Quad;

// ---------------------------------------------------------------------------------------------
// The twenty parameters.
// ---------------------------------------------------------------------------------------------

TEST(UllnerQuadParams, TwentyNamedParametersAddressableAsArray) {
  EXPECT_EQ(kernels::kUllnerParamCount, 20u);
  std::set<std::string_view> names(kernels::kUllnerParamNames.begin(),
                                   kernels::kUllnerParamNames.end());
  EXPECT_EQ(names.size(), 20u);
  UllnerQuadParams<float> P;
  for (std::size_t i = 0; i < 20; ++i) P.word[i] = static_cast<float>(i);
  EXPECT_EQ(P.n_p(), Vec3T<float>(0, 1, 2));
  EXPECT_EQ(P.d_p(), 3.0f);
  EXPECT_EQ(P.u_a(), Vec3T<float>(4, 5, 6));
  EXPECT_EQ(P.u_a0(), 7.0f);
  EXPECT_EQ(P.u_c(), Vec3T<float>(8, 9, 10));
  EXPECT_EQ(P.u_c0(), 11.0f);
  EXPECT_EQ(P.v_a(), Vec3T<float>(12, 13, 14));
  EXPECT_EQ(P.v_a0(), 15.0f);
  EXPECT_EQ(P.v_b(), Vec3T<float>(16, 17, 18));
  EXPECT_EQ(P.v_b0(), 19.0f);
  EXPECT_EQ(P[QuadParam::v_b0], 19.0f);
  EXPECT_EQ(sizeof(P.word), 20 * sizeof(float));  // 640 bits in float (seed 000 L891)
}

// Unit square: both edge pairs parallel, so both coordinates use the parallel form (L380, L408)
// with the unscaled n_a, d_u1, n_c, d_u0 (and n_a, d_v1, n_b, d_v0). Hand-derived:
// p_a = 0, p_b = x, p_c = y, n_p = z; n_a = 0, n_b = p_b x n_p = -y, n_c = p_c x n_p = x;
// d_u1 = -(n_c.p_b) = -1, d_u0 = 0; d_v1 = -(n_b.p_c) = 1, d_v0 = 0.
TEST(UllnerQuadParams, UnitSquareHandDerived) {
  const auto P = UllnerQuadParams<double>::precompute({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  ASSERT_TRUE(P);
  EXPECT_TRUE(P->u_parallel);
  EXPECT_TRUE(P->v_parallel);
  EXPECT_EQ(P->u_family, QuadFamily::Parallel);
  EXPECT_EQ(P->n_p(), Vec3(0, 0, 1));
  EXPECT_DOUBLE_EQ(P->d_p(), 0.0);
  EXPECT_EQ(P->u_a(), Vec3(0, 0, 0));
  EXPECT_DOUBLE_EQ(P->u_a0(), -1.0);
  EXPECT_EQ(P->u_c(), Vec3(1, 0, 0));
  EXPECT_DOUBLE_EQ(P->u_c0(), 0.0);
  EXPECT_EQ(P->v_a(), Vec3(0, 0, 0));
  EXPECT_DOUBLE_EQ(P->v_a0(), 1.0);
  EXPECT_EQ(P->v_b(), Vec3(0, -1, 0));
  EXPECT_DOUBLE_EQ(P->v_b0(), 0.0);
  // Ray down the z axis through (0.25, 0.75): u = x, v = y; t = 2 (distance along unit d).
  const auto r = intersect<double>(*P, Vec3(0.25, 0.75, 2.0), Vec3(0, 0, -1));
  EXPECT_TRUE(r.t_valid && r.u_valid && r.v_valid);
  EXPECT_DOUBLE_EQ(r.t, 2.0);
  EXPECT_DOUBLE_EQ(r.u, 0.25);
  EXPECT_DOUBLE_EQ(r.v, 0.75);
}

// A quad with no parallel edges, p00 = 0, p10 = x, p11 = (2,2,0), p01 = y. Hand-derived:
// p_a = (1,1,0), n_a = (1,-1,0), n_b = (0,-1,0), n_c = (1,0,0);
// d_u2 = -n_a.p_b = -1, d_u1 = -(n_c.p_b) = -1, d_u0 = 0; d_v2 = -n_a.p_c = 1, d_v1 = 1, d_v0 = 0.
// Stored (L538-L542 with the 2d_u2 erratum): n_a/(2d_u2) = (-.5,.5,0), d_u1/(2d_u2) = .5,
// n_c/d_u2 = (-1,0,0), d_u0/d_u2 = 0; n_a/(2d_v2) = (.5,-.5,0), d_v1/(2d_v2) = .5,
// n_b/d_v2 = (0,-1,0), d_v0/d_v2 = 0.
TEST(UllnerQuadParams, GeneralQuadHandDerivedPrescaling) {
  const auto P = UllnerQuadParams<double>::precompute({0, 0, 0}, {1, 0, 0}, {2, 2, 0}, {0, 1, 0});
  ASSERT_TRUE(P);
  EXPECT_FALSE(P->u_parallel);
  EXPECT_FALSE(P->v_parallel);
  EXPECT_EQ(P->u_a(), Vec3(-0.5, 0.5, 0));
  EXPECT_DOUBLE_EQ(P->u_a0(), 0.5);
  EXPECT_EQ(P->u_c(), Vec3(-1, 0, 0));
  EXPECT_DOUBLE_EQ(P->u_c0(), 0.0);
  EXPECT_EQ(P->v_a(), Vec3(0.5, -0.5, 0));
  EXPECT_DOUBLE_EQ(P->v_a0(), 0.5);
  EXPECT_EQ(P->v_b(), Vec3(0, -1, 0));
  EXPECT_DOUBLE_EQ(P->v_b0(), 0.0);
  // p(0.5, 0.5) = p_a/4 + p_b/2 + p_c/2 = (0.75, 0.75, 0): B = 0.5, C = -0.75, u = -0.5 +- 1.
  const auto r = intersect<double>(*P, Vec3(0.75, 0.75, -1.0), Vec3(0, 0, 1));
  ASSERT_TRUE(r.hit());
  EXPECT_NEAR(r.u, 0.5, 1e-15);
  EXPECT_NEAR(r.v, 0.5, 1e-15);
}

TEST(UllnerQuadParams, RejectionsWithReasonsAtEveryScale) {
  const double nan = std::nan("");
  struct Case {
    const char* name;
    Quad q;
    QuadRejection why;
  };
  const Case cases[] = {
      {"non-finite",
       {{{0, 0, 0}, {1, 0, 0}, {1, nan, 0}, {0, 1, 0}}},
       QuadRejection::NonFiniteVertex},
      {"point", {{{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}}}, QuadRejection::ZeroArea},
      {"collinear", {{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}}, QuadRejection::ZeroArea},
      {"segment (two edges collapsed)",
       {{{0, 0, 0}, {0, 0, 0}, {1, 1, 0}, {1, 1, 0}}},
       QuadRejection::ZeroArea},
      {"non-planar", {{{0, 0, 0}, {1, 0, 0}, {1, 1, 1e-3}, {0, 1, 0}}}, QuadRejection::NonPlanar},
      {"concave dart",
       {{{0, 0, 0}, {2, 0, 0}, {0.5, 0.5, 0}, {0, 2, 0}}},
       QuadRejection::NonConvex},
      {"bowtie", {{{0, 0, 0}, {2, 2, 0}, {2, 0, 0}, {0, 1, 0}}}, QuadRejection::NonConvex},
  };
  for (const double scale : {1.0, 1e-6, 1e6}) {
    for (const Case& c : cases) {
      Quad q = c.q;
      for (Vec3& p : q) p *= scale;
      const auto pre = UllnerQuadParams<double>::precompute_checked(q[0], q[1], q[2], q[3]);
      EXPECT_FALSE(pre.ok()) << c.name << " at scale " << scale;
      EXPECT_EQ(pre.rejection, c.why)
          << c.name << " at scale " << scale << ": got " << kernels::to_string(pre.rejection);
      QuadRejection why = QuadRejection::None;
      EXPECT_FALSE(UllnerQuadKernel::from(q[0], q[1], q[2], q[3], nullptr, why));
      EXPECT_EQ(why, c.why);
    }
    // Tiny non-planarity (below kUllnerPlanarityTolerance) and a straight corner are accepted.
    EXPECT_TRUE(UllnerQuadParams<double>::precompute(scale * Vec3(0, 0, 0), scale * Vec3(1, 0, 0),
                                                     scale * Vec3(1, 1, 1e-7),
                                                     scale * Vec3(0, 1, 0)));
    EXPECT_TRUE(UllnerQuadParams<double>::precompute(scale * Vec3(0, 0, 0), scale * Vec3(1, 0, 0),
                                                     scale * Vec3(2, 0, 0), scale * Vec3(0, 1, 0)));
  }
}

// The parallel decision is relative: the same shape gets the same family at any scale.
TEST(UllnerQuadParams, ParallelDecisionIsScaleInvariant) {
  for (const double s : {1e-2, 1e-8, 1e-10}) {
    std::set<int> families;
    for (const double scale : {1e-6, 1.0, 1e6}) {
      const auto P = UllnerQuadParams<double>::precompute(
          scale * Vec3(-1, -0.5, 0), scale * Vec3(1, -0.5, 0), scale * Vec3(0.5, 0.5 + s, 0),
          scale * Vec3(-0.5, 0.5, 0));
      ASSERT_TRUE(P);
      families.insert(static_cast<int>(P->u_family));
    }
    EXPECT_EQ(families.size(), 1u) << "sine " << s;
    EXPECT_EQ(*families.begin(),
              static_cast<int>(s > kernels::kUllnerParallelEdgeSine ? QuadFamily::Quadratic
                                                                    : QuadFamily::Parallel));
  }
}

// ---------------------------------------------------------------------------------------------
// Intersection against the independent reference.
// ---------------------------------------------------------------------------------------------

template <typename T>
quadtest::Tally random_quads_vs_reference(std::uint64_t seed, int quads, int rays_per_quad,
                                          double min_corner_sine) {
  std::mt19937_64 rng(seed);
  quadtest::Tally tally;
  for (int i = 0; i < quads; ++i) {
    const Quad q = quadtest::random_convex_quad(rng, 1.0, 2.0, min_corner_sine);
    const auto P = UllnerQuadParams<T>::precompute(q[0], q[1], q[2], q[3]);
    EXPECT_TRUE(P);
    if (!P) continue;
    for (int j = 0; j < rays_per_quad; ++j) {
      Vec3 o, d;
      quadtest::random_ray_at(rng, q, o, d, 0.6);
      quadtest::tally_ray<T>(*P, q, o, d, tally);
    }
  }
  return tally;
}

void print_tally(const char* what, const quadtest::Tally& t) {
  std::printf(
      "%-28s rays %8ld  ref hits %7ld  disagree %5ld (%.2e)  unexplained %ld  "
      "max |p(u,v)-p_r|/L %.2e  non-finite %ld\n",
      what, t.rays, t.ref_hits, t.disagree, t.disagree_rate(), t.unexplained, t.max_residual,
      t.nonfinite);
}

// Random convex quads (corner sines >= 0.05, or >= 1e-3 for near-degenerate shapes) and random
// rays aimed near them. The kernel may disagree with the reference only within the
// disagreement band around the edges (range tolerance plus the rounding of p_r; see
// ullner_quad_reference.hpp). Expected in double: no disagreement at all on random rays.
TEST(UllnerQuadIntersect, RandomQuadsAgreeWithReference) {
  const auto d = random_quads_vs_reference<double>(1, 1500, 300, 0.05);
  const auto d2 = random_quads_vs_reference<double>(2, 1500, 300, 1e-3);
  const auto f = random_quads_vs_reference<float>(1, 1500, 300, 0.05);
  const auto f2 = random_quads_vs_reference<float>(2, 1500, 300, 1e-3);
  print_tally("double", d);
  print_tally("double, sharp corners", d2);
  print_tally("float", f);
  print_tally("float, sharp corners", f2);
  for (const auto* t : {&d, &d2, &f, &f2}) {
    EXPECT_GT(t->ref_hits, t->rays / 10);  // the test does exercise hits
    EXPECT_EQ(t->unexplained, 0);
    EXPECT_EQ(t->nonfinite, 0);
  }
  EXPECT_LE(d.disagree + d2.disagree, 2);  // double: only rays within ~1e-9 of an edge
  EXPECT_LT(d.max_residual, 1e-12);        // p(u,v) reproduces p_r
  EXPECT_LT(f.max_residual, 1e-5);         // float: a few eps * |p|/L
  // Float vs the double reference: hit/miss disagreement rate bound (stated in the stress test
  // too): rays within the band of an edge only.
  EXPECT_LT(f.disagree_rate(), 2e-4);
  EXPECT_LT(f2.disagree_rate(), 2e-4);
}

// u, v round trip: shoot at p(u,v) for random (u,v) in the unit square and get (u,v) back.
template <typename T>
double round_trip_error(const Quad& q, std::mt19937_64& rng, int n, int* misses) {
  const auto P = UllnerQuadParams<T>::precompute(q[0], q[1], q[2], q[3]);
  EXPECT_TRUE(P);
  if (!P) return 1.0;
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const Vec3 nrm = quadtest::quad_normal(q);
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = U(rng), v = U(rng);
    const Vec3 target = quadtest::bilinear(q, u, v);
    // Directions within 60 degrees of the normal (either side).
    const Vec3 dir = glm::normalize(nrm * (U(rng) < 0.5 ? 1.0 : -1.0) +
                                    1.5 * (quadtest::random_unit(rng) * U(rng)));
    if (std::fabs(glm::dot(dir, nrm)) < 0.5) {
      --i;
      continue;
    }
    const Vec3 o = target - 3.0 * quadtest::quad_size(q) * dir;
    const auto r = intersect<T>(*P, Vec3T<T>(o), Vec3T<T>(dir));
    if (!r.hit()) {
      ++*misses;
      continue;
    }
    worst = std::max({worst, std::fabs(double(r.u) - u), std::fabs(double(r.v) - v)});
  }
  return worst;
}

TEST(UllnerQuadIntersect, UVRoundTrip) {
  std::mt19937_64 rng(3);
  double worst_d = 0.0, worst_f = 0.0;
  int miss_d = 0, miss_f = 0;
  for (int i = 0; i < 300; ++i) {
    const Quad q = quadtest::random_convex_quad(rng, 1.0, 2.0, 0.05);
    worst_d = std::max(worst_d, round_trip_error<double>(q, rng, 100, &miss_d));
    worst_f = std::max(worst_f, round_trip_error<float>(q, rng, 100, &miss_f));
  }
  std::printf(
      "u,v round trip over 30000 points: double max error %.2e (misses %d), float %.2e "
      "(misses %d)\n",
      worst_d, miss_d, worst_f, miss_f);
  // Double: rounding only (the quads' conditioning is bounded by the 0.05 corner sine).
  EXPECT_LT(worst_d, 1e-12);
  // Float: eps * |p|/L * conditioning ~ 1e-7 * 10 * 10.
  EXPECT_LT(worst_f, 1e-5);
  EXPECT_EQ(miss_d, 0);
  // Points up to the very edge are targeted; float may lose one only within its band.
  EXPECT_LE(miss_f, 3);
}

// Rectangles, parallelograms and trapezoids: the parallel-case formula (L380, L408).
TEST(UllnerQuadIntersect, ParallelEdgeCases) {
  struct Case {
    const char* name;
    std::array<glm::dvec2, 4> p;
    QuadFamily u, v;
  };
  const Case cases[] = {
      {"rectangle", {{{0, 0}, {3, 0}, {3, 1}, {0, 1}}}, QuadFamily::Parallel, QuadFamily::Parallel},
      {"parallelogram",
       {{{0, 0}, {2, 0}, {2.7, 1}, {0.7, 1}}},
       QuadFamily::Parallel,
       QuadFamily::Parallel},
      {"trapezoid, v=0 || v=1",
       {{{0, 0}, {2, 0}, {1.5, 1}, {0.2, 1}}},
       QuadFamily::Parallel,
       QuadFamily::Quadratic},
      {"trapezoid, u=0 || u=1",
       {{{0, 0}, {2, 0.3}, {2, 1.5}, {0, 1}}},
       QuadFamily::Quadratic,
       QuadFamily::Parallel},
  };
  std::mt19937_64 rng(5);
  for (const Case& c : cases) {
    quadtest::Tally td, tf;
    double worst_d = 0.0, worst_f = 0.0;
    int miss = 0;
    for (int k = 0; k < 50; ++k) {
      const Vec3 n = quadtest::random_unit(rng);
      Vec3 t1, t2;
      quadtest::frame(n, t1, t2);
      const Quad q = quadtest::embed(c.p, quadtest::random_unit(rng) * 2.0, t1, t2);
      const auto P = UllnerQuadParams<double>::precompute(q[0], q[1], q[2], q[3]);
      const auto Pf = UllnerQuadParams<float>::precompute(q[0], q[1], q[2], q[3]);
      ASSERT_TRUE(P && Pf);
      EXPECT_EQ(P->u_family, c.u) << c.name;
      EXPECT_EQ(P->v_family, c.v) << c.name;
      for (int j = 0; j < 400; ++j) {
        Vec3 o, d;
        quadtest::random_ray_at(rng, q, o, d, 0.6);
        quadtest::tally_ray<double>(*P, q, o, d, td);
        quadtest::tally_ray<float>(*Pf, q, o, d, tf);
      }
      worst_d = std::max(worst_d, round_trip_error<double>(q, rng, 50, &miss));
      worst_f = std::max(worst_f, round_trip_error<float>(q, rng, 50, &miss));
    }
    std::printf(
        "%-24s double: disagree %ld unexplained %ld round trip %.2e | float: disagree "
        "%ld unexplained %ld round trip %.2e\n",
        c.name, td.disagree, td.unexplained, worst_d, tf.disagree, tf.unexplained, worst_f);
    EXPECT_EQ(td.unexplained + tf.unexplained, 0) << c.name;
    EXPECT_EQ(td.nonfinite + tf.nonfinite, 0) << c.name;
    EXPECT_LT(worst_d, 1e-12) << c.name;
    EXPECT_LT(worst_f, 1e-5) << c.name;
    EXPECT_EQ(miss, 0) << c.name;
  }
}

// A triangle given as a quad with two equal vertices, each of the four edges collapsed in turn:
// the family of that edge is deflated and the other is a pencil through the collapsed vertex.
TEST(UllnerQuadIntersect, TriangleAsQuadWithTwoEqualVertices) {
  std::mt19937_64 rng(11);
  for (int e = 0; e < 4; ++e) {
    quadtest::Tally td, tf;
    for (int k = 0; k < 200; ++k) {
      Quad q = quadtest::random_convex_quad(rng, 1.0, 2.0, 0.05);
      q[static_cast<std::size_t>((e + 1) % 4)] = q[static_cast<std::size_t>(e)];
      const auto P = UllnerQuadParams<double>::precompute(q[0], q[1], q[2], q[3]);
      const auto Pf = UllnerQuadParams<float>::precompute(q[0], q[1], q[2], q[3]);
      ASSERT_TRUE(P && Pf);
      const bool v_edge = (e % 2) == 0;  // edges 0 (v=0) and 2 (v=1)
      EXPECT_EQ(P->u_family, v_edge ? QuadFamily::Pencil : QuadFamily::Deflated);
      EXPECT_EQ(P->v_family, v_edge ? QuadFamily::Deflated : QuadFamily::Pencil);
      for (int j = 0; j < 300; ++j) {
        Vec3 o, d;
        quadtest::random_ray_at(rng, q, o, d, 0.6);
        quadtest::tally_ray<double>(*P, q, o, d, td);
        quadtest::tally_ray<float>(*Pf, q, o, d, tf);
      }
    }
    std::printf(
        "triangle, edge %d collapsed: double disagree %ld unexplained %ld residual %.2e | "
        "float disagree %ld unexplained %ld residual %.2e\n",
        e, td.disagree, td.unexplained, td.max_residual, tf.disagree, tf.unexplained,
        tf.max_residual);
    EXPECT_EQ(td.unexplained + tf.unexplained, 0);
    EXPECT_EQ(td.nonfinite + tf.nonfinite, 0);
    EXPECT_LE(td.disagree, 1);
    EXPECT_LT(td.max_residual, 1e-12);
    // Float: eps |p_r| / h, h the triangle's height; dropping a corner of a random quad leaves
    // triangles as thin as ~1/20 of their size, hence a looser bound than for quads.
    EXPECT_LT(tf.max_residual, 5e-5);
  }
}

// Validity bits as the pipeline produces them (L522-L530).
TEST(UllnerQuadIntersect, ValidityBits) {
  const auto P = UllnerQuadParams<double>::precompute({0, 0, 0}, {1, 0, 0}, {2, 2, 0}, {0, 1, 0});
  ASSERT_TRUE(P);
  // Parallel to the plane: t invalid, and so are u and v (propagation, L526).
  auto r = intersect<double>(*P, Vec3(0.5, 0.5, 1), Vec3(1, 0, 0));
  EXPECT_FALSE(r.t_valid);
  EXPECT_FALSE(r.u_valid || r.v_valid || r.hit());
  // Behind the origin (t < 0, L275).
  r = intersect<double>(*P, Vec3(0.5, 0.5, 1), Vec3(0, 0, 1));
  EXPECT_FALSE(r.t_valid);
  EXPECT_LT(r.t, 0.0);
  // Beyond t_max, and before t_min.
  r = intersect<double>(*P, Vec3(0.5, 0.5, 1), Vec3(0, 0, -1), 0.0, 0.5);
  EXPECT_FALSE(r.t_valid);
  r = intersect<double>(*P, Vec3(0.5, 0.5, 1), Vec3(0, 0, -1), 1.5);
  EXPECT_FALSE(r.t_valid);
  // In the plane, u in range but v out: u = 0.5 line beyond the v = 1 edge.
  const Vec3 beyond_v =
      quadtest::bilinear({{{0, 0, 0}, {1, 0, 0}, {2, 2, 0}, {0, 1, 0}}}, 0.5, 1.3);
  r = intersect<double>(*P, beyond_v + Vec3(0, 0, 1), Vec3(0, 0, -1));
  EXPECT_TRUE(r.t_valid);
  EXPECT_TRUE(r.u_valid);
  EXPECT_FALSE(r.v_valid);
  EXPECT_FALSE(r.hit());
  EXPECT_NEAR(r.u, 0.5, 1e-12);
  // And the other way round.
  const Vec3 beyond_u =
      quadtest::bilinear({{{0, 0, 0}, {1, 0, 0}, {2, 2, 0}, {0, 1, 0}}}, -0.2, 0.4);
  r = intersect<double>(*P, beyond_u + Vec3(0, 0, 1), Vec3(0, 0, -1));
  EXPECT_FALSE(r.u_valid);
  EXPECT_TRUE(r.v_valid);
  EXPECT_NEAR(r.v, 0.4, 1e-12);
  // Far away in the plane (complex roots or both out of range): a miss with no NaN reported.
  r = intersect<double>(*P, Vec3(-50, 80, 1), Vec3(0, 0, -1));
  EXPECT_TRUE(r.t_valid);
  EXPECT_FALSE(r.hit());
}

// ---------------------------------------------------------------------------------------------
// The adapter.
// ---------------------------------------------------------------------------------------------

TEST(UllnerQuadKernel, AdapterFillsHitAndInterpolatesCornerNormals) {
  const Vec3 p00(0, 0, 0), p10(2, 0, 0), p11(2.5, 2, 0), p01(0, 1.5, 0);
  const Vec3 normals[4] = {glm::normalize(Vec3(-1, -1, 2)), glm::normalize(Vec3(1, -1, 2)),
                           glm::normalize(Vec3(1, 1, 2)), glm::normalize(Vec3(-1, 1, 2))};
  const auto k = UllnerQuadKernel::from(p00, p10, p11, p01, normals);
  const auto flat = UllnerQuadKernel::from(p00, p10, p11, p01);
  ASSERT_TRUE(k && flat);
  EXPECT_TRUE(k->has_corner_normals);
  EXPECT_FALSE(flat->has_corner_normals);
  EXPECT_EQ(k->bounds().lo, Vec3(0, 0, 0));
  EXPECT_EQ(k->bounds().hi, Vec3(2.5, 2, 0));
  const Quad q = {p00, p10, p11, p01};
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    const double u = U(rng), v = U(rng);
    const Vec3 target = quadtest::bilinear(q, u, v);
    const Vec3 o = target + Vec3(0.3, -0.2, 4.0);
    const Ray ray{o, glm::normalize(target - o)};
    SurfaceHit h;
    ASSERT_TRUE(k->intersect(ray, 1e-9, kInfinity, h));
    EXPECT_NEAR(h.t, glm::length(target - o), 1e-12);  // t is a distance (plane z = 0 exact)
    // The kernel's parameters are stored as singles, as the peripheral's memories hold them
    // (ullner_quad_words.hpp): u and v carry their rounding, ~1e-7 of the quad.
    constexpr double kSingleParams = 1e-6;
    EXPECT_NEAR(h.u, u, kSingleParams);
    EXPECT_NEAR(h.v, v, kSingleParams);
    EXPECT_EQ(h.geometric_normal, Vec3(0, 0, 1));  // CCW p00, p10, p11, p01 about +z
    // L452-L456: bilinear interpolation of the corner normals, then normalised.
    const Vec3 expect = glm::normalize((1 - u) * (1 - v) * normals[0] + u * (1 - v) * normals[1] +
                                       u * v * normals[2] + (1 - u) * v * normals[3]);
    EXPECT_NEAR(glm::length(h.shading_normal - expect), 0.0, kSingleParams);
    SurfaceHit hf;
    ASSERT_TRUE(flat->intersect(ray, 1e-9, kInfinity, hf));
    EXPECT_EQ(hf.shading_normal, hf.geometric_normal);
    // t range of the caller.
    EXPECT_FALSE(k->intersect(ray, 1e-9, h.t * 0.99, h));
    EXPECT_FALSE(k->intersect(ray, h.t * 1.01, kInfinity, h));
  }
  // Bad corner normals are dropped, not propagated.
  const Vec3 bad[4] = {Vec3(0, 0, 1), Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 0, 1)};
  const auto kb = UllnerQuadKernel::from(p00, p10, p11, p01, bad);
  ASSERT_TRUE(kb);
  EXPECT_FALSE(kb->has_corner_normals);
}

TEST(UllnerQuadKernel, TestCostCountsTheHardwareFormulation) {
  constexpr Cost c = kernels::kUllnerQuadPreparedTestCost;
  // Arithmetic: 23 mul, 24 add, 3 div, 2 sqrt (thesis: 23/26/3/2, L588); 13 compares.
  EXPECT_EQ(c.fp_mul, 23u);
  EXPECT_EQ(c.fp_add, 24u + 13u);
  EXPECT_EQ(c.fp_div, 3u);
  EXPECT_EQ(c.fp_sqrt, 2u);
  EXPECT_EQ(c.mem_words, 24u);
  EXPECT_EQ(UllnerQuadKernel::kTestCost.fp_add, c.fp_add + 2u);  // + per-ray setup
}

// ---------------------------------------------------------------------------------------------
// Polygon -> convex quads.
// ---------------------------------------------------------------------------------------------

double area_of(const geometry::ConvexQuad& q) {
  return 0.5 * glm::length(glm::cross(q.corners[2] - q.corners[0], q.corners[3] - q.corners[1]));
}

double polygon_area(const std::vector<Vec3>& v) {
  Vec3 a(0.0);
  for (std::size_t i = 0; i < v.size(); ++i) a += glm::cross(v[i], v[(i + 1) % v.size()]);
  return 0.5 * glm::length(a);
}

/// Crossing-number point-in-polygon in the xy plane (the reference for concave polygons).
bool inside_xy(const std::vector<Vec3>& v, double x, double y) {
  bool in = false;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    if ((v[i].y > y) != (v[j].y > y) &&
        x < (v[j].x - v[i].x) * (y - v[i].y) / (v[j].y - v[i].y) + v[i].x) {
      in = !in;
    }
  }
  return in;
}

/// Every produced primitive must be accepted by the kernel; random vertical rays must hit the
/// union of the primitives exactly where they hit the polygon (away from its edges).
void check_conversion(const std::vector<Vec3>& poly, const std::vector<geometry::ConvexQuad>& qs,
                      int* disagreements) {
  std::vector<UllnerQuadKernel> ks;
  double area = 0.0;
  for (const auto& q : qs) {
    const auto k = UllnerQuadKernel::from(q.corners[0], q.corners[1], q.corners[2], q.corners[3],
                                          q.has_normals ? q.normals.data() : nullptr);
    ASSERT_TRUE(k);
    EXPECT_GT(k->params.n_p().z, 0.0);  // orientation kept
    ks.push_back(*k);
    area += area_of(q);
  }
  EXPECT_NEAR(area, polygon_area(poly), 1e-9 * polygon_area(poly));
  Bounds b;
  for (const Vec3& p : poly) b.extend(p);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int i = 0; i < 4000; ++i) {
    const double x = b.lo.x + (b.hi.x - b.lo.x) * U(rng);
    const double y = b.lo.y + (b.hi.y - b.lo.y) * U(rng);
    int hits = 0;
    for (const auto& k : ks) {
      SurfaceHit h;
      hits += k.intersect(Ray{Vec3(x, y, 5), Vec3(0, 0, -1)}, 0.0, kInfinity, h);
    }
    if ((hits > 0) != inside_xy(poly, x, y)) ++*disagreements;
    EXPECT_LE(hits, 1) << "overlapping primitives at " << x << ", " << y;
  }
}

TEST(ConvexQuads, SquareTriangleAndConcavePolygons) {
  geometry::ConvexQuadReport rep;
  // A convex quad is kept as given.
  const std::vector<Vec3> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  auto out = geometry::convert_polygon(square, {}, rep);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_FALSE(out[0].triangle);
  EXPECT_EQ(out[0].corners[0], square[0]);
  EXPECT_EQ(out[0].corners[2], square[2]);
  // A triangle becomes a quad with two equal vertices, normals carried.
  const std::vector<Vec3> tri = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<Vec3> tri_n = {{0, 0, 1}, {0, 0.1, 1}, {0.1, 0, 1}};
  out = geometry::convert_polygon(tri, tri_n, rep);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].triangle);
  EXPECT_EQ(out[0].corners[2], out[0].corners[3]);
  EXPECT_TRUE(out[0].has_normals);
  EXPECT_EQ(out[0].normals[2], out[0].normals[3]);

  struct Case {
    const char* name;
    std::vector<Vec3> v;
    std::size_t min_quads;  // merges the greedy pass must find (the comb's teeth and the star's
                            // points are triangles that no convex quad can contain)
  };
  std::vector<Case> cases = {
      {"L shape", {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, 2},
      {"concave quad (dart)", {{0, 0, 0}, {2, 0, 0}, {0.5, 0.5, 0}, {0, 2, 0}}, 0},
      {"U shape",
       {{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {2, 3, 0}, {2, 1, 0}, {1, 1, 0}, {1, 3, 0}, {0, 3, 0}},
       3},
      {"comb",
       {{0, 0, 0},
        {5, 0, 0},
        {5, 2, 0},
        {4.5, 2, 0},
        {4, 0.5, 0},
        {3.5, 2, 0},
        {3, 0.5, 0},
        {2.5, 2, 0},
        {2, 0.5, 0},
        {1.5, 2, 0},
        {1, 0.5, 0},
        {0.5, 2, 0},
        {0, 2, 0}},
       3},
  };
  // A 5-point star and a 16-gon (convex, many vertices).
  Case star{"star", {}, 3}, ngon{"16-gon", {}, 6};
  for (int i = 0; i < 10; ++i) {
    const double a = kPi / 2 + i * kPi / 5, r = (i % 2 == 0) ? 2.0 : 0.8;
    star.v.push_back(Vec3(r * std::cos(a), r * std::sin(a), 0));
  }
  for (int i = 0; i < 16; ++i) {
    ngon.v.push_back(Vec3(std::cos(i * kPi / 8), std::sin(i * kPi / 8), 0));
  }
  cases.push_back(star);
  cases.push_back(ngon);
  for (const Case& c : cases) {
    geometry::ConvexQuadReport r;
    const auto qs = geometry::convert_polygon(c.v, {}, r);
    int dis = 0;
    check_conversion(c.v, qs, &dis);
    std::printf("%-20s %2zu vertices -> %zu quads + %zu triangles; ray disagreements %d/4000\n",
                c.name, c.v.size(), r.quads, r.triangles, dis);
    EXPECT_EQ(r.rejected, 0u) << c.name;
    // Only rays within the kernels' tolerance of an edge may differ from the polygon test.
    EXPECT_LE(dis, 1) << c.name;
    EXPECT_GE(r.quads, c.min_quads) << c.name << ": too few merges";
    EXPECT_EQ(2 * r.quads + r.triangles, c.v.size() - 2) << c.name;  // n - 2 triangles in all
    rep.merge(r);
  }
  std::printf("%s\n", rep.summary().c_str());
}

TEST(ConvexQuads, RepairsAndRejectionsAreCounted) {
  geometry::ConvexQuadReport rep;
  std::vector<geometry::ConvexQuad> out;
  const double nan = std::nan("");
  // Rejected.
  geometry::convert_polygon({{0, 0, 0}, {1, 0, 0}}, {}, out, rep);
  geometry::convert_polygon({{0, 0, 0}, {1, nan, 0}, {0, 1, 0}}, {}, out, rep);
  geometry::convert_polygon({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}, {}, out, rep);
  geometry::convert_polygon({{0, 0, 0}, {3, 0, 0}, {0, 2, 0}, {1, 3, 0}}, {}, out, rep);  // bowtie
  EXPECT_EQ(out.size(), 0u);
  EXPECT_EQ(rep.rejected, 4u);
  EXPECT_EQ(rep.count(geometry::PolygonRejection::TooFewVertices), 1u);
  EXPECT_EQ(rep.count(geometry::PolygonRejection::NonFiniteVertex), 1u);
  EXPECT_EQ(rep.count(geometry::PolygonRejection::ZeroArea), 1u);
  EXPECT_EQ(rep.count(geometry::PolygonRejection::NotSimple), 1u);
  // Repaired: duplicate vertex, collinear vertex, wrong normal count, non-planar.
  geometry::convert_polygon({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {}, out, rep);
  geometry::convert_polygon({{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {}, out,
                            rep);
  geometry::convert_polygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {{0, 0, 1}}, out, rep);
  geometry::convert_polygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0.2}, {0, 1, 0}}, {}, out, rep);
  EXPECT_EQ(rep.converted, 4u);
  EXPECT_EQ(rep.repaired, 4u);
  EXPECT_EQ(rep.count(geometry::PolygonRepair::DuplicateVertex), 1u);
  EXPECT_EQ(rep.count(geometry::PolygonRepair::CollinearVertex), 1u);
  EXPECT_EQ(rep.count(geometry::PolygonRepair::NormalsDropped), 1u);
  EXPECT_EQ(rep.count(geometry::PolygonRepair::NonPlanar), 1u);
  EXPECT_EQ(rep.polygons, 8u);
  // The duplicate and the collinear square each became one quad; the non-planar one triangles.
  EXPECT_EQ(rep.quads, 2u);
  EXPECT_EQ(rep.triangles, 3u);
  for (const auto& q : out) {
    EXPECT_TRUE(UllnerQuadKernel::from(q.corners[0], q.corners[1], q.corners[2], q.corners[3]));
  }
  std::printf("%s\n", rep.summary().c_str());
}

TEST(ConvexQuads, TriangleListMergedIntoQuads) {
  // A 4x3 grid of squares, each split into two triangles along alternating diagonals, with
  // per-vertex normals: every pair merges back into a quad.
  std::vector<Vec3> v, n;
  const int nx = 4, ny = 3;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      v.push_back(Vec3(i, j, 0.0));
      n.push_back(glm::normalize(Vec3(0.1 * i, 0.1 * j, 1.0)));
    }
  }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (nx + 1) + i); };
  std::vector<std::array<std::uint32_t, 3>> tris;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      if ((i + j) % 2 == 0) {
        tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        tris.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        tris.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  }
  tris.push_back({id(0, 0), id(1, 0), id(2, 0)});  // degenerate: dropped and counted
  geometry::ConvexQuadReport rep;
  const auto out = geometry::convert_triangles_to_quads(v, tris, n, &rep);
  EXPECT_EQ(rep.quads, static_cast<std::size_t>(nx * ny));
  EXPECT_EQ(rep.triangles, 0u);
  EXPECT_EQ(rep.triangles_dropped, 1u);
  double area = 0.0;
  for (const auto& q : out) {
    EXPECT_TRUE(q.has_normals);
    const auto k = UllnerQuadKernel::from(q.corners[0], q.corners[1], q.corners[2], q.corners[3],
                                          q.normals.data());
    ASSERT_TRUE(k);
    EXPECT_GT(k->params.n_p().z, 0.0);
    area += area_of(q);
  }
  EXPECT_NEAR(area, nx * ny, 1e-12);
  // A fold (two non-coplanar triangles) is not merged.
  const std::vector<Vec3> fv = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.5}};
  const auto folded = geometry::convert_triangles_to_quads(fv, {{{0, 1, 2}}, {{0, 2, 3}}});
  EXPECT_EQ(folded.size(), 2u);
  for (const auto& q : folded) EXPECT_TRUE(q.triangle);
}

TEST(UllnerQuadWords, TheKernelComputesOnWhatTheMemoriesHold) {
  // A quad with a parallel family (u) and a quadratic one (v), so both flag kinds are set.
  const Vec3 p00(0.1, 0.2, 0.3), p10(2.1, 0.2, 0.3), p11(2.6, 2.2, 0.3), p01(0.1, 1.7, 0.3);
  const auto k = UllnerQuadKernel::from(p00, p10, p11, p01);
  const auto exact = UllnerQuadParams<double>::precompute(p00, p10, p11, p01);
  ASSERT_TRUE(k && exact);
  std::array<std::uint32_t, kUllnerStoredWords> line{};
  store_words(*exact, line);
  const auto loaded = load_words(line);
  // The kernel's parameters are the words, widened: what the peripheral's fetch stage reads.
  for (std::size_t i = 0; i < kUllnerParamCount; ++i) {
    EXPECT_EQ(k->params.word[i], loaded.word[i]) << kUllnerParamNames[i];
    EXPECT_EQ(loaded.word[i], static_cast<double>(static_cast<float>(exact->word[i])));
  }
  EXPECT_EQ(loaded.u_parallel, exact->u_parallel);
  EXPECT_EQ(loaded.v_parallel, exact->v_parallel);
  EXPECT_EQ(loaded.u_plus_root, exact->u_plus_root);
  EXPECT_EQ(loaded.v_plus_root, exact->v_plus_root);
  EXPECT_EQ(loaded.u_pole_b, k->params.u_pole_b);
  // Storing again gives the same words (the rounding happens once).
  std::array<std::uint32_t, kUllnerStoredWords> again{};
  store_words(k->params, again);
  EXPECT_EQ(line, again);
  // Every decision comes from the words: flipping the branch flags changes the answer.
  const Ray ray{Vec3(1.0, 1.0, 5.0), Vec3(0, 0, -1)};
  SurfaceHit h, hc;
  ASSERT_TRUE(k->intersect_with(loaded, ray, 0.0, kInfinity, h));
  line[kUllnerFlagsWord] ^= kUllnerFlagUParallel | kUllnerFlagVParallel;
  const bool hit_corrupt = k->intersect_with(load_words(line), ray, 0.0, kInfinity, hc);
  EXPECT_TRUE(!hit_corrupt || hc.u != h.u || hc.v != h.v);
}

// The pipeline's 21-word description (seed 000 L717) holds what the peripheral's 25-word line
// holds, for every kind of quad the host prepares: quadratic families with either root,
// parallel families (trapezoids, parallelograms), triangles with each edge collapsed (a pencil
// and a deflated family), and near-triangles whose short edge is just too long to collapse.
TEST(UllnerDescriptionWords, TwentyOneWordsHoldWhatThePeripheralsLineHolds) {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> uni(-3.0, 3.0);
  std::vector<std::array<Vec3, 4>> quads;
  for (int i = 0; i < 400; ++i) {
    const Vec3 o(uni(rng), uni(rng), uni(rng));
    const Vec3 e1(1.0 + std::fabs(uni(rng)), 0.1 * uni(rng), 0.0);
    const Vec3 e2(0.2 * uni(rng), 1.0 + std::fabs(uni(rng)), 0.0);
    const double shrink = 0.2 + 0.25 * std::fabs(uni(rng));
    quads.push_back({o, o + e1, o + e1 + e2 + Vec3(0.1 * uni(rng), 0.1 * uni(rng), 0), o + e2});
    quads.push_back({o, o + e1, o + e1 + e2, o + e2});           // parallelogram
    quads.push_back({o, o + e1, o + e2 + shrink * e1, o + e2});  // trapezoid
    for (int c = 0; c < 4; ++c) {                                // triangles
      std::array<Vec3, 4> t = {o, o + e1, o + e1 + e2, o + e2};
      t[static_cast<std::size_t>((c + 1) % 4)] = t[static_cast<std::size_t>(c)];
      quads.push_back(t);
    }
    const double tiny = 1e-7 * (1.0 + std::fabs(uni(rng)));  // near-triangle
    quads.push_back({o, o + e1, o + e2 + (0.5 + tiny) * e1, o + e2 + (0.5 - tiny) * e1});
  }
  std::map<std::pair<int, int>, int> kinds;
  std::uint32_t identity = 0;
  for (const auto& q : quads) {
    const auto k = UllnerQuadKernel::from(q[0], q[1], q[2], q[3]);
    if (!k) continue;
    const UllnerQuadParams<double>& P = k->params;
    ++kinds[{static_cast<int>(P.u_family), static_cast<int>(P.v_family)}];
    // Only a pencil has thresholds.
    if (P.u_family != QuadFamily::Pencil) {
      EXPECT_EQ(P.u_pole_b + P.u_pole_c, 0.0);
    }
    if (P.v_family != QuadFamily::Pencil) {
      EXPECT_EQ(P.v_pole_b + P.v_pole_c, 0.0);
    }
    std::array<std::uint32_t, kUllnerStoredWords> line{};
    store_words(P, line);
    const UllnerQuadParams<double> want = load_words(line);
    std::array<std::uint32_t, kernels::kUllnerDescriptionWords> words{};
    identity = (identity * 2654435761u + 12345u) & kernels::kUllnerMaxIdentity;
    kernels::describe(P, identity, words);
    const kernels::UllnerDescribedPolygon got = kernels::read_description(words);
    EXPECT_EQ(got.identity, identity);
    for (std::size_t i = 0; i < kUllnerParamCount; ++i)
      ASSERT_EQ(got.params.word[i], want.word[i]) << kUllnerParamNames[i];
    ASSERT_EQ(got.params.u_parallel, want.u_parallel);
    ASSERT_EQ(got.params.v_parallel, want.v_parallel);
    ASSERT_EQ(got.params.u_plus_root, want.u_plus_root);
    ASSERT_EQ(got.params.v_plus_root, want.v_plus_root);
    ASSERT_EQ(got.params.u_pole_b, want.u_pole_b);
    ASSERT_EQ(got.params.u_pole_c, want.u_pole_c);
    ASSERT_EQ(got.params.v_pole_b, want.v_pole_b);
    ASSERT_EQ(got.params.v_pole_c, want.v_pole_c);
    // Any word decodes: a flipped family bit is another polygon, never a crash.
    for (unsigned bit = 0; bit < 32; ++bit) {
      auto bad = words;
      bad[kernels::kUllnerDescriptionIdWord] ^= 1u << bit;
      (void)kernels::read_description(bad);
    }
  }
  // Every kind was made: quadratic x quadratic, parallel forms, and both pencil-deflated pairs.
  const auto count = [&](QuadFamily u, QuadFamily v) {
    return kinds[{static_cast<int>(u), static_cast<int>(v)}];
  };
  EXPECT_GT(count(QuadFamily::Quadratic, QuadFamily::Quadratic), 0);
  EXPECT_GT(count(QuadFamily::Parallel, QuadFamily::Parallel), 0);
  EXPECT_GT(count(QuadFamily::Pencil, QuadFamily::Deflated), 0);
  EXPECT_GT(count(QuadFamily::Deflated, QuadFamily::Pencil), 0);
  EXPECT_GT(count(QuadFamily::Parallel, QuadFamily::Quadratic) +
                count(QuadFamily::Quadratic, QuadFamily::Parallel),
            0);
}

}  // namespace
}  // namespace rtsim
