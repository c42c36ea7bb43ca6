// The scan-line tree's segments (firmware/scanline/: scan conversion, merging, pixel conversion,
// the tree evaluated functionally): a merged stream keeps raster order without overlaps and
// holds the nearest segment at every step; on real scenes the tree's image is what a brute-force
// depth comparison of the leaves' segments gives.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>

#include "firmware/raster/raster_mesh.hpp"
#include "firmware/scanline/merging.hpp"
#include "firmware/scanline/pixel_converter.hpp"
#include "firmware/scanline/scan_converter.hpp"
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
  for (const auto p : tally.passes) EXPECT_GT(p, 0u);
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

TEST(ScanlineTree, ATreeFrameIsTheNearestOfItsLeavesSegments) {
  for (const char* name : {"teapot-s2.nff", "balls-s1.nff"}) {
    SCOPED_TRACE(name);
    scenes::Scene scene = scenes::load_scene(std::string(RTSIM_SHARED_DIR) + "/scenes/" + name);
    const int width = 256, height = 256;
    const raster::RasterMesh mesh = raster::build_raster_mesh(scene, raster::MeshSettings{});
    const TcFrame frame = tc_frame(scene, mesh, width, height, shading::ShadeParams{});
    const auto leaves = leaf_assignment(frame.polygons.size(), true, 1983);
    const TreeFrame tree = evaluate_tree(frame, height, leaves);
    expect_stream(tree.root);
    // The leaves' streams again, for the brute-force answer.
    const auto chains = transform_and_clip(frame);
    std::vector<std::vector<Segment>> streams;
    for (std::uint32_t p = 0; p < chains.size(); ++p)
      streams.push_back(scan_convert(chains[p], height, p));
    std::vector<std::vector<std::int64_t>> want_owner, got_owner;
    nearest(streams, height, &want_owner);
    nearest({tree.root}, height, &got_owner);
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
        name, frame.polygons.size(), (unsigned long long)tree.leaf_segments, tree.root.size() - 1,
        covered, 100.0 * same / covered, (unsigned long long)tree.tally.total(),
        (unsigned long long)tree.tally.passes[static_cast<int>(MergeCase::Intersects)]);
    EXPECT_GT(static_cast<double>(same) / covered, 0.98);
    // The picture, for looking at.
    const auto rows = paint_frame(tree.root, width, height, scene.background, false, false);
    std::ofstream ppm(std::string("/tmp/scanline-tree-") + name + ".ppm", std::ios::binary);
    ppm << "P6\n" << width << " " << height << "\n255\n";
    for (const auto& r : rows)
      for (const Color& c : r.colour)
        for (int k = 0; k < 3; ++k)
          ppm.put(static_cast<char>(std::lround(std::clamp(c[k], 0.0, 1.0) * 255)));
  }
}

}  // namespace
