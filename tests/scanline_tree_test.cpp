// The scan-line tree's segments (firmware/scanline/: scan conversion, merging, pixel conversion,
// the tree evaluated functionally): a merged stream keeps raster order without overlaps and
// holds the nearest segment at every step; on real scenes the tree's image is what a brute-force
// depth comparison of the leaves' segments gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <set>
#include <utility>
#include <fstream>
#include <random>

#include "firmware/raster/raster_mesh.hpp"
#include "firmware/scanline/merging.hpp"
#include "firmware/scanline/pixel_converter.hpp"
#include "firmware/scanline/scan_converter.hpp"
#include "firmware/scanline/splitting.hpp"
#include "firmware/scanline/tree_frame.hpp"
#include "scenes/scene_loader.hpp"

namespace {

using namespace rtsim;
using namespace rtsim::scanline;

/// Checks that `out` is in raster order, without overlaps, ends with the dummy.
void expect_stream(const std::vector<Segment>& out) {
  ASSERT_FALSE(out.empty());
  EXPECT_TRUE(out.back().dummy());
  for (std::size_t k = 0; k + 1 < out.size(); ++k) {
    const Segment &a = out[k], &b = out[k + 1];
    EXPECT_FALSE(a.dummy());
    EXPECT_LE(a.left.x, a.right.x);
    if (!b.dummy() && a.y == b.y) {
      EXPECT_LT(a.right.x, b.left.x) << "line " << a.y << " segments " << k << ", " << k + 1;
    } else if (!b.dummy()) {
      EXPECT_LT(a.y, b.y);
    }
  }
}

/// Per step of every line: the nearest depth among the segments covering it (4096 = none).
std::vector<std::vector<int>> nearest(const std::vector<std::vector<Segment>>& streams, int lines,
                                      std::vector<std::vector<std::int64_t>>* owner) {
  std::vector<std::vector<int>> z(static_cast<std::size_t>(lines),
                                  std::vector<int>(kWordSteps, kWordSteps));
  if (owner)
    owner->assign(static_cast<std::size_t>(lines), std::vector<std::int64_t>(kWordSteps, -1));
  for (const auto& s : streams)
    for (const Segment& seg : s) {
      if (seg.dummy()) continue;
      for (int x = seg.left.x; x <= seg.right.x; ++x) {
        const int d = point_at(seg, x).z;
        auto& cell = z[static_cast<std::size_t>(seg.y)][static_cast<std::size_t>(x)];
        if (d < cell) {
          cell = d;
          if (owner)
            (*owner)[static_cast<std::size_t>(seg.y)][static_cast<std::size_t>(x)] = seg.polygon;
        }
      }
    }
  return z;
}

Segment random_segment(std::mt19937& rng, int y) {
  std::uniform_int_distribution<int> x(0, kWordMax), z(0, kWordMax), c(0, kWordMax);
  int a = x(rng), b = x(rng);
  if (a > b) std::swap(a, b);
  Segment s;
  s.y = static_cast<std::int16_t>(y);
  s.left = {static_cast<std::int16_t>(a), static_cast<std::int16_t>(z(rng)),
            static_cast<std::int16_t>(c(rng)), 0, 0};
  s.right = {static_cast<std::int16_t>(b), static_cast<std::int16_t>(z(rng)),
             static_cast<std::int16_t>(c(rng)), 0, 0};
  return s;
}

TEST(MergingProcessor, MergedStreamsKeepOrderAndTheNearestSegmentEverywhere) {
  std::mt19937 rng(1367);
  std::vector<std::vector<Segment>> streams;
  const int lines = 40;
  for (int polygon = 0; polygon < 12; ++polygon) {
    std::vector<Segment> s;
    for (int y = 0; y < lines; ++y) {
      if (rng() % 3 == 0) continue;
      Segment seg = random_segment(rng, y);
      seg.polygon = static_cast<std::uint32_t>(polygon);
      s.push_back(seg);
    }
    s.push_back(dummy_segment());
    streams.push_back(s);
  }
  MergeTally tally;
  const std::vector<Segment> out = merge_tree(streams, &tally);
  expect_stream(out);
  const auto want = nearest(streams, lines, nullptr);
  const auto got = nearest({out}, lines, nullptr);
  std::size_t steps = 0, same = 0, covered_differently = 0;
  for (int y = 0; y < lines; ++y)
    for (int x = 0; x < kWordSteps; ++x) {
      const int w = want[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)];
      const int g = got[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)];
      if ((w == kWordSteps) != (g == kWordSteps)) ++covered_differently;
      if (w == kWordSteps) continue;
      ++steps;
      // The breaks interpolate at whole steps: a step next to a crossing may keep the other.
      if (std::abs(w - g) <= 8) ++same;
    }
  std::printf(
      "%zu covered steps, %.4f%% nearest; passes: apart %llu, disappears %llu, "
      "intersects %llu, protrudes %llu, hidden %llu\n",
      steps, 100.0 * same / steps, (unsigned long long)tally.passes[0],
      (unsigned long long)tally.passes[1], (unsigned long long)tally.passes[2],
      (unsigned long long)tally.passes[3], (unsigned long long)tally.passes[4]);
  EXPECT_EQ(covered_differently, 0u);
  EXPECT_GT(static_cast<double>(same) / steps, 0.995);
  // Every case of the six steps occurs (line marks come only from splitting processors).
  for (int k = 0; k < kMergeCases; ++k)
    EXPECT_EQ(tally.passes[static_cast<std::size_t>(k)] > 0, k != static_cast<int>(MergeCase::Mark))
        << kMergeCaseNames[static_cast<std::size_t>(k)];
}

TEST(MergingProcessor, AStreamMergedWithNothingIsItself) {
  std::mt19937 rng(7);
  std::vector<Segment> s;
  for (int y = 0; y < 5; ++y) s.push_back(random_segment(rng, y));
  s.push_back(dummy_segment());
  const auto out = merge_streams(s, {dummy_segment()}, nullptr);
  ASSERT_EQ(out.size(), s.size());
  for (std::size_t k = 0; k < s.size(); ++k) EXPECT_EQ(out[k].words(), s[k].words());
  // A stream cut short (no dummy) ends as if it had one.
  EXPECT_EQ(merge_streams(s, {}, nullptr).size(), s.size());
}

TEST(PixelConverter, CoveredPixelsTileTheRowWithoutGapsOrOverlaps) {
  for (const int width : {512, 640, 333, 4096}) {
    std::vector<int> hits(static_cast<std::size_t>(width), 0);
    Segment s;
    s.y = 0;
    int x = 0;
    std::mt19937 rng(static_cast<unsigned>(width));
    while (x < kWordSteps) {
      const int len = 1 + static_cast<int>(rng() % 90);
      s.left.x = static_cast<std::int16_t>(x);
      s.right.x = static_cast<std::int16_t>(std::min(x + len, kWordSteps) - 1);
      const auto [first, end] = covered_pixels(s, width);
      for (int p = first; p < end; ++p) ++hits[static_cast<std::size_t>(p)];
      x += len;
    }
    for (int p = 0; p < width; ++p)
      EXPECT_EQ(hits[static_cast<std::size_t>(p)], 1) << width << " " << p;
  }
}

/// A strip's segment in the screen's steps (the steps it covers, rounded in).
Segment on_screen(Segment s, int levels, int strip) {
  const int origin = strip * (kWordSteps >> levels);
  s.left.x = static_cast<std::int16_t>(origin + (s.left.x >> levels));
  s.right.x = static_cast<std::int16_t>(origin + (((s.right.x + 1) >> levels) - 1));
  if (s.right.x < s.left.x) s.right.x = s.left.x;
  return s;
}

TEST(ScanlineTree, ATreeFrameIsTheNearestOfItsLeavesSegments) {
  for (const auto& [name, levels] : {std::pair{"teapot-s2.nff", 0}, std::pair{"balls-s1.nff", 0},
                                     std::pair{"teapot-s2.nff", 2}, std::pair{"balls-s1.nff", 5}}) {
    SCOPED_TRACE(std::string(name) + " split " + std::to_string(levels));
    scenes::Scene scene = scenes::load_scene(std::string(RTSIM_SHARED_DIR) + "/scenes/" + name);
    const int width = 256, height = 256;
    const raster::RasterMesh mesh = raster::build_raster_mesh(scene, raster::MeshSettings{});
    const TcFrame frame = tc_frame(scene, mesh, width, height, shading::ShadeParams{});
    const auto leaves = leaf_assignment(frame.polygons, frame.polygons.size(), LeafPlan{});
    const TreeFrame tree = evaluate_tree(frame, height, leaves, levels);
    ASSERT_EQ(tree.strips.size(), std::size_t{1} << levels);
    std::vector<Segment> root;  // the strips' streams on the screen, line by line
    for (std::size_t k = 0; k < tree.strips.size(); ++k) {
      // Line marks (splitting.hpp) carry no pixels.
      std::vector<Segment> strip;
      for (const Segment& s : tree.strips[k])
        if (!s.mark) strip.push_back(s);
      expect_stream(strip);
      for (const Segment& s : strip)
        if (!s.dummy()) root.push_back(on_screen(s, levels, static_cast<int>(k)));
    }
    std::stable_sort(root.begin(), root.end(), [](const Segment& a, const Segment& b) {
      return a.y != b.y ? a.y < b.y : a.left.x < b.left.x;
    });
    root.push_back(dummy_segment());
    // The leaves' streams again, for the brute-force answer.
    const auto chains = transform_and_clip(frame);
    std::vector<std::vector<Segment>> streams;
    for (std::uint32_t p = 0; p < chains.size(); ++p)
      streams.push_back(scan_convert(chains[p], height, p));
    std::vector<std::vector<std::int64_t>> want_owner, got_owner;
    nearest(streams, height, &want_owner);
    nearest({root}, height, &got_owner);
    std::size_t covered = 0, same = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < kWordSteps; ++x) {
        const auto w = want_owner[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)];
        const auto g = got_owner[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)];
        EXPECT_EQ(w < 0, g < 0);
        if (w < 0) continue;
        ++covered;
        if (w == g) ++same;
      }
    std::printf(
        "%s: %zu polygons, %llu leaf segments, %zu root segments, %zu covered steps, "
        "%.3f%% the nearest polygon's; passes %llu (intersects %llu)\n",
        name, frame.polygons.size(), (unsigned long long)tree.leaf_segments, root.size() - 1,
        covered, 100.0 * same / covered, (unsigned long long)tree.tally.total(),
        (unsigned long long)tree.tally.passes[static_cast<int>(MergeCase::Intersects)]);
    EXPECT_GT(static_cast<double>(same) / covered, 0.98);
    // The picture, for looking at.
    const auto rows = paint_frame(tree.strips, width, height, scene.background, false, false);
    std::ofstream ppm(std::string("/tmp/scanline-tree-") + name + "-split" +
                          std::to_string(levels) + ".ppm",
                      std::ios::binary);
    ppm << "P6\n" << width << " " << height << "\n255\n";
    for (const auto& r : rows)
      for (const Color& c : r.colour)
        for (int k = 0; k < 3; ++k)
          ppm.put(static_cast<char>(std::lround(std::clamp(c[k], 0.0, 1.0) * 255)));
  }
}

TEST(ScanlineTree, ASplittingProcessorSendsEachHalfItsPartInFullScreenSteps) {
  // Fig. 3-25: left whole, right whole, across the centre; the dummy to both sides.
  Segment s;
  s.y = 7;
  s.left = {100, 0, 0, 0, 0};
  s.right = {2047, 4000, 4095, 0, 0};
  SplitParts p = split_segment(s);
  ASSERT_TRUE(p.left && !p.right && !p.broken);
  EXPECT_EQ(p.left->left.x, 200);
  EXPECT_EQ(p.left->right.x, 4095);  // covers up to 2048 steps: the whole left half
  s.left.x = 2048;
  s.right.x = 4095;
  p = split_segment(s);
  ASSERT_TRUE(!p.left && p.right);
  EXPECT_EQ(p.right->left.x, 0);
  EXPECT_EQ(p.right->right.x, 4095);
  s.left = {1000, 0, 0, 0, 0};
  s.right = {3000, 2000, 2000, 0, 0};
  p = split_segment(s);
  ASSERT_TRUE(p.left && p.right && p.broken);
  EXPECT_EQ(p.left->left.x, 2000);
  EXPECT_EQ(p.left->right.x, 4095);
  EXPECT_EQ(p.right->left.x, 0);
  EXPECT_EQ(p.right->right.x, 2 * (3000 - 2048) + 1);
  // z at the cut: 1047 / 2000 and 1048 / 2000 of the way from 0 to 2000.
  EXPECT_EQ(p.left->right.z, 1047);
  EXPECT_EQ(p.right->left.z, 1048);
  p = split_segment(dummy_segment());
  EXPECT_TRUE(p.left && p.left->dummy() && p.right && p.right->dummy());
}

TEST(ScanlineTree, ASplitRootHasTheSeedsProcessorCountsAndEveryStreamOnce) {
  // L1594: n 2^n splitting processors, (n - 1) 2^n + 1 extra merging processors; n = 6 gives
  // 384 and 321.
  EXPECT_EQ(split_counts(6).splitters, 384u);
  EXPECT_EQ(split_counts(6).extra_merging, 321u);
  EXPECT_EQ(split_counts(1).splitters, 2u);
  EXPECT_EQ(split_counts(1).extra_merging, 1u);
  EXPECT_EQ(split_counts(0).splitters, 0u);
  for (int n = 1; n <= kMaxSplitLevels; ++n) {
    std::uint64_t splitters = 0, merging = 0;
    for (int stage = 0; stage < n; ++stage) {
      std::set<std::size_t> in, out;
      for (const SplitPair& p : split_stage(n, stage)) {
        EXPECT_TRUE(in.insert(p.first).second && in.insert(p.second).second);
        EXPECT_TRUE(out.insert(p.left).second && out.insert(p.right).second);
        // A pair's streams are one strip's; its outputs the two halves of that strip.
        const std::size_t per = std::size_t{1} << (n - stage);
        EXPECT_EQ(p.first / per, p.second / per);
        EXPECT_EQ(p.left / (per / 2), 2 * (p.first / per));
        EXPECT_EQ(p.right / (per / 2), 2 * (p.first / per) + 1);
        splitters += 2;
        merging += 2;
      }
      EXPECT_EQ(in.size(), std::size_t{1} << n);
      EXPECT_EQ(out.size(), std::size_t{1} << n);
    }
    EXPECT_EQ(splitters, split_counts(n).splitters);
    // The n levels it replaced held 2^n - 1 merging processors.
    EXPECT_EQ(merging - ((std::uint64_t{1} << n) - 1), split_counts(n).extra_merging);
  }
}

TEST(ScanlineTree, EveryPixelBelongsToOneStrip) {
  // A segment covering a strip whole paints exactly the pixels whose centres lie in it.
  for (const int width : {64, 100, 512, 640})
    for (int n = 0; n <= kMaxSplitLevels; ++n) {
      std::vector<int> hits(static_cast<std::size_t>(width), 0);
      for (int k = 0; k < (1 << n); ++k) {
        Segment s;
        s.y = 0;
        s.left.x = 0;
        s.right.x = kWordMax;
        const auto [first, end] = covered_pixels(s, width, {.levels = n, .index = k});
        for (int p = first; p < end; ++p) ++hits[static_cast<std::size_t>(p)];
      }
      for (int p = 0; p < width; ++p)
        EXPECT_EQ(hits[static_cast<std::size_t>(p)], 1) << width << " " << n << " " << p;
    }
}

TEST(ScanlineTree, SubvolumeAssignmentSpreadsEverySubvolumeOverTheSubtrees) {
  // 64 polygons in 8 subvolumes (8 each): each of the 8 subtrees at depth 3 holds one of each.
  std::vector<TcPolygon> polygons;
  for (int cell = 0; cell < 8; ++cell)
    for (int k = 0; k < 8; ++k) {
      TcPolygon p;
      const Vec3 c(cell % 2 + 0.25 + 0.01 * k, (cell / 2) % 2 + 0.25, cell / 4 + 0.25);
      p.vertex = {c, c + Vec3(0.1, 0, 0), c + Vec3(0.1, 0.1, 0), c + Vec3(0, 0.1, 0)};
      polygons.push_back(p);
    }
  const auto leaf = leaf_assignment(polygons, 64, {.order = LeafOrder::Subvolume, .subvolumes = 2});
  ASSERT_EQ(leaf.size(), 64u);
  EXPECT_EQ(std::set<std::uint32_t>(leaf.begin(), leaf.end()).size(), 64u);
  for (const auto& [lo, hi] : subtree_ranges(64, 3)) {
    std::set<std::uint32_t> cells;
    for (std::size_t k = lo; k < hi; ++k) cells.insert(leaf[k] / 8);
    EXPECT_EQ(cells.size(), 8u);
  }
  // Idle leaves past the polygons: a permutation of all of them.
  const auto padded = leaf_assignment(polygons, 100, LeafPlan{});
  EXPECT_EQ(std::set<std::uint32_t>(padded.begin(), padded.end()).size(), 100u);
  EXPECT_GE(*std::min_element(padded.begin() + 64, padded.end()), 64u);
}

}  // namespace
