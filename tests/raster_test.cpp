// The rasterization layer (firmware/raster/) and PixelFlow's functional passes: exact coverage on
// shared edges, order-independent z-compositing, the Fig. 8 record's bytes, the views' round
// trips, and the bowling frame rendered whole.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <random>

#include "firmware/raster/appearance.hpp"
#include "firmware/raster/raster_mesh.hpp"
#include "firmware/raster/region_samples.hpp"
#include "firmware/raster/screen_triangle.hpp"
#include "firmware/raster/table_maps.hpp"
#include "platform/machines/pixelflow/functional_passes.hpp"
#include "scenes/generators/bowling.hpp"
#include "scenes/scene_loader.hpp"

namespace rtsim {
namespace {

using raster::RegionGrid;
using raster::RegionSampleGrid;

/// A camera looking down -z at the unit square [0, 1]^2 at z = 0, from z = 2.
scenes::Camera square_camera() {
  scenes::Camera c;
  c.from = Vec3(0.5, 0.5, 2.0);
  c.at = Vec3(0.5, 0.5, 0.0);
  c.up = Vec3(0.0, 1.0, 0.0);
  c.angle_deg = 40.0;
  return c;
}

raster::RasterTriangle flat(const Vec3& a, const Vec3& b, const Vec3& c,
                            std::uint32_t material = 0) {
  raster::RasterTriangle t;
  const Vec3 n(0.0, 0.0, 1.0);
  t.v = {raster::RasterVertex{a, n, {a.x, a.y}}, raster::RasterVertex{b, n, {b.x, b.y}},
         raster::RasterVertex{c, n, {c.x, c.y}}};
  t.face_normal = n;
  t.material = material;
  return t;
}

TEST(Raster, TrianglesSharingAnEdgeCoverEverySampleOnceAcrossManyRandomSplits) {
  // A fan of triangles round a random interior point tiles a quad exactly: every sample inside
  // is covered by exactly one triangle (the top-left rule on exact integer edge functions).
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  for (int trial = 0; trial < 20; ++trial) {
    raster::RasterMesh mesh;
    const Vec3 centre(u(rng), u(rng), 0.0);
    const std::array<Vec3, 4> corner = {Vec3(0.0, 0.0, 0.0), Vec3(1.0, 0.0, 0.0),
                                        Vec3(1.0, 1.0, 0.0), Vec3(0.0, 1.0, 0.0)};
    for (int i = 0; i < 4; ++i)
      mesh.triangles.push_back(flat(corner[i], corner[(i + 1) % 4], centre));
    for (const auto& t : mesh.triangles)
      for (const auto& v : t.v) mesh.bounds.extend(v.position);
    mesh.bounds.extend(Vec3(0.0, 0.0, -1.0));
    const auto view = raster::ViewTransform::camera(square_camera(), 128, 64, mesh.bounds);
    const auto setup = raster::set_up_view(mesh, view, {raster::MaterialWord{}});
    ASSERT_EQ(setup.front_facing, 4u);
    const RegionGrid grid{128, 64};
    for (int s = 0; s < 5; ++s) {
      raster::RegionDepths region(RegionSampleGrid::of(grid, 0, s));
      std::vector<int> hits(raster::kRegionPixels, 0);
      std::size_t covered = 0;
      for (const auto& t : setup.triangles) {
        raster::RegionDepths one(region.at);
        covered += raster::scan_depth(t, view, one).covered;
        for (int i = 0; i < raster::kRegionPixels; ++i)
          hits[static_cast<std::size_t>(i)] +=
              one.depth[static_cast<std::size_t>(i)] != raster::kBackgroundDepth;
      }
      // The quad's samples: covered by one triangle each, never two.
      EXPECT_EQ(*std::max_element(hits.begin(), hits.end()), 1) << "trial " << trial;
      EXPECT_EQ(covered, static_cast<std::size_t>(std::count(hits.begin(), hits.end(), 1)));
      EXPECT_GT(covered, 1000u);
    }
  }
}

TEST(Raster, TheRecordTravelsAsItsThirtyFourBytes) {
  raster::Appearance a;
  a.depth = 0x12345678u;
  a.shader = 3;
  a.colour = {1, 2, 250};
  a.normal = {-32767, 5, 32767};
  a.u = 65535;
  a.v = 7;
  a.footprint_u = 300;
  a.footprint_v = 65535;
  a.dp_dx = {-1, 0, 1};
  a.dp_dy = {32767, -32767, 12};
  const raster::AppearanceWord w = raster::pack(a);
  EXPECT_EQ(w.size(), 34u);  // seed 004 L110
  EXPECT_EQ(raster::pack(raster::unpack(w)), w);
  // Depth first: the composition order compares it before anything else.
  raster::Appearance b = a;
  b.depth = a.depth - 1;
  b.shader = 255;
  EXPECT_TRUE(raster::nearer(raster::pack(b), w));
  EXPECT_FALSE(raster::nearer(w, raster::pack(b)));
  EXPECT_TRUE(raster::nearer(w, raster::background_word()));
}

TEST(Raster, ViewsProjectAndRebuildTheSamePoint) {
  Bounds b;
  b.extend(Vec3(-1.0));
  b.extend(Vec3(1.0));
  scenes::Camera cam;
  cam.from = Vec3(3.0, -4.0, 2.0);
  cam.at = Vec3(0.0);
  cam.up = Vec3(0.0, 0.0, 1.0);
  for (const auto& view : {raster::ViewTransform::camera(cam, 640, 512, b),
                           raster::ViewTransform::enclosing(Vec3(0.5, -2.0, 6.0), b, b, 512)}) {
    const Vec3 p(0.3, -0.7, 0.2);
    const Vec3 e = view.to_eye(p);
    const Vec3 back = view.world_at(view.screen_x(e), view.screen_y(e), e.z);
    EXPECT_LT(glm::length(back - p), 1e-12);
    // Through the depth word: within its step.
    const Vec3 q =
        view.world_at(view.screen_x(e), view.screen_y(e), view.depth_of(view.depth_word(e.z)));
    EXPECT_LT(glm::length(q - p), 1e-8);
    EXPECT_GT(e.z, view.near);
    EXPECT_LT(e.z, view.far);
  }
}

/// Renders builtin:bowling with the functional passes at `w` x `h` x `spp`.
functional::RenderResult render_bowling(int w, int h, int spp, std::size_t* triangles = nullptr) {
  const scenes::Scene scene = scenes::make_bowling();
  const auto f = platform::pixelflow::make_frame_setup(scene, {}, w, h, spp);
  if (triangles) *triangles = f.mesh.triangles.size();
  const auto maps = platform::pixelflow::render_maps(f);
  functional::FrameState frame(w, h, spp, false, false);
  platform::pixelflow::render_camera(f, maps, frame);
  return frame.finish(0.0);
}

TEST(Raster, TheBowlingFrameHasTheSeedsTrianglesAndRendersWhole) {
  std::size_t triangles = 0;
  const auto image = render_bowling(160, 128, 2, &triangles);
  // About 10,700 triangles (seed 004 L93).
  std::cout << "bowling: " << triangles << " triangles (seed 004 L93: 10,700)\n";
  EXPECT_NEAR(static_cast<double>(triangles), 10700.0, 300.0);
  double sum = 0.0;
  for (float c : image.rgb) {
    ASSERT_TRUE(std::isfinite(c));
    sum += c;
  }
  EXPECT_GT(sum / static_cast<double>(image.rgb.size()), 0.05);
  // The same frame twice: the same floats.
  EXPECT_EQ(render_bowling(160, 128, 2).rgb, image.rgb);
  if (const char* out = std::getenv("RTSIM_RASTER_IMAGE")) {
    const auto full = render_bowling(640, 512, 5);
    auto file = OIIO::ImageOutput::create(out);
    ASSERT_TRUE(file);
    OIIO::ImageSpec spec(full.width, full.height, 3, OIIO::TypeDesc::FLOAT);
    ASSERT_TRUE(file->open(out, spec));
    ASSERT_TRUE(file->write_image(OIIO::TypeDesc::FLOAT, full.rgb.data()));
    file->close();
  }
}

}  // namespace
}  // namespace rtsim
