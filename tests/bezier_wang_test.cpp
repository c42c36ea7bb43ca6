// Wang, Lewis & Hung's ray/Bezier-patch pipeline (firmware/kernels/bezier_wang*.hpp,
// bezier_patch_kernel.*): the subdivision identities, each functional block, the counters and
// costs, the kernel adapter, and the accuracy of the whole pipeline against the double reference
// solver on the Newell teapot (the paper's own benchmark, seed 002 L266, which printed no number).
#include "firmware/kernels/bezier_wang.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "firmware/kernels/bezier_patch_kernel.hpp"
#include "firmware/kernels/bezier_patch_math.hpp"
#include "firmware/kernels/bezier_reference.hpp"
#include "firmware/kernels/bezier_wang_blocks.hpp"
#include "firmware/kernels/culler_network.hpp"
#include "tests/bezier_teapot.hpp"

namespace rtsim::kernels {
namespace {

ControlNet<double> random_net(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> c(-2.0, 2.0);
  ControlNet<double> net;
  for (auto& row : net.p)
    for (auto& q : row) q = Vec3(c(rng), c(rng), c(rng));
  return net;
}

template <typename T>
double max_diff(const ControlNet<T>& a, const ControlNet<T>& b) {
  double m = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) m = std::max(m, max_abs_component(Vec3(a.p[i][j] - b.p[i][j])));
  return m;
}

// ---------------------------------------------------------------- subdivision identities

// The de Casteljau split must equal the paper's literal products D^{L|R} P D^{T|B} (eq. 11).
// Tolerance: the two orders of summation differ by a few roundings of values <= 2 (so ~1e-15 in
// double, ~1e-6 in float).
TEST(BezierPatchMath, SplitEqualsLiteralMatrixProducts) {
  std::mt19937_64 rng(1);
  for (int k = 0; k < 50; ++k) {
    const ControlNet<double> net = random_net(rng);
    ControlNet<double> quads[4];
    split4(net, quads);
    EXPECT_LT(max_diff(quads[kTL], right_multiply(left_multiply(kDL, net), kDT)), 1e-14);
    EXPECT_LT(max_diff(quads[kTR], right_multiply(left_multiply(kDR, net), kDT)), 1e-14);
    EXPECT_LT(max_diff(quads[kBL], right_multiply(left_multiply(kDL, net), kDB)), 1e-14);
    EXPECT_LT(max_diff(quads[kBR], right_multiply(left_multiply(kDR, net), kDB)), 1e-14);
    const ControlNet<float> netf = convert_net<float>(net);
    ControlNet<float> qf[4];
    split4(netf, qf);
    EXPECT_LT(max_diff(qf[kBR], right_multiply(left_multiply(kDR, netf), kDB)), 4e-6);
  }
  // D^T and D^B are the transposes of D^L and D^R (eq. 10).
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      EXPECT_EQ(kDT[r][c], kDL[c][r]);
      EXPECT_EQ(kDB[r][c], kDR[c][r]);
    }
}

// Each quadrant reproduces its quarter of the parent: Q_q(s, t) = Q((s + uh)/2, (t + vh)/2).
TEST(BezierPatchMath, FourSubpatchesReproduceTheParentSurface) {
  std::mt19937_64 rng(2);
  for (int k = 0; k < 20; ++k) {
    const ControlNet<double> net = random_net(rng);
    ControlNet<double> quads[4];
    split4(net, quads);
    const ControlNet<float> netf = convert_net<float>(net);
    ControlNet<float> qf[4];
    split4(netf, qf);
    for (int q = 0; q < 4; ++q)
      for (int i = 0; i <= 6; ++i)
        for (int j = 0; j <= 6; ++j) {
          const double s = i / 6.0, t = j / 6.0;
          const double u = (s + quadrant_u_half(q)) / 2, v = (t + quadrant_v_half(q)) / 2;
          const Vec3 parent = evaluate(net, u, v);
          EXPECT_LT(max_abs_component(evaluate(quads[q], s, t) - parent), 1e-14);
          EXPECT_LT(max_abs_component(Vec3(evaluate(qf[q], float(s), float(t))) - parent), 1e-5);
        }
  }
}

// Eq. 18's weights (1/64)[1 3 3 1] P [1 3 3 1]^t evaluate Q(1/2, 1/2) (eq. 17).
TEST(BezierPatchMath, CentreFormulaIsQHalfHalf) {
  std::mt19937_64 rng(3);
  for (int k = 0; k < 50; ++k) {
    const ControlNet<double> net = random_net(rng);
    EXPECT_LT(max_abs_component(parametric_center(net) - evaluate(net, 0.5, 0.5)), 1e-14);
    EXPECT_LT(max_abs_component(PatchCenter::center(net) - evaluate(net, 0.5, 0.5)), 1e-14);
  }
}

// scenes::BezierPatch (row i = v, column j = u) is transposed into the eq.-4 orientation.
TEST(BezierPatchMath, SceneOrientationPutsUAlongARow) {
  scenes::BezierPatch patch;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) patch.control[static_cast<std::size_t>(4 * i + j)] = Vec3(j, i, 0);
  const ControlNet<double> net = control_net_from(patch);
  const Vec3 q = evaluate(net, 0.25, 0.75);  // x = 3u, y = 3v
  EXPECT_NEAR(q.x, 0.75, 1e-15);
  EXPECT_NEAR(q.y, 2.25, 1e-15);
  Vec3 n;
  ASSERT_TRUE(patch_normal(net, 0.3, 0.4, n));
  EXPECT_NEAR(n.z, 1.0, 1e-15);  // Q_u x Q_v = x x y = +z
}

// ---------------------------------------------------------------- the functional blocks

TEST(WangBlocks, PlaneGeneratorPlanesArePerpendicularAndContainTheRay) {
  std::mt19937_64 rng(4);
  std::normal_distribution<double> g;
  std::vector<Vec3> dirs = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {1, 1, 1}};
  for (int k = 0; k < 200; ++k) dirs.push_back(Vec3(g(rng), g(rng), g(rng)));
  for (Vec3 d : dirs) {
    d = glm::normalize(d);
    const Vec3 o(g(rng), g(rng), g(rng));
    const RayPlanes<double> pl = PlaneGenerator::generate(o, d);
    EXPECT_NEAR(glm::dot(pl.n_u, d), 0.0, 1e-15);
    EXPECT_NEAR(glm::dot(pl.n_v, d), 0.0, 1e-15);
    EXPECT_NEAR(glm::dot(pl.n_u, pl.n_v), 0.0, 1e-15);
    // |N_u| = sqrt(1 - D_xi^2) >= sqrt(2/3) since |D_xi| is the smallest component
    EXPECT_GE(glm::length(pl.n_u), std::sqrt(2.0 / 3.0) - 1e-15);
    for (double t : {0.0, 1.0, 7.5}) {  // O + tD on both planes (E = -N.O)
      EXPECT_NEAR(glm::dot(pl.n_u, o + t * d) + pl.e_u, 0.0, 1e-13);
      EXPECT_NEAR(glm::dot(pl.n_v, o + t * d) + pl.e_v, 0.0, 1e-13);
    }
  }
  // D = +z: xi = x (first of the tied smallest), N_u = e_x x D = (0, -1, 0)
  const RayPlanes<double> pz = PlaneGenerator::generate(Vec3(0.0), Vec3(0, 0, 1));
  EXPECT_EQ(pz.n_u, Vec3(0, -1, 0));
  EXPECT_EQ(pz.n_v, Vec3(-1, 0, 0));
}

ControlNet<double> flat_net(double x0, double x1, double y0, double y1, double z) {
  ControlNet<double> net;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      net.p[a][b] = Vec3(x0 + (x1 - x0) * a / 3, y0 + (y1 - y0) * b / 3, z);
  return net;
}

TEST(WangBlocks, HullClassificationSgnsumAndTieRule) {
  // ray along +z through the origin: plane U is -y = 0, plane V is -x = 0
  const RayPlanes<double> pl = PlaneGenerator::generate(Vec3(0.0), Vec3(0, 0, 1));
  // straddles both planes: may hit
  HullClass h = HullClassification::classify(pl, flat_net(-1, 1, -1, 1, 5));
  EXPECT_TRUE(h.may_hit);
  EXPECT_EQ(h.sgnsum_u, 0);  // 8 points with -y >= 0, 8 with -y < 0
  EXPECT_EQ(h.sgnsum_v, 0);
  // entirely at x > 0: all 16 on the negative side of V (-x < 0): reject
  h = HullClassification::classify(pl, flat_net(0.5, 2, -1, 1, 5));
  EXPECT_FALSE(h.may_hit);
  EXPECT_EQ(h.sgnsum_v, -16);
  // y in [-1, 0]: the row at y = 0 lies ON plane U and counts as positive (L181, eq. 16), the
  // others have -y > 0: Sgnsum_u = +16, so a ray grazing the patch's edge is rejected.
  h = HullClassification::classify(pl, flat_net(-1, 1, -1, 0, 5));
  EXPECT_EQ(h.sgnsum_u, 16);
  EXPECT_FALSE(h.may_hit);
  // y in [0, 1]: the y = 0 row is "positive", the rest negative: 4 - 12 = -8, may hit
  h = HullClassification::classify(pl, flat_net(-1, 1, 0, 1, 5));
  EXPECT_EQ(h.sgnsum_u, -8);
  EXPECT_TRUE(h.may_hit);
}

TEST(WangBlocks, PatchDistanceIsManhattanOrBehindFlag) {
  const Vec3 o(1, 2, 3), d = glm::normalize(Vec3(1, 1, 0));
  EXPECT_DOUBLE_EQ(PatchDistance::distance(o, d, Vec3(3, 1, 5)), 2.0 + 1.0 + 2.0);  // eq. 20
  EXPECT_DOUBLE_EQ(PatchDistance::distance(o, d, Vec3(0, 0, 3)), PatchDistance::kBehind);
  // (C - O).D = 0 exactly counts as in front (eq. 21's >=)
  EXPECT_DOUBLE_EQ(PatchDistance::distance(o, d, Vec3(2, 1, 3)), 2.0);
  EXPECT_FLOAT_EQ(PatchDistance::distance(Vec3T<float>(o), Vec3T<float>(d), Vec3T<float>(3, 1, 5)),
                  5.0f);
}

TEST(WangBlocks, CullerKeepsTheFourNearestValidKeys) {
  std::array<float, 16> keys;
  keys.fill(-1.0f);
  std::array<int, 4> out{};
  EXPECT_EQ(Culler::select(keys, out), 0);  // all flagged: null result
  keys[3] = 5.0f;
  keys[9] = 0.0f;
  EXPECT_EQ(Culler::select(keys, out), 2);
  EXPECT_EQ(out[0], 9);
  EXPECT_EQ(out[1], 3);
  const std::array<double, 16> many = {7, -1, 3, 3, 9, 0.5, -1, 8, 2, 3, 1, -1, 6, 4, 10, 3};
  std::array<int, 4> o2{};
  ASSERT_EQ(Culler::select(many, o2), 4);
  EXPECT_EQ(o2[0], 5);   // 0.5
  EXPECT_EQ(o2[1], 10);  // 1
  EXPECT_EQ(o2[2], 8);   // 2
  EXPECT_EQ(o2[3], 2);   // 3, the lowest index of the four tied 3s
  std::array<double, 16> with_nan = many;
  with_nan[5] = std::nan("");  // never kept
  ASSERT_EQ(Culler::select(with_nan, o2), 4);
  EXPECT_EQ(o2[0], 10);
}

// The Culler ASIC (L302-L318): a 16-input bitonic network, 10 stages, on tagged keys. Its
// outputs are those of the software's selection sort at every key width (both sort the same
// total order), on random keys with ties, zeros, flagged and NaN candidates; fewer key bits
// change which four are kept.
TEST(CullerNetwork, KeepsWhatTheSelectionSortKeepsAtEveryKeyWidth) {
  EXPECT_EQ(rtsim::kernels::CullerNetwork::kStages, 10);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> near(1.0f, 1.001f);  // close distances: deep subpatches
  std::uniform_int_distribution<int> kind(0, 9);
  for (const int bits : {36, 24, 12, 5}) {
    int differs_from_exact = 0;
    for (int trial = 0; trial < 20000; ++trial) {
      std::array<float, 16> keys;
      for (auto& k : keys) {
        const int c = kind(rng);
        k = c == 0 ? -1.0f : c == 1 ? std::nanf("") : c == 2 ? 0.0f : c == 3 ? 1.0f : near(rng);
      }
      std::array<int, 4> net{}, sel{}, exact{};
      const int n = rtsim::kernels::CullerNetwork::select(keys, net, bits);
      ASSERT_EQ(n, Culler::select(keys, sel, bits)) << bits;
      for (int i = 0; i < n; ++i) ASSERT_EQ(net[i], sel[i]) << bits << " trial " << trial;
      Culler::select(keys, exact);
      if (!std::equal(net.begin(), net.begin() + n, exact.begin())) ++differs_from_exact;
    }
    std::printf("%2d-bit keys: %d of 20000 sets keep other candidates than 36-bit keys\n", bits,
                differs_from_exact);
    if (bits == 36) {
      EXPECT_EQ(differs_from_exact, 0);
    }
    if (bits <= 12) {
      EXPECT_GT(differs_from_exact, 0);
    }
  }
}

// ---------------------------------------------------------------- the loop, counters, cost

TEST(WangLoop, CountersFollowTheBuffersAndCostAddsUp) {
  const ControlNet<double> net = flat_net(-1, 1, -1, 1, 5);
  WangCounters c;
  const auto hit = wang_intersect(net, Vec3(0.1, 0.2, 0), Vec3(0, 0, 1), 10, &c);
  ASSERT_TRUE(hit.hit);
  EXPECT_EQ(c.calls, 1u);
  EXPECT_EQ(c.iterations, 10u);
  EXPECT_EQ(c.culls, 10u);
  // stage 0 splits once; each iteration splits every buffer1 patch and classifies its children
  EXPECT_EQ(c.hull_tests, 4 * (c.subdivisions - 1));
  EXPECT_LE(c.subdivisions, 1u + 10u * 4u);
  EXPECT_EQ(hit.level, 11u);
  EXPECT_NEAR(hit.point.z, 5.0, 1e-15);
  EXPECT_NEAR(hit.point.x, 0.1, 2.0 / 2048);  // one final subpatch is 2/2048 wide
  EXPECT_NEAR(hit.point.y, 0.2, 2.0 / 2048);
  EXPECT_NEAR(hit.u, 0.55, 1.5 / 2048);  // the centre of the final subpatch or a neighbour's
  EXPECT_NEAR(hit.v, 0.6, 1.5 / 2048);

  // a miss ends as soon as buffer1 is empty
  WangCounters m;
  EXPECT_FALSE(wang_intersect(net, Vec3(3, 0, 0), Vec3(0, 0, 1), 10, &m).hit);
  EXPECT_EQ(m.iterations, 1u);
  EXPECT_EQ(m.subdivisions, 5u);
  EXPECT_EQ(m.hull_tests, 16u);
  // behind the origin: every key is flagged
  EXPECT_FALSE(wang_intersect(net, Vec3(0, 0, 6), Vec3(0, 0, 1), 10).hit);

  // cost: the counted work, and the data-independent pipeline figure (stage 0 + 10 full stages)
  const Cost miss_cost = wang_cost(m);
  EXPECT_EQ(miss_cost.fp_mul, PlaneGenerator::kCost.fp_mul + 5 * PatchSubdivider::kCost.fp_mul +
                                  16 * (HullClassification::kCost.fp_mul +
                                        PatchCenter::kCost.fp_mul + PatchDistance::kCost.fp_mul) +
                                  Culler::kCost.fp_mul);
  const Cost full = wang_pipeline_cost(10);
  EXPECT_EQ(full.fp_add, kWangStage0Cost.fp_add + 10 * kWangLoopStageCost.fp_add);
  EXPECT_EQ(BezierPatchKernel::kTestCost.fp_ops(), full.fp_ops());
  EXPECT_GE(full.fp_ops(), wang_cost(c).fp_ops());  // the software never does more than the pipe
  std::printf("pipeline cost, 10 stages: %llu fp add, %llu fp mul, %llu words, %llu instr\n",
              (unsigned long long)full.fp_add, (unsigned long long)full.fp_mul,
              (unsigned long long)full.mem_words, (unsigned long long)full.instructions);
}

// Fixed-point words (bezier.arithmetic = fixed): rounded to the nearest 2^-(bits - integer
// bits), ties to even, saturating at the two's complement range; NaN stores as 0. On a flat
// patch 24-bit words (16 below the point) still find the hit within a final subpatch; 10-bit
// words (2 below the point) cannot tell the subpatches apart.
TEST(WangArithmetic, FixedWordsRoundAndSaturate) {
  const FixedWords w{.bits = 12, .integer_bits = 4};  // 8 fraction bits, range [-8, 8)
  EXPECT_EQ(w(0.1), std::round(0.1 * 256) / 256);
  EXPECT_EQ(w(1.0 / 512), 0.0);        // a half step: ties to even
  EXPECT_EQ(w(3.0 / 512), 2.0 / 256);  // 1.5 steps: to 2
  EXPECT_EQ(w(100.0), 8.0 - 1.0 / 256);
  EXPECT_EQ(w(-100.0), -8.0);
  EXPECT_EQ(w(std::nan("")), 0.0);
  EXPECT_EQ(w(-kInfinity), -8.0);
  const FixedWords exact{.bits = 53, .integer_bits = 8};
  EXPECT_EQ(exact(0.1), std::ldexp(std::round(std::ldexp(0.1, 45)), -45));

  const ControlNet<double> net = flat_net(-1, 1, -1, 1, 5);
  const FixedWords wide{.bits = 24, .integer_bits = 8};
  const auto hit = wang_intersect(net, Vec3(0.1, 0.2, 0), Vec3(0, 0, 1), 10, nullptr, {}, &wide);
  ASSERT_TRUE(hit.hit);
  EXPECT_NEAR(hit.point.x, 0.1, 2.0 / 2048);
  EXPECT_NEAR(hit.point.y, 0.2, 2.0 / 2048);
  const auto exact_hit = wang_intersect(net, Vec3(0.1, 0.2, 0), Vec3(0, 0, 1), 10);
  EXPECT_EQ(hit.u, exact_hit.u);  // 2^-16 is far below the final subpatch (2^-10 here)
  const FixedWords narrow{.bits = 10, .integer_bits = 8};
  const auto coarse =
      wang_intersect(net, Vec3(0.1, 0.2, 0), Vec3(0, 0, 1), 10, nullptr, {}, &narrow);
  EXPECT_TRUE(!coarse.hit || std::abs(coarse.point.x - 0.1) > 2.0 / 2048 ||
              std::abs(coarse.point.y - 0.2) > 2.0 / 2048);
}

// ---------------------------------------------------------------- the kernel adapter

scenes::BezierPatch scene_patch(const ControlNet<double>& net) {
  scenes::BezierPatch p;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) p.control[static_cast<std::size_t>(4 * b + a)] = net.p[a][b];
  return p;
}

TEST(BezierPatchKernel, FlatPatchConventionsAndBadInput) {
  const auto patch = scene_patch(flat_net(-1, 1, -1, 1, 5));
  const auto k = BezierPatchKernel::from(patch);
  EXPECT_EQ(k.iterations(), 10);
  EXPECT_EQ(k.bounds().lo, Vec3(-1, -1, 5));
  EXPECT_EQ(k.bounds().hi, Vec3(1, 1, 5));
  SurfaceHit hit;
  const Ray ray{Vec3(0.1, 0.2, 0), Vec3(0, 0, 1)};
  ASSERT_TRUE(k.intersect(ray, 0.0, kInfinity, hit));
  EXPECT_NEAR(hit.t, 5.0, 1e-6);  // a flat patch: the centre is on the plane (float rounding)
  EXPECT_NEAR(hit.u, 0.55, 1.5 / 2048);
  EXPECT_NEAR(hit.v, 0.6, 1.5 / 2048);
  EXPECT_NEAR(hit.geometric_normal.z, 1.0, 1e-12);
  EXPECT_EQ(hit.geometric_normal, hit.shading_normal);
  // [t_min, t_max]
  EXPECT_FALSE(k.intersect(ray, 0.0, 4.9, hit));
  EXPECT_FALSE(k.intersect(ray, 5.1, kInfinity, hit));
  ASSERT_TRUE(k.intersect(ray, 4.9, 5.1, hit));
  EXPECT_NEAR(hit.t, 5.0, 1e-6);
  EXPECT_FALSE(k.intersect(Ray{ray.origin, -ray.direction}, 0.0, kInfinity, hit));
  EXPECT_FALSE(k.intersect(Ray{Vec3(1.5, 0, 0), ray.direction}, 0.0, kInfinity, hit));
  // bad input never hits, never produces NaN
  EXPECT_FALSE(k.intersect(Ray{Vec3(std::nan(""), 0, 0), ray.direction}, 0, kInfinity, hit));
  EXPECT_FALSE(k.intersect(Ray{ray.origin, Vec3(0.0)}, 0, kInfinity, hit));
  EXPECT_FALSE(k.intersect(ray, 1.0, 0.5, hit));
  auto bad = patch;
  bad.control[7].x = std::nan("");
  EXPECT_FALSE(BezierPatchKernel::from(bad).intersect(ray, 0, kInfinity, hit));
  auto huge = patch;
  huge.control[7].x = 1e300;  // finite in double, infinite in the float pipeline
  EXPECT_FALSE(BezierPatchKernel::from(huge).intersect(ray, 0, kInfinity, hit));
  EXPECT_THROW(BezierPatchKernel::from(patch, 0), std::invalid_argument);
  EXPECT_THROW(BezierPatchKernel::from(patch, kWangMaxIterations + 1), std::invalid_argument);
  // iterations set the resolution: 2^-(n+1) of the parameter range
  const auto k4 = BezierPatchKernelDouble::from(patch, 4);
  ASSERT_TRUE(k4.intersect(ray, 0.0, kInfinity, hit));
  EXPECT_NEAR(hit.u, 0.55, 1.0 / 32);
  EXPECT_DOUBLE_EQ(std::fmod(hit.u * 32 - 0.5, 1.0), 0.0);  // a level-5 subpatch centre
}

// ---------------------------------------------------------------- accuracy on the teapot

struct Teapot {
  std::vector<ControlNet<double>> nets;
  std::vector<ControlNet<float>> nets_f;
  std::vector<Bounds> boxes;
  double size = 0;          ///< diagonal of the teapot's box
  double patch_extent = 0;  ///< largest patch box diagonal
  Teapot() {
    const auto patches = bezier_test::teapot();
    for (const auto& p : patches) {
      nets.push_back(control_net_from(p));
      nets_f.push_back(convert_net<float>(nets.back()));
      boxes.push_back(control_bounds(nets.back()));
      patch_extent = std::max(patch_extent, glm::length(boxes.back().extent()));
    }
    size = glm::length(bezier_test::patches_bounds(patches).extent());
  }
};

struct NearestHit {
  bool hit = false;
  double t = kInfinity;
  Vec3 point{0.0};
  int patch = -1;
};

NearestHit reference_nearest(const Teapot& tp, const Ray& ray) {
  NearestHit best;
  for (std::size_t i = 0; i < tp.nets.size(); ++i) {
    double t0, t1;
    if (!tp.boxes[i].intersect(ray, 0.0, best.t, t0, t1)) continue;  // exact: hull property
    SurfaceHit h;
    if (reference_intersect(tp.nets[i], ray, 0.0, best.t, h) && h.t < best.t) {
      best = {true, h.t, ray.at(h.t), static_cast<int>(i)};
    }
  }
  return best;
}

/// Wang's pipeline on every patch whose box, grown by 5% of its size, the ray meets (a final
/// subpatch that passes the hull test lies within one subpatch width, < 2^-5 of the patch for
/// n >= 4 iterations, of the ray), nearest by t = (C - O).D.
template <typename T>
NearestHit wang_nearest(const Teapot& tp, const Ray& ray, int iterations, WangCounters* c) {
  NearestHit best;
  for (std::size_t i = 0; i < tp.nets.size(); ++i) {
    Bounds grown = tp.boxes[i];
    const Vec3 m(0.05 * glm::length(grown.extent()));
    grown.lo -= m;
    grown.hi += m;
    double t0, t1;
    if (!grown.intersect(ray, 0.0, kInfinity, t0, t1)) continue;
    ControlNet<T> net;
    if constexpr (std::is_same_v<T, float>)
      net = tp.nets_f[i];
    else
      net = tp.nets[i];
    const auto r =
        wang_intersect<T>(net, Vec3T<T>(ray.origin), Vec3T<T>(ray.direction), iterations, c);
    if (!r.hit) continue;
    const Vec3 p(r.point);
    const double t = glm::dot(p - ray.origin, ray.direction);
    if (t < best.t) best = {true, t, p, static_cast<int>(i)};
  }
  return best;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
  return v[std::min(k, v.size() - 1)];
}

struct Comparison {
  int rays = 0, both = 0, neither = 0, wang_only = 0, ref_only = 0, gross = 0;
  double median = 0, p99 = 0, max = 0;  ///< position error / teapot size, rays both hit
  double t_median = 0;
  std::vector<int> disagreeing;  ///< ray indices: hit/miss differs or gross position error
  WangCounters counters;
};

/// The views: from the front-left-above (body, spout, handle, lid) and from low at the side.
const Vec3 kViews[] = {Vec3(-0.55, -1.0, 0.6), Vec3(1.0, 0.35, 0.15)};
constexpr int kPixels = 128;  ///< per view: 2 x 128 x 128 = 32768 rays
constexpr double kZoom =
    1.5;  ///< the teapot is flat: crop the empty corners of its bounding sphere

template <typename T>
Comparison compare(const Teapot& tp, const std::vector<Ray>& rays,
                   const std::vector<NearestHit>& ref, int iterations) {
  Comparison c;
  std::vector<double> err, terr;
  for (std::size_t k = 0; k < rays.size(); ++k) {
    const NearestHit w = wang_nearest<T>(tp, rays[k], iterations, &c.counters);
    ++c.rays;
    if (w.hit && ref[k].hit) {
      ++c.both;
      const double e = glm::length(w.point - ref[k].point) / tp.size;
      err.push_back(e);
      terr.push_back(std::fabs(w.t - ref[k].t) / tp.size);
      // "gross": further than 8 final subpatch widths: another surface, not a rounding of this one
      if (e * tp.size > 8.0 * tp.patch_extent * std::ldexp(1.0, -(iterations + 1))) {
        ++c.gross;
        c.disagreeing.push_back(static_cast<int>(k));
      }
    } else if (w.hit) {
      ++c.wang_only;
      c.disagreeing.push_back(static_cast<int>(k));
    } else if (ref[k].hit) {
      ++c.ref_only;
      c.disagreeing.push_back(static_cast<int>(k));
    } else {
      ++c.neither;
    }
  }
  c.median = quantile(err, 0.5);
  c.p99 = quantile(err, 0.99);
  c.max = quantile(err, 1.0);
  c.t_median = quantile(terr, 0.5);
  return c;
}

/// How far is this ray from a place where the reference's answer changes: hit vs miss (a
/// silhouette or an open edge), or a jump in depth (one surface in front of another)? The
/// smallest delta = size * 2^-k (k = 20 .. 4) at which one of 8 rays offset by delta (parallel,
/// in the image plane) differs; infinity if none. A depth jump is |dt| > 8 delta + 0.5% of the
/// teapot: on one continuous surface |dt| ~ delta tan(incidence), so only a surface seen at more
/// than ~83 degrees (itself next to a silhouette) passes for an edge.
double distance_to_edge(const Teapot& tp, const Ray& ray, const NearestHit& here,
                        const bezier_test::FramingCamera& cam) {
  for (int k = 20; k >= 4; --k) {
    const double delta = tp.size * std::ldexp(1.0, -k);
    for (int a = 0; a < 8; ++a) {
      const double th = a * kPi / 4;
      const Ray nb{ray.origin + delta * (std::cos(th) * cam.right + std::sin(th) * cam.up),
                   ray.direction};
      const NearestHit h = reference_nearest(tp, nb);
      if (h.hit != here.hit || (h.hit && std::fabs(h.t - here.t) > 8.0 * delta + 0.005 * tp.size))
        return delta;
    }
  }
  return kInfinity;
}

/// "Near an edge": within this distance (fraction of the teapot size) of a reference edge.
/// The Culler loses the true subpatch when more than N_i = 4 candidates pass the hull test and the
/// nearer ones (by Manhattan centre distance) are phantoms (note 002 §2.7). The hull test is a
/// box in the ray's (N_u, N_v) frame (eq. 16), loose around a subpatch, so this happens
/// (a) where the ray passes within a few subpatch widths of the surface without hitting it, at
/// the stage where that happens (typically 5-8: subpatches of 2^-6..2^-9 of a patch, a patch
/// being up to 0.39 of the teapot), so within ~2^-5 of the teapot of an edge; and (b) on
/// slivers: where the parametrisation is very anisotropic (the rim's lip, 7:1; the lid-knob
/// and bottom poles) a tilted sliver's box covers several neighbours, anywhere on the patch.
constexpr double kEdgeDistance = 1.0 / 32;

TEST(WangAccuracy, TeapotAgainstReferenceSolver) {
  const Teapot tp;
  ASSERT_EQ(tp.nets.size(), 32u);
  std::vector<Ray> rays;
  std::vector<bezier_test::FramingCamera> cams;
  for (const Vec3& dir : kViews) {
    Bounds box;
    for (const auto& b : tp.boxes) box.extend(b);
    cams.emplace_back(box, dir, kPixels, 2.0, kZoom);
    for (int j = 0; j < kPixels; ++j)
      for (int i = 0; i < kPixels; ++i) rays.push_back(cams.back().ray(i, j));
  }
  auto cam_of = [&](std::size_t k) -> const bezier_test::FramingCamera& {
    return cams[k / (kPixels * kPixels)];
  };
  std::vector<NearestHit> ref;
  std::vector<std::size_t> hit_rays;
  for (const Ray& r : rays) {
    ref.push_back(reference_nearest(tp, r));
    if (ref.back().hit) hit_rays.push_back(ref.size() - 1);
  }
  const int ref_hits = static_cast<int>(hit_rays.size());
  // Baseline: how close to an edge is a typical hit ray? (every 25th hit ray)
  std::vector<double> baseline;
  for (std::size_t s = 0; s < hit_rays.size(); s += 25) {
    const std::size_t k = hit_rays[s];
    baseline.push_back(distance_to_edge(tp, rays[k], ref[k], cam_of(k)) / tp.size);
  }
  const double baseline_near =
      static_cast<double>(std::count_if(baseline.begin(), baseline.end(),
                                        [](double d) { return d <= kEdgeDistance; })) /
      static_cast<double>(baseline.size());
  std::printf(
      "teapot: size (box diagonal) %.3f, largest patch %.3f; %zu rays from %zu views, %d hit "
      "(reference); of a sample of %zu hit rays, %.0f%% lie within %.4f x size of a silhouette "
      "or depth edge (median distance %.2e x size)\n",
      tp.size, tp.patch_extent, rays.size(), std::size(kViews), ref_hits, baseline.size(),
      100.0 * baseline_near, kEdgeDistance, quantile(baseline, 0.5));
  std::printf(
      "errors are |Wang point - reference point| / teapot size over rays both hit;\n"
      "'subpatch' is the largest patch's final subpatch width / teapot size\n");
  std::printf("%5s %6s %9s %9s %6s %10s %9s %9s %9s %9s %9s\n", "iter", "prec", "wang-only",
              "ref-only", "gross", "disagree%", "median", "p99", "max", "t-median", "subpatch");
  const int sweep[] = {4, 6, 8, 10, 12};
  std::vector<Comparison> by_prec[2];
  for (int n : sweep) {
    for (int prec = 0; prec < 2; ++prec) {
      Comparison c =
          prec == 0 ? compare<float>(tp, rays, ref, n) : compare<double>(tp, rays, ref, n);
      std::printf("%5d %6s %9d %9d %6d %9.3f%% %9.2e %9.2e %9.2e %9.2e %9.2e\n", n,
                  prec ? "double" : "float", c.wang_only, c.ref_only, c.gross,
                  100.0 * static_cast<double>(c.disagreeing.size()) / c.rays, c.median, c.p99,
                  c.max, c.t_median, tp.patch_extent * std::ldexp(1.0, -(n + 1)) / tp.size);
      by_prec[prec].push_back(std::move(c));
    }
  }
  for (int prec = 0; prec < 2; ++prec) {
    const auto& cs = by_prec[prec];
    for (std::size_t s = 0; s < cs.size(); ++s) {
      const int n = sweep[s];
      const double width = tp.patch_extent * std::ldexp(1.0, -(n + 1)) / tp.size;
      // The centre of a final subpatch that contains the hit is within half its diagonal of it;
      // the Culler may pick a neighbour one width away. Measured: median 0.27, p99 1.4-1.6 widths.
      EXPECT_LT(cs[s].median, 0.5 * width) << n << " iterations";
      EXPECT_LT(cs[s].p99, 3.0 * width) << n << " iterations";
      // Each iteration halves the subpatch, so two iterations divide the error by ~4.
      if (s > 0) {
        const double ratio = cs[s - 1].median / cs[s].median;
        EXPECT_GT(ratio, 3.0) << n << " iterations";
        EXPECT_LT(ratio, 5.0) << n << " iterations";
      }
    }
  }
  // IEEE single (the paper's DSPs, seed 002 L296) costs nothing measurable here: float rounding
  // (~1e-7 of the coordinates) is far below the 2^-13 subpatch at 12 iterations.
  for (std::size_t s = 0; s < by_prec[0].size(); ++s) {
    EXPECT_NEAR(by_prec[0][s].median, by_prec[1][s].median, 0.02 * by_prec[1][s].median);
    EXPECT_NEAR(static_cast<double>(by_prec[0][s].disagreeing.size()),
                static_cast<double>(by_prec[1][s].disagreeing.size()),
                2.0 + 0.05 * static_cast<double>(by_prec[1][s].disagreeing.size()));
  }
  // At the hardware's 10 stages: disagreements are rare and mostly close to reference edges.
  ASSERT_EQ(sweep[3], 10);
  for (int prec = 0; prec < 2; ++prec) {
    const Comparison& c = by_prec[prec][3];
    std::vector<double> dist;
    for (int k : c.disagreeing) {
      const auto kk = static_cast<std::size_t>(k);
      dist.push_back(distance_to_edge(tp, rays[kk], ref[kk], cam_of(kk)) / tp.size);
    }
    const auto near = static_cast<int>(
        std::count_if(dist.begin(), dist.end(), [](double d) { return d <= kEdgeDistance; }));
    const int away = static_cast<int>(dist.size()) - near;
    std::printf(
        "10 iterations %s: %zu disagreements (%.2f%% of reference hits; %d missed, %d phantom, "
        "%d on another surface); distance to a reference edge / size: median %.2e; %d (%.0f%%) "
        "within %.4f, %d away from edges (%.3f%% of hits)\n",
        prec ? "double" : "float", c.disagreeing.size(),
        100.0 * static_cast<double>(c.disagreeing.size()) / ref_hits, c.ref_only, c.wang_only,
        c.gross, quantile(dist, 0.5), near, 100.0 * near / static_cast<double>(dist.size()),
        kEdgeDistance, away, 100.0 * away / ref_hits);
    // Measured 1.2% of hits; the bound leaves room for another view, not for a bug.
    EXPECT_LT(static_cast<double>(c.disagreeing.size()), 0.02 * ref_hits);
    // Concentrated at edges: measured 94% of the disagreements within kEdgeDistance of an edge,
    // against 35% of all hit rays. The rest are the sliver case (see kEdgeDistance): measured
    // 0.06% of hits.
    EXPECT_GE(near, 0.85 * static_cast<double>(dist.size()));
    EXPECT_LT(away, 0.002 * ref_hits);
    // Phantom hits (the hull passes, the patch is missed) die out by 10 stages (measured 0).
    EXPECT_LE(c.wang_only, ref_hits / 1000);
  }
}

}  // namespace
}  // namespace rtsim::kernels
