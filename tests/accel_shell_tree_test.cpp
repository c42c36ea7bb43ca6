// Gaudet's box-shell hierarchy (seed 001 §4.1-4.5, §5.3, §6.1.2): Fig. 6-1 counts for the npp
// scenes, tree invariants, the ShellTask/PrimTask search against brute force, the leaf-shell
// stop rule, the 50-entry LeafShellList, and the three broadcast memory images.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <vector>

#include "firmware/accel/gaudet_data_sets.hpp"
#include "firmware/accel/primitive_bounds.hpp"
#include "firmware/accel/shell_traversal.hpp"
#include "firmware/accel/shell_tree.hpp"
#include "firmware/scene.hpp"
#include "tests/kernel_test_support.hpp"

namespace rtsim::accel {
namespace {

/// An npp-like scene: 64 clusters of pp randomly placed spheres (seed 001 L970), cluster
/// centres random in a 20-unit cube, spheres within 1.5 units of their centre.
scenes::Scene cluster_scene(int pp, std::uint64_t seed, int clusters = 64) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), rad(0.2, 0.6);
  scenes::Scene s;
  s.name = "test:clusters";
  s.materials = {scenes::Material{},
                 scenes::Material{Color(0.8, 0.2, 0.1), 0.7, 0.3, 20.0, 0.0, 1.0}};
  for (int c = 0; c < clusters; ++c) {
    const Vec3 centre(10.0 * u(rng), 10.0 * u(rng), 10.0 * u(rng));
    for (int i = 0; i < pp; ++i) {
      scenes::Sphere sp{centre + 1.5 * Vec3(u(rng), u(rng), u(rng)), rad(rng)};
      s.primitives.push_back({scenes::PrimitiveKind::Sphere,
                              static_cast<std::uint32_t>(s.spheres.size()),
                              static_cast<std::uint32_t>(i % 2), 0});
      s.spheres.push_back(sp);
      s.cluster_of_primitive.push_back(static_cast<std::uint32_t>(c));
    }
  }
  return s;
}

bool encloses(const Bounds& outer, const Bounds& inner) {
  return outer.lo.x <= inner.lo.x && outer.lo.y <= inner.lo.y && outer.lo.z <= inner.lo.z &&
         outer.hi.x >= inner.hi.x && outer.hi.y >= inner.hi.y && outer.hi.z >= inner.hi.z;
}

/// Structural invariants every tree must satisfy.
void check_tree(const ShellTree& t, std::span<const Bounds> bounds, int branching,
                int max_leaf = 0) {
  ASSERT_GE(t.shell_packet_count(), 1u);
  std::vector<int> packet_refs(t.shell_packet_count(), 0), prim_refs(t.prim_packet_count(), 0);
  packet_refs[0] = 1;  // the root's children
  for (std::size_t i = 0; i < t.shell_packet_count(); ++i) {
    EXPECT_LE(t.shell_packet(i).size(), static_cast<std::size_t>(branching));
    for (const Shell& s : t.shell_packet(i)) {
      EXPECT_TRUE(encloses(t.scene_shell(), s.box));
      if (s.leaf) {
        ASSERT_LT(s.child_index, t.prim_packet_count());
        ++prim_refs[s.child_index];
        for (const std::uint32_t p : t.prim_packet(s.child_index))
          EXPECT_TRUE(encloses(s.box, bounds[p]));
        if (max_leaf > 0) {
          EXPECT_LE(t.prim_packet(s.child_index).size(), std::size_t(max_leaf));
        }
      } else {
        ASSERT_LT(s.child_index, t.shell_packet_count());
        EXPECT_GT(s.child_index, i);  // breadth-first numbering
        ++packet_refs[s.child_index];
        for (const Shell& c : t.shell_packet(s.child_index)) EXPECT_TRUE(encloses(s.box, c.box));
      }
    }
  }
  for (const int r : packet_refs) EXPECT_EQ(r, 1);
  for (const int r : prim_refs) EXPECT_EQ(r, 1);
  std::vector<int> seen(bounds.size(), 0);
  for (std::size_t j = 0; j < t.prim_packet_count(); ++j)
    for (const std::uint32_t p : t.prim_packet(j)) ++seen[p];
  for (const int s : seen) EXPECT_EQ(s, 1);
}

TEST(AccelShellTree, Fig61CountsForTheNppScenes) {
  // Fig. 6-1 (seed 001 L980-L989): shells (without the root) / shell packets (with the root's)
  // / primitives / primitive packets.
  struct Row {
    int scene, b, pp;
    ShellTreeCounts expect;
  };
  const Row rows[] = {{204, 2, 4, {126, 63, 256, 64}},
                      {408, 4, 8, {84, 21, 512, 64}},
                      {812, 8, 12, {72, 9, 768, 64}},
                      {816, 8, 16, {72, 9, 1024, 64}},
                      {820, 8, 20, {72, 9, 1280, 64}}};
  std::printf("[ shells ] scene  shells  shell-packets  prims  prim-packets  (Fig. 6-1)\n");
  for (const Row& r : rows) {
    const scenes::Scene s = cluster_scene(r.pp, 6000 + r.scene);
    const std::vector<Bounds> bounds = primitive_bounds(s);
    const ShellTree t = ShellTree::from_clusters(bounds, s.cluster_of_primitive, r.b);
    const ShellTreeCounts c = t.counts();
    std::printf("[ shells ] %5d  %6zu  %13zu  %5zu  %12zu  expected %zu/%zu/%zu/%zu\n", r.scene,
                c.shells, c.shell_packets, c.prims, c.prim_packets, r.expect.shells,
                r.expect.shell_packets, r.expect.prims, r.expect.prim_packets);
    EXPECT_EQ(c, r.expect) << "scene " << r.scene;
    check_tree(t, bounds, r.b);
    // Complete tree: every packet is full, depth log_b(64), PRIM_ARRAY[j] = cluster j.
    for (std::size_t i = 0; i < t.shell_packet_count(); ++i)
      EXPECT_EQ(t.shell_packet(i).size(), static_cast<std::size_t>(r.b));
    EXPECT_EQ(t.depth(), static_cast<int>(std::lround(std::log(64.0) / std::log(r.b))));
    for (std::size_t j = 0; j < t.prim_packet_count(); ++j)
      for (const std::uint32_t p : t.prim_packet(j)) EXPECT_EQ(s.cluster_of_primitive[p], j);
  }
}

TEST(AccelShellTree, ClusterTreesThatAreNotComplete) {
  const scenes::Scene s = cluster_scene(3, 11, 10);
  const std::vector<Bounds> bounds = primitive_bounds(s);
  for (const int b : {2, 3, 4, 8, 16}) {
    const ShellTree t = ShellTree::from_clusters(bounds, s.cluster_of_primitive, b);
    check_tree(t, bounds, b);
    EXPECT_EQ(t.counts().prim_packets, 10u);
  }
  EXPECT_THROW(ShellTree::from_clusters(bounds, std::vector<std::uint32_t>(3, 0), 2),
               std::invalid_argument);
  EXPECT_THROW(ShellTree::from_clusters(bounds, s.cluster_of_primitive, 1), std::invalid_argument);
  // No primitives: an empty root packet, nothing to hit.
  const ShellTree empty = ShellTree::from_clusters({}, {}, 4);
  EXPECT_EQ(empty.counts(), (ShellTreeCounts{0, 1, 0, 0}));
}

TEST(AccelShellTree, GenericBuildInvariants) {
  const scenes::Scene s = cluster_scene(16, 77);
  std::vector<Bounds> bounds = primitive_bounds(s);
  bounds[5] = Bounds{};  // an empty one is left out
  for (const int b : {2, 4, 8}) {
    for (const int m : {1, 4, 16}) {
      const ShellTree t = ShellTree::build(bounds, b, m);
      EXPECT_EQ(t.skipped_count(), 1u);
      EXPECT_EQ(t.counts().prims, bounds.size() - 1);
      const ShellTree again = ShellTree::build(bounds, b, m);
      ASSERT_EQ(t.shells().size(), again.shells().size());
      for (std::size_t i = 0; i < t.shells().size(); ++i) {
        EXPECT_EQ(t.shells()[i].child_index, again.shells()[i].child_index);
        EXPECT_EQ(t.shells()[i].box.lo, again.shells()[i].box.lo);
      }
      for (std::size_t j = 0; j < t.prim_packet_count(); ++j) {
        EXPECT_LE(t.prim_packet(j).size(), static_cast<std::size_t>(m));
        EXPECT_GE(t.prim_packet(j).size(), 1u);
      }
      std::printf(
          "[ shells ] generic b=%d leaf<=%d: %zu shells, %zu shell packets, %zu leaf "
          "shells, depth %d\n",
          b, m, t.counts().shells, t.counts().shell_packets, t.counts().prim_packets, t.depth());
    }
  }
  const std::vector<Bounds> clean = primitive_bounds(s);
  check_tree(ShellTree::build(clean, 4, 6), clean, 4, 6);
  check_tree(ShellTree::build(clean, 3, 1), clean, 3, 1);
  EXPECT_THROW(ShellTree::build(clean, 4, 0), std::invalid_argument);
  // Few primitives: one leaf under the root.
  const ShellTree small = ShellTree::build(std::span(clean).first(3), 8, 4);
  EXPECT_EQ(small.counts(), (ShellTreeCounts{1, 1, 3, 1}));
}

struct SearchTally {
  int rays = 0, hits = 0;
  ShellTraversalStats closest, shadow;
};

void search_against_brute_force(const scenes::Scene& s, const ShellTree& t,
                                const std::vector<Ray>& rays, SearchTally& tally) {
  ShellTraverser trav(t);
  for (const Ray& ray : rays) {
    double brute_t = kInfinity;
    int brute_id = -1;
    for (std::size_t i = 0; i < s.spheres.size(); ++i) {
      const double th =
          rtsim::testing::sphere_root(s.spheres[i].center, s.spheres[i].radius, ray, 1e-9, brute_t);
      if (th < brute_t) {
        brute_t = th;
        brute_id = static_cast<int>(i);
      }
    }
    auto test = [&](std::uint32_t slot, double t0, double t1) {
      return rtsim::testing::sphere_root(s.spheres[slot].center, s.spheres[slot].radius, ray, t0,
                                         t1);
    };
    const ShellHit h = trav.closest_hit(ray, 1e-9, kInfinity, test, tally.closest);
    ++tally.rays;
    EXPECT_EQ(h.prim, brute_id);
    if (brute_id >= 0) {
      ++tally.hits;
      EXPECT_EQ(h.t, brute_t);
      // A shadow ray to just past the hit is blocked; one stopping short of it is not
      // (unless something else is in between, which brute force would have found first).
      EXPECT_TRUE(trav.any_hit(ray, 1e-9, brute_t * 1.0001, test, tally.shadow).valid());
      EXPECT_FALSE(trav.any_hit(ray, 1e-9, brute_t * 0.9999, test, tally.shadow).valid());
    } else {
      EXPECT_FALSE(trav.any_hit(ray, 1e-9, kInfinity, test, tally.shadow).valid());
    }
  }
}

/// Vision rays from a camera at distance 35 through a 64x64 raster covering the scene.
std::vector<Ray> camera_rays() {
  std::vector<Ray> rays;
  const Vec3 eye(4.0, 6.0, 35.0);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const Vec3 target(-12.0 + 24.0 * (x + 0.5) / 64.0, -12.0 + 24.0 * (y + 0.5) / 64.0, 0.0);
      rays.push_back({eye, glm::normalize(target - eye)});
    }
  return rays;
}

TEST(AccelShellTree, SearchFindsTheClosestHitAndStopsEarly) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Ray> random_rays;
  for (int i = 0; i < 1500; ++i)
    random_rays.push_back({Vec3(12.0 * u(rng), 12.0 * u(rng), 12.0 * u(rng)),
                           glm::normalize(Vec3(g(rng), g(rng), g(rng)))});
  const std::vector<Ray> vision = camera_rays();
  std::printf(
      "[ shells ] scene  tree        rays  hits  box tests/ray  leaf shells sorted/ray  "
      "tested/ray  tested/sorted (mean per ray)  prim tests/ray\n");
  for (const int pp : {4, 8, 16}) {
    const scenes::Scene s = cluster_scene(pp, 500 + pp);
    const std::vector<Bounds> bounds = primitive_bounds(s);
    struct Variant {
      const char* name;
      int b;
      ShellTree tree;
    };
    const Variant variants[] = {
        {"clusters b=2", 2, ShellTree::from_clusters(bounds, s.cluster_of_primitive, 2)},
        {"clusters b=4", 4, ShellTree::from_clusters(bounds, s.cluster_of_primitive, 4)},
        {"clusters b=8", 8, ShellTree::from_clusters(bounds, s.cluster_of_primitive, 8)},
        {"generic b=4 ", 4, ShellTree::build(bounds, 4, pp)}};
    for (const Variant& v : variants) {
      SearchTally vis, rnd;
      search_against_brute_force(s, v.tree, vision, vis);
      search_against_brute_force(s, v.tree, random_rays, rnd);
      const ShellTraversalStats& c = vis.closest;
      const double n = vis.rays;
      std::printf("[ shells ] %2d%02d  %s  %5d  %4d  %13.1f  %22.2f  %10.2f  %28.1f%%  %14.1f\n",
                  v.b, pp, v.name, vis.rays, vis.hits, c.box_tests / n, c.leaf_shells_sorted / n,
                  c.leaf_shells_tested / n, 100.0 * c.mean_tested_fraction(), c.prim_tests / n);
      // The stop rule saves work: fewer leaf shells tested than sorted, and far fewer
      // primitive tests than brute force.
      EXPECT_LT(c.leaf_shells_tested, c.leaf_shells_sorted);
      EXPECT_LT(c.prim_tests, static_cast<std::uint64_t>(n * s.spheres.size() / 4));
      EXPECT_GT(vis.hits, vis.rays / 10);
    }
  }
  std::printf(
      "[ shells ] (Gaudet, jogger scene of Fig. 1-4: a ray tests 80%% of its sorted leaf "
      "shells, seed 001 L650)\n");
}

TEST(AccelShellTree, OverlappingShellsOfFig42) {
  // Fig. 4-2 (L646-L648): shell A is entered first, but primitive B (in shell B, entered
  // later) is hit before primitive A. The search must test both shells and return B.
  scenes::Scene s;
  s.materials.resize(1);
  s.spheres = {{Vec3(6.0, 0.0, 0.0), 0.5},   // A: far along the ray
               {Vec3(3.0, 0.0, 0.0), 0.5},   // B: near
               {Vec3(1.5, 2.0, 0.0), 0.2}};  // stretches shell A's box toward the origin
  for (std::uint32_t i = 0; i < 3; ++i)
    s.primitives.push_back({scenes::PrimitiveKind::Sphere, i, 0, 0});
  const std::vector<Bounds> bounds = primitive_bounds(s);
  const std::vector<std::uint32_t> clusters = {0, 1, 0};
  const ShellTree t = ShellTree::from_clusters(bounds, clusters, 2);
  ShellTraverser trav(t);
  ShellTraversalStats st;
  const Ray ray{Vec3(0.0), Vec3(1.0, 0.0, 0.0)};
  auto test = [&](std::uint32_t slot, double t0, double t1) {
    return rtsim::testing::sphere_root(s.spheres[slot].center, s.spheres[slot].radius, ray, t0, t1);
  };
  const ShellHit h = trav.closest_hit(ray, 0.0, kInfinity, test, st);
  ASSERT_EQ(trav.leaf_shell_list().size(), 2u);
  EXPECT_EQ(trav.leaf_shell_list()[0].child_index, 0u);  // shell A first
  EXPECT_EQ(h.prim, 1);
  EXPECT_DOUBLE_EQ(h.t, 2.5);
  EXPECT_EQ(st.leaf_shells_tested, 2u);
  // Disjoint shells: the second one is never opened.
  const std::vector<std::uint32_t> apart = {0, 1, 1};
  const ShellTree t2 = ShellTree::from_clusters(bounds, apart, 2);
  ShellTraverser trav2(t2);
  ShellTraversalStats st2;
  const ShellHit h2 = trav2.closest_hit(ray, 0.0, kInfinity, test, st2);
  EXPECT_EQ(h2.prim, 1);
  EXPECT_EQ(st2.leaf_shells_sorted, 2u);
  EXPECT_EQ(st2.leaf_shells_tested, 1u);
}

TEST(AccelShellTree, LeafShellListCapacityIsCounted) {
  // 80 one-sphere clusters in a row along x: a ray down the row hits all 80 leaf shells.
  scenes::Scene s;
  s.materials.resize(1);
  std::vector<std::uint32_t> clusters;
  for (std::uint32_t i = 0; i < 80; ++i) {
    s.spheres.push_back({Vec3(2.0 * i, 0.0, 0.0), 0.5});
    s.primitives.push_back({scenes::PrimitiveKind::Sphere, i, 0, 0});
    clusters.push_back(i);
  }
  const std::vector<Bounds> bounds = primitive_bounds(s);
  const ShellTree t = ShellTree::from_clusters(bounds, clusters, 4);
  ShellTraverser trav(t);
  ShellTraversalStats st;
  // Miss every sphere but cross every box: along a box edge line, just inside.
  const Ray ray{Vec3(-5.0, 0.49, 0.49), Vec3(1.0, 0.0, 0.0)};
  auto test = [&](std::uint32_t slot, double t0, double t1) {
    return rtsim::testing::sphere_root(s.spheres[slot].center, s.spheres[slot].radius, ray, t0, t1);
  };
  EXPECT_FALSE(trav.closest_hit(ray, 0.0, kInfinity, test, st).valid());
  EXPECT_EQ(st.leaf_shells_sorted, 80u);
  EXPECT_EQ(st.leaf_shells_tested, 80u);
  EXPECT_EQ(st.rays_over_capacity, 1u);
  EXPECT_EQ(st.entries_over_capacity, 30u);
  EXPECT_EQ(st.longest_list, 80u);
  EXPECT_EQ(kLeafShellListCapacity, 50u);
}

float word_float(std::uint32_t w) { return std::bit_cast<float>(w); }

TEST(AccelShellTree, BroadcastMemoryImages) {
  const scenes::Scene s = cluster_scene(4, 204);
  const std::vector<Bounds> bounds = primitive_bounds(s);
  const ShellTree t = ShellTree::from_clusters(bounds, s.cluster_of_primitive, 2);
  const GaudetDataSets d = make_gaudet_data_sets(t, s);
  const RecordWords w;
  // Shell data set: 63 packets of 2 SHELLs of 8 words; ID list of 3 words per packet first.
  ASSERT_EQ(d.shell.packet_count(), 63u);
  EXPECT_EQ(d.shell.id_list_words(), 63u * 3u);
  EXPECT_EQ(d.shell.packet_words(), 126u * 8u);
  std::uint32_t next = 63 * 3;
  for (const IdListEntry& e : d.shell.id_list()) {
    EXPECT_EQ(e.address, next);  // packets contiguous, in ID order
    EXPECT_EQ(e.size_words, 16u);
    const auto mem = d.shell.memory();
    EXPECT_EQ(mem[3 * e.id], e.id);
    EXPECT_EQ(mem[3 * e.id + 1], e.address);
    EXPECT_EQ(mem[3 * e.id + 2], e.size_words);
    next += e.size_words;
  }
  // A SHELL record decodes to its shell, the single-precision box enclosing the double one.
  for (std::uint32_t i = 0; i < 63; ++i) {
    const auto words = d.shell.packet(i);
    for (std::size_t k = 0; k < 2; ++k) {
      const Shell& sh = t.shell_packet(i)[k];
      const std::uint32_t* r = words.data() + 8 * k;
      EXPECT_EQ(r[0], sh.leaf ? 1u : 0u);
      EXPECT_EQ(r[1], sh.child_index);
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(word_float(r[2 + a]), sh.box.hi[a]);
        EXPECT_LE(word_float(r[5 + a]), sh.box.lo[a]);
        EXPECT_NEAR(word_float(r[2 + a]), sh.box.hi[a], 1e-5 * std::fabs(sh.box.hi[a]) + 1e-30);
      }
    }
  }
  // Prim data set: 64 packets of 4 sphere PRIMs of 3 + 4 words.
  ASSERT_EQ(d.prim.packet_count(), 64u);
  for (std::uint32_t j = 0; j < 64; ++j) {
    const auto words = d.prim.packet(j);
    ASSERT_EQ(words.size(), 4u * (w.prim_header + w.sphere));
    for (std::size_t k = 0; k < 4; ++k) {
      const std::uint32_t* r = words.data() + 7 * k;
      const std::uint32_t slot = t.prim_packet(j)[k];
      EXPECT_EQ(r[0], slot);
      EXPECT_EQ(r[1], s.primitives[slot].material);
      EXPECT_EQ(r[2], static_cast<std::uint32_t>(PrimType::Sphere));
      EXPECT_FLOAT_EQ(word_float(r[6]), static_cast<float>(s.spheres[slot].radius));
    }
  }
  // Shade data set: one 9-word packet per surface.
  ASSERT_EQ(d.shade.packet_count(), 2u);
  EXPECT_EQ(d.shade.packet(1).size(), 9u);
  EXPECT_FLOAT_EQ(word_float(d.shade.packet(1)[0]), 0.3f);  // k_s
  EXPECT_FLOAT_EQ(word_float(d.shade.packet(1)[1]), 0.7f);  // k_d
  EXPECT_EQ(d.shade.packet(1)[2], 20u);                     // n
  std::printf(
      "[ shells ] scene 204 images: shell %zu words (largest packet %u), prim %zu words "
      "(largest %u), shade %zu words\n",
      d.shell.memory().size(), d.shell.largest_packet_words(), d.prim.memory().size(),
      d.prim.largest_packet_words(), d.shade.memory().size());
  // Calibration knobs: larger records are padded, smaller ones are refused.
  RecordWords big;
  big.shell = 12;
  big.id_list_entry = 4;
  const BroadcastImage padded = shell_data_set(t, big);
  EXPECT_EQ(padded.packet(0).size(), 24u);
  EXPECT_EQ(padded.id_list_words(), 63u * 4u);
  EXPECT_EQ(padded.packet(0)[8], 0u);
  RecordWords small;
  small.shell = 7;
  EXPECT_THROW(shell_data_set(t, small), std::invalid_argument);
  small = {};
  small.id_list_entry = 2;
  EXPECT_THROW(shell_data_set(t, small), std::invalid_argument);
}

TEST(AccelShellTree, PrimitiveBoundsOfEveryKind) {
  scenes::Scene s;
  s.spheres = {{Vec3(1.0, 2.0, 3.0), -0.5}};
  s.polygons = {{{Vec3(0.0), Vec3(1.0, 0.0, 0.0), Vec3(0.0, 2.0, 0.0)}, {}, {}}};
  s.cones = {{Vec3(0.0), 1.0, Vec3(0.0, 0.0, 4.0), 0.5}};
  scenes::BezierPatch patch;
  for (int i = 0; i < 16; ++i) patch.control[i] = Vec3(i % 4, i / 4, (i % 5) * 0.1);
  s.patches = {patch};
  using K = scenes::PrimitiveKind;
  s.primitives = {
      {K::Sphere, 0, 0, 0}, {K::Polygon, 0, 0, 0}, {K::Cone, 0, 0, 0}, {K::Patch, 0, 0, 0}};
  const std::vector<Bounds> b = primitive_bounds(s);
  EXPECT_EQ(b[0].lo, Vec3(0.5, 1.5, 2.5));
  EXPECT_EQ(b[1].hi, Vec3(1.0, 2.0, 0.0));
  EXPECT_EQ(b[2].lo, Vec3(-1.0, -1.0, 0.0));  // axis along z: circles span +-r in x and y
  EXPECT_EQ(b[2].hi, Vec3(1.0, 1.0, 4.0));
  EXPECT_EQ(b[3].hi, Vec3(3.0, 3.0, 0.4));
  // PRIM records of the other kinds: polygon 3 + 1 + 9, cone 3 + 8, patch 3 + 48 words.
  std::vector<std::uint32_t> out;
  const PrimEncoder enc = scene_prim_encoder(s);
  enc(1, out);
  EXPECT_EQ(out.size(), 13u);
  EXPECT_EQ(out[3], 3u);
  out.clear();
  enc(2, out);
  EXPECT_EQ(out.size(), 11u);
  out.clear();
  enc(3, out);
  EXPECT_EQ(out.size(), 51u);
}

}  // namespace
}  // namespace rtsim::accel
