// The T&C processors of Ullner's scan-line tree (firmware/scanline/tc_*): the broadcast program
// of Figs. 3-10 to 3-15 run on simulated processors in lockstep. Its instruction counts are the
// program's (printed beside Fig. 3-16's); its answers are checked against a plain double-
// precision transform, Sutherland-Hodgman clipper and perspective division; and a processor whose
// polygon is clipped away, or a lane that is shut down, sends nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "firmware/scanline/tc_program.hpp"

namespace {

using namespace rtsim;
using namespace rtsim::scanline;

/// A camera at the origin looking down +z (L979-L985), a 90-degree view, near 1, far 100:
/// [x y z 1] M = (x, y, (z - n) f / (f - n), z): -w <= x, y <= w, 0 <= z <= w inside (L1005).
TcLiterals camera_literals() {
  TcLiterals lit;
  const float n = 1.0f, f = 100.0f;
  lit.matrix = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, f / (f - n), 1}, {0, 0, -n * f / (f - n), 0}}};
  lit.ambient = {0.2f, 0.2f, 0.2f};
  lit.point = {0.8f, 0.7f, 0.6f};
  lit.direction = {0.0f, 0.0f, -1.0f};
  return lit;
}

struct H {
  double x, y, z, w, r, g, b;
};

/// The reference: transform, colour, clip against the six planes in the program's order,
/// divide. Screen (x, y) of the clipped polygon's vertices.
std::vector<std::pair<double, double>> reference(const TcPolygon& poly, const TcLiterals& lit) {
  std::vector<H> v;
  for (int k = 0; k < 4; ++k) {
    const Vec3 p = poly.vertex[static_cast<std::size_t>(k)];
    double o[4];
    for (int c = 0; c < 4; ++c)
      o[c] = p.x * lit.matrix[0][static_cast<std::size_t>(c)] +
             p.y * lit.matrix[1][static_cast<std::size_t>(c)] +
             p.z * lit.matrix[2][static_cast<std::size_t>(c)] +
             lit.matrix[3][static_cast<std::size_t>(c)];
    v.push_back({o[0], o[1], o[2], o[3], 0, 0, 0});
  }
  const auto dist = [](int plane, const H& h) {
    switch (plane) {
      case 0:
        return h.w - h.x;
      case 1:
        return h.w + h.x;
      case 2:
        return h.w - h.y;
      case 3:
        return h.w + h.y;
      case 4:
        return h.z;
      default:
        return h.w - h.z;
    }
  };
  for (int plane = 0; plane < 6; ++plane) {
    std::vector<H> out;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const H& cur = v[i];
      const H& prev = v[(i + v.size() - 1) % v.size()];
      const double dp = dist(plane, prev), dc = dist(plane, cur);
      if (dp * dc < 0) {
        const double t = dp / (dp - dc);
        out.push_back({prev.x + t * (cur.x - prev.x), prev.y + t * (cur.y - prev.y),
                       prev.z + t * (cur.z - prev.z), prev.w + t * (cur.w - prev.w), 0, 0, 0});
      }
      if (dc >= 0) out.push_back(cur);
    }
    v = out;
  }
  std::vector<std::pair<double, double>> screen;
  if (v.size() < 3) return screen;
  for (const H& h : v) screen.emplace_back(h.x / h.w, h.y / h.w);
  return screen;
}

TcPolygon quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  TcPolygon p;
  p.vertex = {a, b, c, d};
  const Vec3 n = glm::normalize(glm::cross(b - a, d - a));
  p.normal = {n, n, n, n};
  p.colour = Color(0.9, 0.5, 0.25);
  return p;
}

std::vector<TcProcessor> run(const std::vector<TcPolygon>& polygons, const TcLiterals& lit) {
  std::vector<TcProcessor> procs(polygons.size());
  for (std::size_t k = 0; k < polygons.size(); ++k) load_polygon(procs[k], polygons[k]);
  broadcast(build_tc_program(lit), procs);
  return procs;
}

TEST(TcProgram, ItsInstructionCountsAreTheProgramsBesideFig316) {
  const BroadcastProgram p = build_tc_program(camera_literals());
  const std::uint32_t fig316[kTcTasks] = {272, 153, 1904, 152, 1171};
  std::printf("%-32s %8s %8s\n", "task", "program", "Fig.3-16");
  for (int t = 0; t < kTcTasks; ++t)
    std::printf("%-32s %8u %8u\n", std::string(kTcTaskNames[static_cast<std::size_t>(t)]).c_str(),
                p.count[static_cast<std::size_t>(t)], fig316[t]);
  std::printf("%-32s %8u %8u\n", "total", p.total(), 3652u);
  EXPECT_EQ(p.total(), p.code.size());
  // The literals change the program's literals, not its length.
  TcLiterals other = camera_literals();
  other.matrix[0][0] = 2.0f;
  EXPECT_EQ(build_tc_program(other).count, p.count);
}

TEST(TcProgram, ClippedPolygonsAreTheReferenceClippersAndEveryChainRunsTopToBottom) {
  const TcLiterals lit = camera_literals();
  std::vector<TcPolygon> polys = {
      // Inside.
      quad({-1, -1, 5}, {1, -1, 5}, {1, 1, 5}, {-1, 1, 5}),
      // Across the right and top planes.
      quad({0, 0, 4}, {8, 0, 4}, {8, 8, 4}, {0, 8, 4}),
      // Across the near plane (z = 1), tilted.
      quad({-1, -1, 0.2}, {1, -1, 0.2}, {1, 1, 6}, {-1, 1, 6}),
      // Outside to the left; behind the eye.
      quad({-30, -1, 5}, {-20, -1, 5}, {-20, 1, 5}, {-30, 1, 5}),
      quad({-1, -1, -5}, {1, -1, -5}, {1, 1, -5}, {-1, 1, -5}),
      // Triangles as quadrilaterals with a repeated vertex, at the bottom and at the top.
      quad({-2, 2, 5}, {-3, -2, 5}, {2, -1, 5}, {2, -1, 5}),
      quad({0, 2, 5}, {0, 2, 5}, {-2, -1, 5}, {3, -2, 5}),
      // Clockwise on the screen, across four planes.
      quad({-9, -9, 6}, {-9, 9, 6}, {9, 9, 6}, {9, -9, 6}),
  };
  std::mt19937 rng(1983);
  std::uniform_real_distribution<double> u(-6.0, 6.0), depth(0.5, 12.0);
  for (int k = 0; k < 200; ++k) {
    // A random convex quadrilateral: a parallelogram.
    const Vec3 o(u(rng), u(rng), depth(rng)), e1(u(rng), u(rng), u(rng) * 0.3),
        e2(u(rng), u(rng), u(rng) * 0.3);
    polys.push_back(quad(o, o + e1, o + e1 + e2, o + e2));
  }
  const auto procs = run(polys, lit);
  int clipped_away = 0;
  for (std::size_t k = 0; k < polys.size(); ++k) {
    SCOPED_TRACE(k);
    const auto want = reference(polys[k], lit);
    const EdgeChains got = edge_chains(procs[k].sent);
    if (want.empty()) {
      ++clipped_away;
      EXPECT_TRUE(procs[k].sent.empty());
      continue;
    }
    ASSERT_FALSE(got.empty());
    // Every entry is one of the reference's vertices, quantized; each chain runs downwards and
    // both start at the top vertex and end at the same height.
    for (const auto* chain : {&got.left, &got.right}) {
      for (std::size_t e = 0; e < chain->size(); ++e) {
        const EdgeEntry& en = (*chain)[e];
        double best = 1e9;
        for (const auto& [x, y] : want) best = std::min(best, std::hypot(x - en.x, y - en.y));
        EXPECT_LT(best, 2e-3) << "entry " << e << " at " << en.x << ", " << en.y;
        if (e > 0) {
          EXPECT_LE(en.y, (*chain)[e - 1].y);
        }
      }
      EXPECT_EQ(chain->front().y, got.left.front().y);
      EXPECT_EQ(chain->back().y, got.left.back().y);
    }
    // The left chain is left of the right one: at the top (the leftmost top vertex) and along.
    EXPECT_LE(got.left.front().x, got.right.front().x);
    // The top vertex twice, the bottom twice, and a level bottom edge in both chains.
    EXPECT_LE(got.left.size() + got.right.size(), want.size() + 3);
  }
  EXPECT_GE(clipped_away, 2);
  std::printf("%zu polygons, %d clipped away\n", polys.size(), clipped_away);
}

TEST(TcProgram, GouraudColoursFollowFig311) {
  const TcLiterals lit = camera_literals();
  // Facing the light (n = (0, 0, -1), p = (0, 0, -1)): d = 1, r = (0.2 + 0.8) 0.9.
  const auto procs = run({quad({-1, -1, 5}, {-1, 1, 5}, {1, 1, 5}, {1, -1, 5})}, lit);
  const EdgeChains c = edge_chains(procs[0].sent);
  ASSERT_FALSE(c.empty());
  EXPECT_NEAR(c.left.front().r, 0.9, 1.0 / 4095);
  EXPECT_NEAR(c.left.front().g, (0.2 + 0.7) * 0.5, 1.0 / 4095);
  EXPECT_NEAR(c.left.front().b, (0.2 + 0.6) * 0.25, 1.0 / 4095);
  // Facing away: ambient only.
  const auto away = run({quad({-1, -1, 5}, {1, -1, 5}, {1, 1, 5}, {-1, 1, 5})}, lit);
  const EdgeChains a = edge_chains(away[0].sent);
  ASSERT_FALSE(a.empty());
  EXPECT_NEAR(a.left.front().r, 0.2 * 0.9, 1.0 / 4095);
}

TEST(TcProcessor, AShutDownProcessorIgnoresAllButReset) {
  TcProcessor p;
  p.memory[3] = 2.0f;
  p.execute({Op::Literal, 0, kNoIndex, 0, 0, 5.0f});
  p.execute({Op::OffIfGreater, 3});
  EXPECT_TRUE(p.off);
  p.execute({Op::Literal, 0, kNoIndex, 0, 0, 7.0f});
  p.execute({Op::Send, 0});
  EXPECT_EQ(p.acc, 5.0f);
  EXPECT_TRUE(p.sent.empty());
  p.execute({Op::Reset, 0});
  p.execute({Op::Send, 0});
  EXPECT_EQ(p.sent.size(), 1u);
  // Indexed addresses wrap as 8-bit addresses do; a garbage index stays in memory.
  p.ix[0] = 300;
  p.execute({Op::Store, 250, 0});
  EXPECT_EQ(p.memory[(250 + 300) % 256], 5.0f);
  p.memory[9] = std::nanf("");
  p.execute({Op::IndexLoad, 9, kNoIndex, 1});
  EXPECT_EQ(p.ix[1], 0);
}

}  // namespace
