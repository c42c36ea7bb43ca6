// End-to-end tests of `rtsim render`: outputs, determinism, AOVs, bad input.
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::test::compare_images;
using rtsim::test::read_file;
using rtsim::test::read_json;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;
using rtsim::test::shared_path;

namespace {

std::vector<float> read_channel(const fs::path& p) {
  rtsim::test::forget_cached_image(p.string());
  OIIO::ImageBuf buf(p.string());
  EXPECT_TRUE(buf.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << p;
  const auto& spec = buf.spec();
  std::vector<float> v(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  buf.get_pixels(buf.roi(), OIIO::TypeDesc::FLOAT, v.data());
  return v;
}

}  // namespace

TEST(RenderCli, WritesImageExrAndStatsWithStableKeys) {
  const auto dir = scratch_dir("render-basic");
  const auto r =
      run_rtsim("render --scene builtin:default --width 64 --height 48 -q --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"image.png", "image.exr", "stats.json"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  EXPECT_FALSE(fs::exists(dir / "id.exr"));
  const auto s = read_json(dir / "stats.json");
  EXPECT_EQ(s["machine"], "functional");
  EXPECT_EQ(s["scene"], "builtin:default");
  EXPECT_EQ(s["width"], 64);
  EXPECT_EQ(s["height"], 48);
  EXPECT_EQ(s["rays"]["primary"], 64 * 48);
  const auto& rays = s["rays"];
  EXPECT_EQ(rays["total"].get<std::uint64_t>(),
            rays["primary"].get<std::uint64_t>() + rays["shadow"].get<std::uint64_t>() +
                rays["reflected"].get<std::uint64_t>() + rays["refracted"].get<std::uint64_t>());
  EXPECT_GT(rays["shadow"].get<std::uint64_t>(), 0u);
  EXPECT_GT(rays["reflected"].get<std::uint64_t>(), 0u);
  EXPECT_GT(rays["refracted"].get<std::uint64_t>(), 0u);
  EXPECT_GT(s["intersection_tests"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(s["image"]["nonfinite_values"], 0);
  EXPECT_TRUE(s["params"].contains("shade.max_depth"));
  // No staging folder is left behind.
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().rfind(".rtsim-partial", 0), std::string::npos);
}

TEST(RenderCli, SameInputsGiveByteIdenticalImagesForAnyThreadCount) {
  const auto a = scratch_dir("render-det-a");
  const auto b = scratch_dir("render-det-b");
  const std::string common =
      "render --scene " + shared_path("scenes/balls-s1.nff") + " --width 96 --height 96 -q";
  ASSERT_EQ(run_rtsim(common + " --threads 1 --out " + a.string()).exit_code, 0);
  ASSERT_EQ(run_rtsim(common + " --threads 3 --out " + b.string()).exit_code, 0);
  EXPECT_EQ(read_file(a / "image.png"), read_file(b / "image.png"));
  EXPECT_EQ(read_file(a / "image.exr"), read_file(b / "image.exr"));
  const auto sa = read_json(a / "stats.json");
  const auto sb = read_json(b / "stats.json");
  EXPECT_EQ(sa["rays"], sb["rays"]);
  EXPECT_EQ(sa["intersection_tests"], sb["intersection_tests"]);
}

TEST(RenderCli, AovsHoldPrimitiveIndexAndDepth) {
  const auto dir = scratch_dir("render-aov");
  const auto r = run_rtsim("render --scene " + shared_path("scenes/balls-s1.nff") +
                           " --width 64 --height 64 --aov id,depth -q --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto id = read_channel(dir / "id.exr");
  const auto depth = read_channel(dir / "depth.exr");
  ASSERT_EQ(id.size(), 64u * 64u);
  ASSERT_EQ(depth.size(), id.size());
  // balls-s1: primitive 0 is the floor polygon, 1..10 the spheres (scene-file order).
  std::size_t misses = 0, floor = 0, spheres = 0;
  for (std::size_t i = 0; i < id.size(); ++i) {
    ASSERT_EQ(id[i], std::floor(id[i]));
    ASSERT_GE(id[i], -1.0f);
    ASSERT_LE(id[i], 10.0f);
    if (id[i] < 0) {
      ++misses;
      EXPECT_TRUE(std::isinf(depth[i]));
    } else {
      EXPECT_TRUE(std::isfinite(depth[i]) && depth[i] > 0.0f);
      (id[i] == 0 ? floor : spheres)++;
    }
  }
  std::cout << "balls-s1 64x64: " << misses << " miss, " << floor << " floor, " << spheres
            << " sphere pixels\n";
  EXPECT_GT(floor, 0u);
  EXPECT_GT(spheres, 0u);
  // The centre of the view looks at the big sphere at the origin (primitive 1).
  EXPECT_EQ(id[32 * 64 + 32], 1.0f);
  // Depth of the centre pixel: the eye is |from| = |(2.1,1.3,1.7)| = 3.0 from the origin and
  // the sphere's radius is 0.5, so the hit is about 2.5 away.
  EXPECT_NEAR(depth[32 * 64 + 32], 2.5, 0.05);
}

TEST(RenderCli, AccelerationStructuresAgree) {
  // The grid, the shell hierarchy and brute force find the same primitives and pixels.
  std::vector<fs::path> dirs;
  for (const char* accel : {"none", "grid", "shells"}) {
    const auto dir = scratch_dir(std::string("render-accel-") + accel);
    const auto r = run_rtsim("render --scene " + shared_path("scenes/balls-s2.nff") +
                             " --width 80 --height 80 --aov id -q -p render.accel=" + accel +
                             " --out " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    dirs.push_back(dir);
  }
  const auto ref = read_channel(dirs[0] / "id.exr");
  for (std::size_t k = 1; k < dirs.size(); ++k) {
    const auto ids = read_channel(dirs[k] / "id.exr");
    std::size_t differ = 0;
    for (std::size_t i = 0; i < ref.size(); ++i) differ += ref[i] != ids[i];
    const auto cr = compare_images((dirs[0] / "image.exr").string(),
                                   (dirs[k] / "image.exr").string(), 1.0f / 255.0f);
    std::cout << dirs[k].filename() << ": " << differ << " id pixels differ; image max error "
              << cr.maxerror << ", " << cr.nfail << " pixels over 1/255\n";
    EXPECT_EQ(differ, 0u);
    EXPECT_EQ(cr.nfail, 0u);
  }
}

TEST(RenderCli, BadSceneIsReportedWithFileAndLineAndWritesNothing) {
  const auto dir = scratch_dir("render-bad-scene");
  const auto r = run_rtsim("render --scene " + std::string(RTSIM_TEST_DATA_DIR) +
                           "/bad-truncated-polygon.nff --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("bad-truncated-polygon.nff:"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir));
}

TEST(RenderCli, MissingSceneAndUnknownBuiltinAreBadInput) {
  const auto dir = scratch_dir("render-missing");
  auto r = run_rtsim("render --scene /nonexistent/x.nff --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = run_rtsim("render --scene builtin:defualt --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("default"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir));
}

TEST(RenderCli, UnknownOrBadParameterIsBadInputWithSuggestion) {
  const auto dir = scratch_dir("render-bad-param");
  auto r = run_rtsim("render -p shade.max_dpth=3 --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("shade.max_depth"), std::string::npos) << r.output;
  r = run_rtsim("render -p render.accel=gird --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("grid"), std::string::npos) << r.output;
  r = run_rtsim("render -p shade.max_depth=-1 --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = run_rtsim("render --width 0 --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = run_rtsim("render --bogus --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_FALSE(fs::exists(dir));
}

TEST(RenderCli, HelpAndListWork) {
  auto r = run_rtsim("--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.output.find("render"), std::string::npos);
  r = run_rtsim("render --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.output.find("--aov"), std::string::npos);
  r = run_rtsim("list scenes");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.output.find("npp-204"), std::string::npos);
  r = run_rtsim("list params");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.output.find("bezier.iterations"), std::string::npos);
  EXPECT_NE(r.output.find("Wang, Lewis & Hung c. 2000, line 284"), std::string::npos);
}

TEST(RenderCli, UllnerQuadAndTriangleKernelsRenderTheSamePolygons) {
  // Polygons as Ullner's convex quadrilaterals (seed 000 §2.2) or as watertight triangles:
  // the same primitives are hit. Only pixels whose primary ray passes within rounding of a
  // polygon's outer edge may differ (the two tests' tie rules differ there).
  for (const char* scene : {"scenes/tetra-s3.nff", "scenes/teapot-s2.nff"}) {
    std::vector<fs::path> dirs;
    for (const char* kernel : {"triangle", "ullner-quad"}) {
      const auto dir = scratch_dir(std::string("render-kernel-") + kernel);
      const auto r =
          run_rtsim("render --scene " + shared_path(scene) +
                    " --width 96 --height 96 --aov id -q -p render.polygon_kernel=" + kernel +
                    " --out " + dir.string());
      ASSERT_EQ(r.exit_code, 0) << r.output;
      dirs.push_back(dir);
    }
    const auto a = read_channel(dirs[0] / "id.exr");
    const auto b = read_channel(dirs[1] / "id.exr");
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.size(); ++i) differ += a[i] != b[i];
    const auto cr = compare_images((dirs[0] / "image.png").string(),
                                   (dirs[1] / "image.png").string(), 2.0f / 255.0f);
    std::cout << scene << ": " << differ << " of " << a.size() << " id pixels differ; " << cr.nfail
              << " image pixels over 2/255 (max error " << cr.maxerror << ")\n";
    EXPECT_LE(differ, a.size() / 500) << "more than 0.2% of primary hits disagree";
    EXPECT_LE(cr.nfail, a.size() / 200) << "more than 0.5% of pixels differ visibly";
  }
}
