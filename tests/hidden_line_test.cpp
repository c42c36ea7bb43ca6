// The hidden-line pipeline's firmware (firmware/hiddenline/; seed 000 §3.4): exact rational
// parameters, boundary planes oriented visible-side positive, the plane and cleanup processors
// of Figs. 3-32 to 3-34, and the pipe's output against an independent check: points sampled
// along every segment, each tested against every polygon by its own 2-D inside test and depth
// (no boundary plane involved).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "firmware/hiddenline/pipe.hpp"
#include "firmware/hiddenline/point_check.hpp"
#include "firmware/hiddenline/screen_scene.hpp"
#include "scenes/scene_loader.hpp"

namespace {

using namespace rtsim;
using namespace rtsim::hiddenline;

TEST(HiddenLineParam, ComparesRationalsExactlyWithTheEndsOfTheLine) {
  EXPECT_EQ(compare({1, 2}, {2, 4}), 0);
  EXPECT_EQ(compare({-1, -2}, {1, 2}), 0);
  EXPECT_LT(compare({1, 3}, {1, 2}), 0);
  EXPECT_GT(compare({1, -3}, {-1, 2}), 0);  // -1/3 > -1/2
  EXPECT_LT(compare(LineParam::minus_infinity(), {-1000000, 1}), 0);
  EXPECT_GT(compare(LineParam::plus_infinity(), {1000000, 1}), 0);
  EXPECT_EQ(compare(LineParam::plus_infinity(), LineParam::plus_infinity()), 0);
  // Products beyond 64 bits.
  const std::int64_t big = std::int64_t{1} << 52;
  EXPECT_LT(compare({big - 1, big}, {big, big + 1}), 0);
}

TEST(HiddenLinePlanes, VisibleSidesArePositiveAndTheHiddenVolumeIsBehindTheInside) {
  const std::vector<ScreenPoint> square = {
      {100, 100, 500}, {300, 100, 500}, {300, 300, 500}, {100, 300, 500}};
  const auto planes = boundary_planes(square);
  ASSERT_EQ(planes.size(), 5u);
  EXPECT_TRUE(planes.back().last);
  const auto hidden = [&](const ScreenPoint& p) {
    for (const auto& pl : planes)
      if (pl.at(p) >= 0) return false;
    return true;
  };
  EXPECT_TRUE(hidden({200, 200, 600}));   // behind the inside
  EXPECT_FALSE(hidden({200, 200, 400}));  // in front
  EXPECT_FALSE(hidden({400, 200, 600}));  // behind, but beside it
  EXPECT_FALSE(hidden({100, 200, 600}));  // on an edge plane: visible
  // Seen edge-on it hides nothing.
  EXPECT_TRUE(boundary_planes({{0, 0, 0}, {10, 0, 0}, {10, 0, 10}}).empty());
}

/// Runs segments through the chain of `polygons` and returns the visible pieces.
std::vector<VisiblePiece> eliminate(const std::vector<std::vector<ScreenPoint>>& polygons,
                                    const std::vector<Segment>& segments, int trailing = 4) {
  auto chain = build_chain(polygons, trailing);
  return divide(run_chain(chain, segment_stream(segments)));
}

double visible_length(const std::vector<VisiblePiece>& pieces, std::uint32_t edge) {
  double sum = 0;
  for (const auto& p : pieces)
    if (p.edge == edge) sum += p.t1 - p.t0;
  return sum;
}

TEST(HiddenLinePipe, HidesBehindMergesAndSuppresses) {
  const std::vector<ScreenPoint> a = {
      {100, 100, 100}, {300, 100, 100}, {300, 300, 100}, {100, 300, 100}};
  const std::vector<ScreenPoint> b = {
      {250, 150, 100}, {450, 150, 100}, {450, 250, 100}, {250, 250, 100}};
  // A segment behind both, across them: hidden from x = 100 to 450 of 0..500 (Fig. 3-30).
  const Segment across{{0, 200, 500}, {500, 200, 500}, 1};
  // Wholly behind a: suppressed. In front of a: untouched.
  const Segment behind{{150, 200, 500}, {250, 200, 500}, 2};
  const Segment front{{0, 200, 50}, {500, 200, 50}, 3};
  // Above a, parallel to its top edge and beside it: not hidden (the parallel-visible case).
  const Segment above{{0, 50, 500}, {500, 50, 500}, 4};
  const auto pieces = eliminate({a, b}, {across, behind, front, above});
  EXPECT_NEAR(visible_length(pieces, 1), 150.0 / 500.0, 1e-12);
  EXPECT_EQ(visible_length(pieces, 2), 0.0);
  EXPECT_EQ(visible_length(pieces, 3), 1.0);
  EXPECT_EQ(visible_length(pieces, 4), 1.0);
  // The polygons' own edges are never hidden by themselves or each other (a's edges lie in
  // front of nothing; b's left edge runs over a, in the same plane: on a's plane is visible).
  std::vector<Segment> edges;
  for (std::size_t i = 0; i < 4; ++i)
    edges.push_back({a[i], a[(i + 1) % 4], 10u + static_cast<std::uint32_t>(i)});
  for (std::size_t i = 0; i < 4; ++i)
    edges.push_back({b[i], b[(i + 1) % 4], 20u + static_cast<std::uint32_t>(i)});
  const auto own = eliminate({a, b}, edges);
  for (const auto& s : edges) EXPECT_EQ(visible_length(own, s.edge), 1.0) << s.edge;
}

TEST(HiddenLinePipe, ThreeHiddenPartsAndTheDebrisCaughtDownstream) {
  // Three squares side by side hide the whole segment between them: the first cleanup that
  // holds three parts must send the segment on; a later one, merging, catches it.
  std::vector<std::vector<ScreenPoint>> squares;
  for (int i = 0; i < 3; ++i)
    squares.push_back({{100 * i, 0, 100},
                       {100 * i + 120, 0, 100},
                       {100 * i + 120, 100, 100},
                       {100 * i, 100, 100}});
  const Segment s{{10, 50, 300}, {300, 50, 300}, 7};
  EXPECT_EQ(visible_length(eliminate(squares, {s}, 0), 7), 0.0);
  EXPECT_TRUE(eliminate(squares, {s}, 4).empty());
}

TEST(HiddenLinePipe, AgreesWithAnIndependentCheckOnRandomScenes) {
  std::mt19937_64 rng(1983);
  const auto coord = [&](int lo, int hi) {
    return static_cast<std::int32_t>(lo +
                                     static_cast<int>(rng() % static_cast<std::uint64_t>(hi - lo)));
  };
  std::size_t samples = 0, mismatches = 0, hidden_samples = 0;
  for (int scene = 0; scene < 20; ++scene) {
    // Triangles and planar quadrilaterals (a parallelogram) at random depths and slopes.
    std::vector<std::vector<ScreenPoint>> polygons;
    for (int k = 0; k < 12; ++k) {
      const ScreenPoint p0{coord(0, 900), coord(0, 900), coord(100, 900)};
      // A third of them with edges along the screen's axes: lines parallel to edge planes.
      const bool axes = k % 3 == 2;
      const ScreenPoint u{coord(-150, 150), axes ? 0 : coord(-150, 150), coord(-60, 60)};
      const ScreenPoint w{axes ? 0 : coord(-150, 150), coord(-150, 150), coord(-60, 60)};
      std::vector<ScreenPoint> poly = {p0, {p0[0] + u[0], p0[1] + u[1], p0[2] + u[2]}};
      if (k % 2) poly.push_back({p0[0] + u[0] + w[0], p0[1] + u[1] + w[1], p0[2] + u[2] + w[2]});
      poly.push_back({p0[0] + w[0], p0[1] + w[1], p0[2] + w[2]});
      polygons.push_back(poly);
    }
    std::vector<Segment> segments;
    for (std::size_t k = 0; k < polygons.size(); ++k)
      for (std::size_t i = 0; i < polygons[k].size(); ++i)
        segments.push_back({polygons[k][i], polygons[k][(i + 1) % polygons[k].size()],
                            static_cast<std::uint32_t>(segments.size())});
    for (int k = 0; k < 30; ++k) {
      // General, horizontal and vertical segments.
      Segment g{{coord(0, 1000), coord(0, 1000), coord(0, 1000)},
                {coord(0, 1000), coord(0, 1000), coord(0, 1000)},
                static_cast<std::uint32_t>(segments.size())};
      if (k % 3 == 1) g.b[1] = g.a[1];
      if (k % 3 == 2) g.b[0] = g.a[0];
      segments.push_back(g);
    }
    const auto pieces = eliminate(polygons, segments);
    for (const Segment& s : segments) {
      std::vector<std::pair<double, double>> vis;
      for (const auto& p : pieces)
        if (p.edge == s.edge) vis.emplace_back(p.t0, p.t1);
      for (int j = 0; j < 400; ++j) {
        const double t = (j + 0.5) / 400.0;
        // Samples next to a piece's end are left out: the ends are where visibility changes.
        bool near_end = false, shown = false;
        for (const auto& [t0, t1] : vis) {
          near_end |= std::abs(t - t0) < 1e-6 || std::abs(t - t1) < 1e-6;
          shown |= t > t0 && t < t1;
        }
        if (near_end) continue;
        const double x = s.a[0] + t * (s.b[0] - s.a[0]), y = s.a[1] + t * (s.b[1] - s.a[1]),
                     z = s.a[2] + t * (s.b[2] - s.a[2]);
        const Seen seen = point_seen(polygons, x, y, z);
        if (seen == Seen::kUnsure) continue;
        const bool hidden = seen == Seen::kHidden;
        ++samples;
        hidden_samples += hidden ? 1 : 0;
        if (hidden == shown) ++mismatches;
      }
    }
  }
  std::printf("%zu samples, %zu hidden, %zu disagree\n", samples, hidden_samples, mismatches);
  EXPECT_GT(hidden_samples, samples / 20);
  EXPECT_EQ(mismatches, 0u);
}

TEST(HiddenLineScreen, AScenesEdgesBehindItsPolygonsAreHiddenAndTheRestDrawn) {
  // SPD's teapot scene (992 triangles and the checkerboard's quadrilaterals) from its camera: the
  // teapot's far side is hidden, its near side and the floor's edges in front of it drawn. The
  // pipe's pieces against the independent check on the screen polygons.
  const scenes::Scene scene =
      scenes::make_builtin_scene("spd-teapot", scenes::default_generator_seeds());
  const raster::RasterMesh mesh = raster::build_raster_mesh(scene, raster::MeshSettings{});
  const raster::ViewTransform view =
      raster::ViewTransform::camera(scene.camera, 160, 120, mesh.bounds);
  const ScreenScene screen = to_screen(scene, mesh, view);
  EXPECT_GT(screen.polygons.size(), 900u);
  EXPECT_GT(screen.segments.size(), 1400u);  // shared edges once
  auto chain = build_chain(screen.polygons, 4);
  const auto pieces = divide(run_chain(chain, segment_stream(screen.segments)));
  double shown = 0;
  for (const auto& p : pieces) shown += p.t1 - p.t0;
  const double share = shown / static_cast<double>(screen.segments.size());
  std::printf("%zu polygons, %zu segments, %zu pieces, %.1f%% of the edges' length visible\n",
              screen.polygons.size(), screen.segments.size(), pieces.size(), 100 * share);
  EXPECT_GT(share, 0.3);
  EXPECT_LT(share, 0.8);
  const PieceCheck c = check_pieces(screen.polygons, screen.segments, pieces, 20);
  std::printf("%zu samples, %zu hidden, %zu visible ones missed, %zu hidden ones drawn\n",
              c.samples, c.hidden, c.missed, c.drawn_hidden);
  EXPECT_GT(c.samples, 10000u);
  EXPECT_EQ(c.missed, 0u);
  EXPECT_EQ(c.drawn_hidden, 0u);
}

}  // namespace

namespace {

TEST(HiddenLineScreen, CubesAndInterpenetratingSquaresAgreeWithTheCheckWhateverTheDebrisString) {
  // Quadrilaterals whose integer corners are not exactly coplanar, cubes sharing edges between
  // faces, squares passing through one another: no wrong point, and the same pieces whether
  // four or a hundred cleanup processors trail the pipe (the divider unites what is left).
  for (const char* name : {"ullner-cubes", "ullner-random-300"}) {
    const scenes::Scene scene = scenes::make_builtin_scene(name, scenes::default_generator_seeds());
    const raster::RasterMesh mesh = raster::build_raster_mesh(scene, raster::MeshSettings{});
    const ScreenScene screen =
        to_screen(scene, mesh, raster::ViewTransform::camera(scene.camera, 256, 256, mesh.bounds));
    std::vector<VisiblePiece> first;
    for (int trailing : {4, 100}) {
      auto chain = build_chain(screen.polygons, trailing);
      const auto pieces = divide(run_chain(chain, segment_stream(screen.segments)));
      const PieceCheck c = check_pieces(screen.polygons, screen.segments, pieces, 20);
      std::printf(
          "%s, %d trailing: %zu points, %zu hidden, %zu visible missed, %zu hidden "
          "drawn\n",
          name, trailing, c.samples, c.hidden, c.missed, c.drawn_hidden);
      EXPECT_GT(c.samples, 10000u);
      EXPECT_GT(c.hidden, c.samples / 4);
      EXPECT_EQ(c.missed, 0u);
      EXPECT_EQ(c.drawn_hidden, 0u);
      if (first.empty()) {
        first = pieces;
        continue;
      }
      ASSERT_EQ(pieces.size(), first.size());
      for (std::size_t k = 0; k < pieces.size(); ++k) {
        EXPECT_EQ(pieces[k].edge, first[k].edge);
        EXPECT_EQ(pieces[k].t0, first[k].t0);
        EXPECT_EQ(pieces[k].t1, first[k].t1);
      }
    }
  }
}

}  // namespace
