// pxpl5-raytrace's sampling (seed 004 L352-L379): rays every `finest` pixels resampled by the
// renderers, adaptive squares refined from one ray per 16 x 16 to one per 4 x 4 (partial or
// conventional subdivision), partial updating at 50% and 25%. In every case the image built from
// the samples that crossed the ring equals the functional twin's render with the same rule, a
// sample changed on the ring changes it, and the counts of rays follow the rule.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

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

/// A run with `args` is refused (exit 2) with a message containing `says`, and writes no image.
void expect_bad_input(const std::string& args, const std::string& says) {
  const fs::path dir = scratch_dir("pxpl5-bad-input");
  const auto r =
      run_rtsim("run --machine pxpl5-raytrace --scene builtin:default --width 64 --height 64 " +
                args + " -q --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
  EXPECT_NE(r.output.find(says), std::string::npos) << args << "\n" << r.output;
  EXPECT_FALSE(fs::exists(dir / "image.png"));
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

// Partial updating (L373-L379): at 25% each position is cast once every 4 frames. The user
// moves during two frames and rests: the fourth frame at the resting view shows the complete
// image and the third does not; every frame after the first casts a quarter of the positions, in
// less time. With every position cast, a resting view already complete casts nothing.
TEST(Pxpl5Sampling, PartialUpdatingCastsAQuarterAFrameAndFillsInAfterFour) {
  const std::string base =
      balls(128, 128) + " -p sampling.finest=2 -p camera.path=\"move 2, rest 4\" -p camera.spin=5";
  const auto full = run_pxpl5("update-full", base);
  const auto quarter = run_pxpl5("update-25", base + " -p update.fraction=25");
  const auto third =
      run_pxpl5("update-25-third", base + " -p update.fraction=25 -p display.frame=4");
  ASSERT_FALSE(full.empty() || quarter.empty() || third.empty());
  // Frame 2 is the first at the resting view, frame 5 the fourth.
  EXPECT_EQ(read_file(full.at("image_png").get<std::string>()),
            read_file(quarter.at("image_png").get<std::string>()));
  EXPECT_NE(read_file(full.at("image_png").get<std::string>()),
            read_file(third.at("image_png").get<std::string>()));
  // Full: frames 0-2 cast every position, the three resting ones after nothing; a quarter: frame
  // 0 every position, frames 1-5 a quarter each (2.25 frames' worth against 3).
  EXPECT_NEAR(rays_per_pixel(quarter) / rays_per_pixel(full), 2.25 / 3.0, 0.02);
  const auto& t = quarter["pxpl5"]["frame_times_s"];
  std::printf("25%% updating: first frame %.4g ms, then %.4g %.4g %.4g %.4g %.4g ms\n",
              t[0].get<double>() * 1e3, t[1].get<double>() * 1e3, t[2].get<double>() * 1e3,
              t[3].get<double>() * 1e3, t[4].get<double>() * 1e3, t[5].get<double>() * 1e3);
  for (int f = 1; f < 6; ++f) EXPECT_LT(t[f].get<double>(), 0.5 * t[0].get<double>());
  const auto& per = full["frame_sequence"]["per_frame"];
  for (int f = 3; f < 6; ++f) EXPECT_EQ(per[f]["cast_level"], -1) << f;
}

// Successive refinement (L288): three levels, the user moving two frames and resting five, 50%
// updating. Moving frames cast and display the coarsest level (a ray every 4 pixels); resting
// ones fill it in, then refine level by level, each displayed once complete. Every frame's
// image is the twin's for the same state, and the finest display costs the most.
TEST(Pxpl5Interaction, EachDisplayedFrameIsTheTwinsAndRefinesWhileTheViewRests) {
  const std::string base = balls(96, 64) +
                           " -p camera.path=\"move 2, rest 5\" -p camera.spin=5 "
                           "-p refine.levels=3 -p update.fraction=50 -p caster_count=4";
  nlohmann::ordered_json last;
  for (int f = 0; f < 7; ++f) {
    const auto s =
        run_pxpl5("refine", base + " -p display.frame=" + std::to_string(f) + " --overhead");
    ASSERT_FALSE(s.empty()) << f;
    EXPECT_TRUE(s.at("functional_image_identical").get<bool>()) << "frame " << f;
    last = s;
  }
  // What each frame casts and is displayed at (refinement_schedule.hpp).
  const std::vector<int> cast = {0, 0, 0, 0, 1, 1, 2}, shown = {0, 0, 0, 0, 0, 1, 1};
  const auto& per = last["frame_sequence"]["per_frame"];
  ASSERT_EQ(per.size(), 7u);
  for (std::size_t f = 0; f < 7; ++f) {
    EXPECT_EQ(per[f]["cast_level"].get<int>(), cast[f]) << f;
    EXPECT_EQ(per[f]["display_level"].get<int>(), shown[f]) << f;
  }
  EXPECT_EQ(last["pxpl5"]["sampling"]["refine_levels"], 3);
}

TEST(Pxpl5Interaction, APathOrDisplayedFrameThatCannotBeIsBadInput) {
  for (const auto& [args, says] :
       {std::pair<std::string, std::string>{"-p camera.path=\"mvoe 3\"", "did you mean 'move'"},
        {"-p camera.path=\"move 0\"", "frame count from 1"},
        {"-p camera.path=\"move 2,, rest 1\"", "empty segment"},
        {"-p camera.path=\"rest 2 3\"", "frame count from 1"},
        {"-p camera.path=\"move 2, rest 2\" -p frames=5", "leave frames unset"},
        {"-p frames=4 -p display.frame=4", "0 to 3"},
        {"-p refine.levels=2 -p sampling.finest=4 -p sampling.start=16",
         "successive refinement"}}) {
    expect_bad_input(args, says);
  }
}

TEST(Pxpl5Sampling, ImpossibleRulesAreBadInput) {
  for (const auto& [args, says] :
       {std::pair<std::string, std::string>{"-p sampling.finest=3", "power of two"},
        {"-p sampling.finest=4 -p sampling.start=2", "at least sampling.finest"},
        {"-p sampling.finest=4 -p sampling.start=16 -p update.fraction=25", "partial updating"},
        {"-p sampling.finest=4 -p sampling.start=128", "must divide the square"}}) {
    expect_bad_input(args, says);
  }
}

}  // namespace
