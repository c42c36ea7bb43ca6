// pxpl5-raytrace's sampling (seed 004 L352-L379): rays every `finest` pixels resampled by the
// renderers, adaptive squares refined from one ray per 16 x 16 to one per 4 x 4 (partial or
// conventional subdivision), partial updating at 50% and 25%. In every case the image built from
// the samples that crossed the ring equals the functional twin's render with the same rule, a
// sample changed on the ring changes it, and the counts of rays follow the rule.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::test::read_file;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;
using rtsim::test::shared_path;

namespace {

nlohmann::ordered_json run_pxpl5(const std::string& tag, const std::string& args) {
  return rtsim::test::run_machine("pxpl5-raytrace", tag, args);
}

const std::string kAdaptive = " -p sampling.finest=4 -p sampling.start=16";

std::string balls(int w, int h) {
  return "--scene " + shared_path("scenes/balls-s2.nff") + " --width " + std::to_string(w) +
         " --height " + std::to_string(h);
}

double rays_per_pixel(const nlohmann::ordered_json& s) {
  return s.empty() ? 0.0 : s["pxpl5"]["rays_per_pixel"].get<double>();
}

TEST(Pxpl5Sampling, TheImageEqualsTheTwinsForEveryRule) {
  // 100 x 70: the lattice runs one position past the last column and row, squares are cut at
  // the image's edge, tiles are partial.
  for (const char* variant :
       {" -p sampling.finest=4", " -p sampling.finest=2 -p assign.scheme=rows",
        " -p sampling.finest=4 -p sampling.start=16 -p assign.square=32",
        " -p sampling.finest=2 -p sampling.start=8 -p sampling.subdivision=conventional "
        "-p caster_count=3 -p compositor_count=2 -p compositor.band_rows=16",
        " -p sampling.finest=2 -p sampling.start=16 -p sampling.object_edges=false "
        "-p sampling.threshold=0.01",
        " -p update.fraction=50 -p frames=3 -p camera.spin=4",
        " -p sampling.finest=2 -p update.fraction=25 -p frames=6 -p camera.spin=3 "
        "-p assign.scheme=rows",
        " -p sampling.finest=4 -p camera.distance=3 -p render.spp=2"}) {
    const auto s = run_pxpl5("twin", balls(100, 70) + variant + " --overhead --aov id,depth");
    ASSERT_FALSE(s.empty()) << variant;
    EXPECT_TRUE(s.at("functional_image_identical").get<bool>()) << variant;
  }
  // `rtsim render --machine` draws the twin's image: the same file.
  const std::string args = balls(96, 64) + kAdaptive;
  const fs::path golden = scratch_dir("pxpl5-sampled-golden");
  const auto g =
      run_rtsim("render --machine pxpl5-raytrace " + args + " -q --out " + golden.string());
  ASSERT_EQ(g.exit_code, 0) << g.output;
  const auto s = run_pxpl5("sampled-run", args);
  ASSERT_FALSE(s.empty());
  EXPECT_EQ(read_file(golden / "image.png"), read_file(s.at("image_png").get<std::string>()));
  fs::remove_all(golden);
}

TEST(Pxpl5Sampling, ASampleChangedOnTheRingChangesTheSampledImage) {
  const std::string args = balls(128, 128) + kAdaptive;
  const auto clean = run_pxpl5("sampled-clean", args);
  const auto bad = run_pxpl5("sampled-bad", args + " -p fault.corrupt_samples=2");
  ASSERT_FALSE(clean.empty() || bad.empty());
  EXPECT_NE(read_file(clean.at("image_png").get<std::string>()),
            read_file(bad.at("image_png").get<std::string>()));
}

// One ray per 16 x 16 refined to one per 4 x 4 (L369) casts more rays than the start grid and
// fewer than the finest; partial subdivision fewer than conventional (L362); fewer rays, a
// shorter frame.
TEST(Pxpl5Sampling, AdaptiveSquaresCastBetweenTheStartAndTheFinestGrid) {
  const std::string base = balls(320, 256);
  const auto every = run_pxpl5("rays-every", base);
  const auto finest = run_pxpl5("rays-4", base + " -p sampling.finest=4");
  const auto start = run_pxpl5("rays-16", base + " -p sampling.finest=16");
  const auto partial = run_pxpl5("rays-partial", base + kAdaptive);
  const auto conventional =
      run_pxpl5("rays-conv", base + kAdaptive + " -p sampling.subdivision=conventional");
  std::printf(
      "rays a pixel: every pixel %.4f, every 4 x 4 %.4f, every 16 x 16 %.4f, 16 -> 4 partial "
      "%.4f, conventional %.4f\n",
      rays_per_pixel(every), rays_per_pixel(finest), rays_per_pixel(start), rays_per_pixel(partial),
      rays_per_pixel(conventional));
  EXPECT_DOUBLE_EQ(rays_per_pixel(every), 1.0);
  EXPECT_GT(rays_per_pixel(partial), rays_per_pixel(start));
  EXPECT_LT(rays_per_pixel(partial), rays_per_pixel(conventional));
  EXPECT_LT(rays_per_pixel(conventional), rays_per_pixel(finest));
  EXPECT_LT(rays_per_pixel(finest), rays_per_pixel(every));
}

// Fewer rays make a shorter frame where there are regions enough to share: at VOL2's 640 x 512
// (80 squares on 16 casters). At 320 x 256 (20 squares) the frame is the costliest square's
// time, where adaptive sampling refines almost everywhere and casts its replicated edges too.
TEST(Pxpl5Sampling, AdaptiveSquaresShortenVol2sFrame) {
  const std::string base = balls(640, 512) + " -p frames=2 -p camera.spin=1";
  const auto finest = run_pxpl5("frame-4", base + " -p sampling.finest=4");
  const auto adaptive = run_pxpl5("frame-adaptive", base + kAdaptive);
  ASSERT_FALSE(finest.empty() || adaptive.empty());
  const double a = adaptive["pxpl5"]["frame_times_s"].back().get<double>();
  const double u = finest["pxpl5"]["frame_times_s"].back().get<double>();
  std::printf("640 x 512, second frame: every 4 x 4 %.4g ms, 16 -> 4 adaptive %.4g ms\n", u * 1e3,
              a * 1e3);
  EXPECT_LT(a, 0.8 * u);
}

// Partial updating (L373-L379): at 25% each position is cast once every 4 frames, so with the
// camera still the fifth frame's image is the full update's, and the frames after the first cast
// a quarter of the rays in less time.
TEST(Pxpl5Sampling, PartialUpdatingCastsAQuarterAFrameAndFillsInAfterFour) {
  const std::string base = balls(128, 128) + " -p sampling.finest=2";
  const auto full = run_pxpl5("update-full", base);
  const auto quarter = run_pxpl5("update-25", base + " -p update.fraction=25 -p frames=5");
  ASSERT_FALSE(full.empty() || quarter.empty());
  EXPECT_EQ(read_file(full.at("image_png").get<std::string>()),
            read_file(quarter.at("image_png").get<std::string>()));
  // Frame 0 casts every position, frames 1-4 a quarter each: 2 frames' worth of rays in 5.
  EXPECT_NEAR(rays_per_pixel(quarter), 2.0 / 5.0 * rays_per_pixel(full),
              0.01 * rays_per_pixel(full));
  const auto& t = quarter["pxpl5"]["frame_times_s"];
  std::printf("25%% updating: first frame %.4g ms, then %.4g %.4g %.4g %.4g ms\n",
              t[0].get<double>() * 1e3, t[1].get<double>() * 1e3, t[2].get<double>() * 1e3,
              t[3].get<double>() * 1e3, t[4].get<double>() * 1e3);
  for (int f = 1; f < 5; ++f) EXPECT_LT(t[f].get<double>(), 0.5 * t[0].get<double>());
}

TEST(Pxpl5Sampling, ImpossibleRulesAreBadInput) {
  for (const auto& [args, says] :
       {std::pair<std::string, std::string>{"-p sampling.finest=3", "power of two"},
        {"-p sampling.finest=4 -p sampling.start=2", "at least sampling.finest"},
        {"-p sampling.finest=4 -p sampling.start=16 -p update.fraction=25", "partial updating"},
        {"-p sampling.finest=4 -p sampling.start=128", "must divide the square"}}) {
    const fs::path dir = scratch_dir("pxpl5-bad-rule");
    const auto r = run_rtsim(
        "run --machine pxpl5-raytrace --scene builtin:default --width 64 "
        "--height 64 " +
        args + " -q --out " + dir.string());
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir / "image.png"));
  }
}

}  // namespace
