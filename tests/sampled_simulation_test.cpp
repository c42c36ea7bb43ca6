// Sampled simulation (`rtsim run --sample K`, platform/machines/frame_sample.hpp): on a small
// frame of every machine that takes it, the image equals the full run's byte for byte and the
// estimate's 99.7% confidence interval contains the full run's frame time, and a timing-only run
// (--image none) gives the same estimate without the image; bad uses exit 2.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>

#include "platform/machines/frame_sample.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::test::read_file;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;

namespace {

class SampledSimulation : public testing::TestWithParam<rtsim::test::MachineInfo> {};

TEST_P(SampledSimulation, TheIntervalHoldsTheFullFrameAndTheImageIsTheSame) {
  const std::string& machine = GetParam().name;
  const std::string args = GetParam().small_run() + " --width 48 --height 48";
  if (!GetParam().samples) {
    // A machine that does not sample refuses it with exit 2, before anything runs.
    const auto r = rtsim::test::run_kit("run --machine " + machine + " " + args + " --sample 4 -q");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("does not sample"), std::string::npos) << r.output;
    GTEST_SKIP() << machine << " does not sample";
  }
  {
    SCOPED_TRACE(machine);
    const auto full = rtsim::test::run_machine(machine, "sample-full", args);
    const auto sampled = rtsim::test::run_machine(machine, "sample-4", args + " --sample 4");
    ASSERT_FALSE(full.empty() || sampled.empty());
    EXPECT_EQ(read_file(full.at("image_png").get<std::string>()),
              read_file(sampled.at("image_png").get<std::string>()));
    const double t = full["simulated_time_s"].get<double>();
    const auto& s = sampled["sample"];
    ASSERT_TRUE(s.contains("ci99_7_s")) << s.dump();
    const double lo = s["ci99_7_s"][0].get<double>(), hi = s["ci99_7_s"][1].get<double>();
    const double est = s["estimate_s"].get<double>();
    std::printf(
        "%-18s full %.6g s, sampled estimate %.6g s (%+.2f%%), 99.7%% CI [%.6g, %.6g] "
        "(+-%.2f%%), %d of %d windows\n",
        machine.c_str(), t, est, 100 * (est / t - 1), lo, hi,
        100 * s["half_width_relative"].get<double>(), s["detailed_windows"].get<int>(),
        s["windows"].get<int>());
    EXPECT_DOUBLE_EQ(sampled["simulated_time_s"].get<double>(), est);
    EXPECT_LE(lo, t);
    EXPECT_GE(hi, t);
    // Timing-only (--image none): the same simulation and estimate, no image, and the rows not
    // simulated in detail are not rendered (fewer rays counted).
    const auto timing =
        rtsim::test::run_machine(machine, "sample-4-timing", args + " --sample 4 --image none");
    ASSERT_FALSE(timing.empty());
    EXPECT_EQ(timing["sample"]["estimate_s"], s["estimate_s"]);
    EXPECT_EQ(timing["sample"]["ci99_7_s"], s["ci99_7_s"]);
    EXPECT_EQ(timing["image"]["files"], "none");
    EXPECT_EQ(sampled["image"]["files"], "all");
    EXPECT_FALSE(fs::exists(timing.at("image_png").get<std::string>()));
    EXPECT_FALSE(fs::exists(
        fs::path(timing.at("image_png").get<std::string>()).replace_filename("image.exr")));
    EXPECT_LT(timing["rays"]["total"].get<double>(), sampled["rays"]["total"].get<double>());
  }
}

INSTANTIATE_TEST_SUITE_P(Machines, SampledSimulation,
                         testing::ValuesIn(rtsim::test::kit_machines()),
                         rtsim::test::machine_param_name);

TEST(SampledSimulation, TheTargetErrorChoosesK) {
  // A pilot of 100 windows of 1 ms each, apart by 20 us (successive differences): the
  // half-width at K is 3 * 99 * 20 us * sqrt(1 / (n - 1) - 1 / 99), n = ceil(100 / K).
  nlohmann::ordered_json pilot = {{"windows", 100}, {"estimate_s", 0.1}, {"window_s_sd", 2e-5}};
  using rtsim::platform::FrameSample;
  for (const double target : {0.002, 0.005, 0.01, 0.05}) {
    const int k = FrameSample::every_for(pilot, target);
    std::printf("target %.1f%%: K = %d\n", 100 * target, k);
    if (k >= 2) {
      EXPECT_LE(FrameSample::half_width(100, (100 + k - 1) / k, 2e-5), target * 0.1);
    }
    // The next K would miss the target, or is more than the pilot's (100 / 10 windows).
    const int next = (100 + k) / (k + 1);
    if (k + 1 <= 100 / FrameSample::kPilotWindows) {
      EXPECT_GT(FrameSample::half_width(100, next, 2e-5), target * 0.1);
    }
  }
  EXPECT_EQ(FrameSample::every_for(pilot, 1e-6), 1);  // not even K = 2: the whole frame
  EXPECT_GT(FrameSample::every_for(pilot, 0.05), FrameSample::every_for(pilot, 0.005));
  // After a warm-up of 10 windows the sample stands for the other 90: windows 0-10 are exact,
  // and K is the largest whose interval over those 90 reaches the target.
  nlohmann::ordered_json warm = pilot;
  warm["warmup_windows"] = 10;
  const int k = FrameSample::every_for(warm, 0.01);
  ASSERT_GE(k, 2);
  const int sampled = (100 + k - 1) / k - (10 / k + 1);  // K, 2K, ... after window 10
  EXPECT_LE(FrameSample::half_width(90, 1 + sampled, 2e-5), 0.01 * 0.1);
  pilot["window_s_sd"] = 0.0;
  // Windows all alike: the largest K that keeps the pilot's 10 windows.
  EXPECT_EQ(FrameSample::every_for(pilot, 0.01), 10);
}

// A synthetic sampled run of `windows` windows of one row (4 pixels), every `every`-th in
// detail, on a machine that does one window after another in ticks(tests) ticks: the sampled
// run's contributions, each window's work as the work count would report it (4 rays a window,
// half its tests and 2 rays in its subsample), and the frame's own length (ticks).
struct SequentialFrame {
  rtsim::platform::FrameSample sample;
  std::vector<rtsim::functional::WindowWork> work;
  std::uint64_t sampled_ticks = 0, full_ticks = 0;

  SequentialFrame(int windows, int every, const std::function<double(int)>& tests_of,
                  const std::function<std::uint64_t(double)>& ticks)
      : sample(4, windows, every, 1, 0), work(static_cast<std::size_t>(windows)) {
    for (int w = 0; w < windows; ++w) {
      const double tests = tests_of(w);
      const bool detailed = sample.detailed_rows()[static_cast<std::size_t>(w)] != 0;
      work[static_cast<std::size_t>(w)] = {detailed, detailed ? tests : 0, detailed ? 4.0 : 0,
                                           tests / 2, 2};
      full_ticks += ticks(tests);
      if (!detailed) continue;
      sampled_ticks += ticks(tests);
      sample.contribution(static_cast<std::uint32_t>(w * 4), sampled_ticks);
    }
  }
  /// The estimate from the sampled run's frame; its stats.json `sample`.
  nlohmann::ordered_json estimate(double& estimate_s) const {
    return sample.estimate(sc_core::SC_ZERO_TIME,
                           sc_core::sc_time::from_value(1) * static_cast<double>(sampled_ticks),
                           estimate_s);
  }
  double full_s() const {
    return static_cast<double>(full_ticks) * sc_core::sc_time::from_value(1).to_seconds();
  }
};

TEST(SampledSimulation, TheWorkWeightedEstimateIsExactWhereTimeFollowsTheWork) {
  // 40 windows of one row, every 4th in detail after window 0, on a machine that does one
  // window after another in 10 + 2 x (its tests) ticks. Its rays do not vary (the regression
  // falls back to the tests alone); the windows not simulated have half their tests in their
  // subsample, as the detailed ones do, so the calibration is exact and so is the estimate.
  SequentialFrame f(
      40, 4,
      [](int w) { return std::round(100 + 60 * std::sin(w * 0.4)) + (w > 20 && w < 28 ? 400 : 0); },
      [](double tests) { return static_cast<std::uint64_t>(10 + 2 * tests); });
  double systematic = 0, estimate = 0;
  (void)f.estimate(systematic);
  f.sample.set_window_work(f.work);
  const auto out = f.estimate(estimate);
  const double exact = f.full_s();
  std::printf("full %.6g s: work-weighted %.6g s, systematic %.6g s (%+.1f%%)\n", exact, estimate,
              systematic, 100 * (systematic / exact - 1));
  EXPECT_EQ(out["estimator"], "work");
  EXPECT_EQ(out["work"]["variables"], "tests");
  EXPECT_NEAR(estimate, exact, 1e-9 * exact);
  EXPECT_LT(out["half_width_relative"].get<double>(), 1e-6);
  // The burst of windows 21-27 is sampled at 24 only: the windows' mean misses it.
  EXPECT_GT(std::fabs(systematic / exact - 1), 0.02);
  // Work the windows do not differ in: nothing to regress on, the systematic estimate.
  for (auto& w : f.work) w.tests = w.whole ? 50 : 0, w.sub_tests = 25;
  f.sample.set_window_work(f.work);
  double fallback = 0;
  EXPECT_EQ(f.estimate(fallback)["estimator"], "systematic");
  EXPECT_DOUBLE_EQ(fallback, systematic);
}

TEST(SampledSimulation, TooFewWindowsForALineWeighByTheRatio) {
  // 40 windows, every 16th in detail: two differences, too few for a line with an intercept.
  // A machine whose windows take 3 ticks a test: the ratio of their time to their tests is exact.
  SequentialFrame f(
      40, 16, [](int w) { return 20.0 + 7 * (w % 5) + (w > 10 && w < 30 ? 50 : 0); },
      [](double tests) { return static_cast<std::uint64_t>(3 * tests); });
  f.sample.set_window_work(f.work);
  double estimate = 0;
  const auto out = f.estimate(estimate);
  EXPECT_EQ(out["estimator"], "work");
  EXPECT_NE(out["work"]["variables"].get<std::string>().find("ratio"), std::string::npos);
  EXPECT_NEAR(estimate, f.full_s(), 1e-9 * f.full_s());
  // A count that left the other windows out (the windows in detail did not differ): none.
  for (auto& w : f.work)
    if (!w.whole) w.sub_tests = w.sub_rays = 0;
  f.sample.set_window_work(f.work);
  EXPECT_EQ(f.estimate(estimate)["estimator"], "systematic");
}

TEST(SampledSimulation, TheWorkWeightedEstimateHoldsWhereAnObjectSitsMidFrame) {
  // vax-750 on ullner-cubes (cubes in the middle of the frame, empty rows above and below) at
  // 96 x 96, K = 16: measured -0.30% +- 1.22% by the work, +7.8% +- 52% by the windows' mean.
  const std::string args = "--scene builtin:ullner-cubes --width 96 --height 96";
  const auto full = rtsim::test::run_machine("vax-750", "work-full", args + " --image none");
  const auto work =
      rtsim::test::run_machine("vax-750", "work-16", args + " --sample 16 --image none");
  const auto plain = rtsim::test::run_machine(
      "vax-750", "work-16-systematic", args + " --sample 16 --image none --sample-work-stride 0");
  ASSERT_FALSE(full.empty() || work.empty() || plain.empty());
  const double t = full["simulated_time_s"].get<double>();
  const auto& s = work["sample"];
  ASSERT_EQ(s["estimator"], "work") << s.dump();
  EXPECT_EQ(plain["sample"]["estimator"], "systematic");
  EXPECT_FALSE(plain["sample"].contains("work"));
  // The systematic estimate is reported beside the work-weighted one, and is the plain run's.
  EXPECT_EQ(s["systematic"]["estimate_s"], plain["sample"]["estimate_s"]);
  const double est = s["estimate_s"].get<double>(),
               sys = plain["sample"]["estimate_s"].get<double>();
  std::printf("full %.6g s: work-weighted %+.2f%% +- %.2f%%, systematic %+.2f%% +- %.2f%%\n", t,
              100 * (est / t - 1), 100 * s["half_width_relative"].get<double>(),
              100 * (sys / t - 1), 100 * plain["sample"]["half_width_relative"].get<double>());
  EXPECT_LT(std::fabs(est / t - 1), 0.01);
  EXPECT_LE(s["ci99_7_s"][0].get<double>(), t);
  EXPECT_GE(s["ci99_7_s"][1].get<double>(), t);
  EXPECT_LT(std::fabs(est / t - 1), std::fabs(sys / t - 1));
  EXPECT_LT(s["half_width_relative"].get<double>(),
            plain["sample"]["half_width_relative"].get<double>());
  EXPECT_EQ(s["work"]["windows"].size(),
            static_cast<std::size_t>(s["detailed_windows"].get<int>() - 1 -
                                     s["warmup_windows"].get<int>()));
}

TEST(SampledSimulation, AWorkWeightedPilotChoosesKByItsResiduals) {
  // 200 windows; the windows' spread alone (the systematic estimate) would need K = 1 for 1%,
  // but their residuals about the work are small: K is the largest whose regression part and
  // subsample part together stay within the target.
  using rtsim::platform::FrameSample;
  nlohmann::ordered_json pilot = {
      {"windows", 200},
      {"estimate_s", 1.0},
      {"window_s_sd", 0.05},
      {"estimator", "work"},
      {"work", {{"residual_s_sd", 5e-5}, {"half_width_subsample_s", 4e-3}}}};
  const double target = 0.01;
  const int k = FrameSample::every_for(pilot, target);
  auto half = [](int k) {
    const double R = 199, m = (200 + k - 1) / k - 1;  // sampled windows after window 0
    return std::hypot(3 * R * 5e-5 * std::sqrt(1 / m - 1 / R), 4e-3);
  };
  std::printf("work-weighted pilot: K = %d (half-width %.3f%%)\n", k, 100 * half(k));
  ASSERT_GE(k, 2);
  EXPECT_LE(half(k), target);
  if (k < 200 / FrameSample::kPilotWindows) {
    EXPECT_GT(half(k + 1), target);
  }
  pilot.erase("work");
  EXPECT_EQ(FrameSample::every_for(pilot, target), 1);  // the spread alone: the whole frame
  // A subsample that alone misses the target: the whole frame, whatever K.
  pilot["work"] = {{"residual_s_sd", 0.0}, {"half_width_subsample_s", 0.02}};
  EXPECT_EQ(FrameSample::every_for(pilot, target), 1);
}

TEST(SampledSimulation, BadUsesExitTwo) {
  for (const auto& [args, says] :
       {std::pair<std::string, std::string>{
            // One 64 x 64 square: one window.
            "--machine pxpl5-raytrace --scene builtin:default --width 32 --height 32 --sample 4",
            "1 windows of 1 regions"},
        {"--machine vax-750 --scene builtin:default --width 8 --height 8 --sample 4", "at least 3"},
        {"--machine vax-750 --scene builtin:default --width 32 --height 32 --sample-window 2",
         "give one of them too"},
        {"--machine vax-750 --scene builtin:default --width 32 --height 32 --sample 4 "
         "--sample-error 1%",
         "not both"},
        {"--machine vax-750 --scene builtin:default --width 32 --height 32 --sample-warmup 2",
         "give one of them too"},
        // A warm-up so long that fewer than two windows are left to sample.
        {"--machine vax-750 --scene builtin:default --width 32 --height 32 --sample 8 "
         "--sample-warmup 20",
         "20 of them a warm-up"},
        {"--machine pxpl5-raytrace --scene builtin:default --width 48 --height 48 "
         "-p assign.scheme=rows --sample 4 --sample-warmup 2",
         "a warm-up does not apply"},
        {"--machine vax-750 --scene builtin:default --width 32 --height 32 "
         "--sample-work-stride 2",
         "give one of them too"},
        {"--machine vax-750 --scene builtin:default --width 32 --height 32 --sample 4 "
         "--sample-work-stride -1",
         "--sample-work-stride"},
        {"--machine vax-750 --scene builtin:default --width 32 --height 32 --sample-error 0%",
         "(0, 50%]"},
        // A timing-only run writes no image: nothing that only shows one.
        {"--machine vax-750 --scene builtin:default --width 8 --height 8 --image none --aov id",
         "takes no --aov"},
        {"--machine vax-750 --scene builtin:default --width 8 --height 8 --image png --aov depth",
         "use --image all"},
        {"--machine vax-750 --scene builtin:default --width 8 --height 8 --image none --report",
         "--report shows the image"},
        {"--machine vax-750 --scene builtin:default --width 8 --height 8 --image jpg", "--image"},
        {"--machine vax-750 --scene builtin:default --width 32 --height 32 --sample-error one",
         "a percentage"},
        {"--machine vax-750 --scene builtin:default --width 5 --height 5 --sample-error 1%",
         "at least 6"},
        {"--machine pxpl5-raytrace --scene builtin:default --width 32 --height 32 "
         "-p assign.scheme=rows -p frames=2 --sample-error 5%",
         "set frames = 1"},
        // Found by the machine, in the pilot: the pilot's message is the run's.
        {"--machine vax-750 --scene builtin:default --width 32 --height 32 --sample-error 1% "
         "--fault nosuch:0:1",
         "has no memory 'nosuch'"}}) {
    const fs::path dir = scratch_dir("sample-bad");
    const auto r = run_rtsim("run " + args + " -q --out " + dir.string());
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir / "image.png"));
  }
}

}  // namespace
