// builtin:ullner-sheets-N: Ullner's Fig. 2-18 scene read literally (seed 000 L654): total area
// a_t = 2 as two sheets through the unit modelling cube, rays travelling d_r ~ 1/2 of it.
#include <gtest/gtest.h>

#include <cmath>

#include "common/input_error.hpp"
#include "firmware/kernels/ullner_quad.hpp"
#include "firmware/shading/camera.hpp"
#include "scenes/generators/ullner_sheets.hpp"
#include "scenes/scene_loader.hpp"

using namespace rtsim;
using namespace rtsim::scenes;

TEST(UllnerSheetsScene, TwoSheetsOfTotalAreaTwoInTheUnitCube) {
  const Scene s = make_ullner_sheets(1000);
  EXPECT_EQ(s.polygons.size(), 2u * 22u * 22u);  // k = round(sqrt(500)) = 22
  EXPECT_EQ(s.primitives.size(), s.polygons.size());
  EXPECT_TRUE(s.lights.empty());
  ASSERT_FALSE(s.modelling_space.empty());
  EXPECT_EQ(s.modelling_space.lo, Vec3(0.0));
  EXPECT_EQ(s.modelling_space.hi, Vec3(1.0));
  double area = 0.0;
  for (const auto& q : s.polygons) {
    ASSERT_EQ(q.vertices.size(), 4u);
    for (const auto& v : q.vertices)
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(v[a], 0.0);
        EXPECT_LE(v[a], 1.0);
      }
    area +=
        0.5 * glm::length(glm::cross(q.vertices[2] - q.vertices[0], q.vertices[3] - q.vertices[1]));
    // Every quad is a valid convex Ullner polygon.
    EXPECT_TRUE(
        kernels::UllnerQuadKernel::from(q.vertices[0], q.vertices[1], q.vertices[2], q.vertices[3])
            .has_value());
  }
  // The tilts add sqrt(1 + a^2 + b^2) - 1 < 0.5% to each unit sheet.
  std::printf("a_t = %.5f (target 2, tilted sheets: within 0.5%%)\n", area);
  EXPECT_NEAR(area, 2.0, 0.01);
}

TEST(UllnerSheetsScene, PrimaryRaysTravelHalfTheModellingSpace) {
  // Every primary ray enters the cube at y = 0 and stops at the first sheet (y ~ 1/2): measured
  // over all 64 x 64 primary rays by brute force over Ullner's quad kernel; accepted d_r in
  // [0.45, 0.55] and every ray hits.
  const Scene s = make_ullner_sheets(1000);
  std::vector<kernels::UllnerQuadKernel> quads;
  for (const auto& q : s.polygons)
    quads.push_back(*kernels::UllnerQuadKernel::from(q.vertices[0], q.vertices[1], q.vertices[2],
                                                     q.vertices[3]));
  const shading::PinholeCamera camera(s.camera, 64, 64);
  double travel = 0.0;
  int hits = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const Ray r = camera.primary(x + 0.5, y + 0.5);
      double t_in = 0.0, t_out = 0.0;
      ASSERT_TRUE(s.modelling_space.intersect(r, 0.0, kInfinity, t_in, t_out));
      double nearest = kInfinity;
      SurfaceHit h;
      for (const auto& q : quads)
        if (q.intersect(r, 0.0, nearest, h)) nearest = h.t;
      if (std::isfinite(nearest)) {
        ++hits;
        travel += nearest - t_in;
      }
    }
  const double d_r = travel / hits;
  std::printf("d_r = %.4f (target 0.5, accepted [0.45, 0.55]); %d of 4096 rays hit\n", d_r, hits);
  EXPECT_EQ(hits, 64 * 64);
  EXPECT_GE(d_r, 0.45);
  EXPECT_LE(d_r, 0.55);
}

TEST(UllnerSheetsScene, LoadsByNameAndRejectsBadCounts) {
  EXPECT_EQ(load_scene("builtin:ullner-sheets-1000").polygons.size(), 968u);
  EXPECT_EQ(load_scene("builtin:ullner-sheets-200").polygons.size(), 200u);
  EXPECT_THROW(load_scene("builtin:ullner-sheets-1"), rtsim::InputError);
  EXPECT_FALSE(parse_ullner_sheets_name("ullner-sheets-01").has_value());
  EXPECT_FALSE(parse_ullner_sheets_name("ullner-sheets-").has_value());
}

TEST(UllnerSheetsScene, TheLitVariantHasOneLightAtTheEye) {
  // The ray-tracing pipeline's "doubling for shadowing" (seed 000 L743): the same sheets, and
  // one light where the eye is, so every hit's shadow ray runs back along its vision ray.
  const auto plain = load_scene("builtin:ullner-sheets-1000");
  const auto lit = load_scene("builtin:ullner-sheets-lit-1000");
  EXPECT_TRUE(plain.lights.empty());
  ASSERT_EQ(lit.lights.size(), 1u);
  EXPECT_EQ(lit.lights[0].position, lit.camera.from);
  ASSERT_EQ(lit.polygons.size(), plain.polygons.size());
  EXPECT_EQ(lit.polygons[17].vertices, plain.polygons[17].vertices);
  bool is_lit = false;
  EXPECT_EQ(parse_ullner_sheets_name("ullner-sheets-lit-200", &is_lit), 200u);
  EXPECT_TRUE(is_lit);
  EXPECT_EQ(parse_ullner_sheets_name("ullner-sheets-200", &is_lit), 200u);
  EXPECT_FALSE(is_lit);
  EXPECT_FALSE(parse_ullner_sheets_name("ullner-sheets-lit-").has_value());
}
