// Sampled simulation (`rtsim run --sample K`, platform/machines/frame_sample.hpp): on a small
// frame of every machine that takes it, the image equals the full run's byte for byte and the
// estimate's 99.7% confidence interval contains the full run's frame time; bad uses exit 2.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::test::read_file;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;

namespace {

struct Case {
  const char* machine;
  const char* args;
};

TEST(SampledSimulation, TheIntervalHoldsTheFullFrameAndTheImageIsTheSame) {
  for (const Case& c : {
           Case{"vax-750", "--scene builtin:default --width 48 --height 48"},
           Case{"ullner-peripheral", "--scene builtin:ullner-cubes --width 48 --height 48"},
           Case{"ullner-pipeline", "--scene builtin:ullner-cubes --width 48 --height 48"},
           Case{"ullner-array", "--scene builtin:ullner-cubes --width 48 --height 48"},
           Case{"gaudet-pert", "--scene builtin:npp-412 --width 48 --height 48 -p pert_count=4"},
           Case{"wang-bezier", "--scene builtin:teapot --width 32 --height 32"},
       }) {
    SCOPED_TRACE(c.machine);
    const auto full = rtsim::test::run_machine(c.machine, "sample-full", c.args);
    const auto sampled =
        rtsim::test::run_machine(c.machine, "sample-4", std::string(c.args) + " --sample 4");
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
        c.machine, t, est, 100 * (est / t - 1), lo, hi,
        100 * s["half_width_relative"].get<double>(), s["detailed_windows"].get<int>(),
        s["windows"].get<int>());
    EXPECT_DOUBLE_EQ(sampled["simulated_time_s"].get<double>(), est);
    EXPECT_LE(lo, t);
    EXPECT_GE(hi, t);
  }
}

TEST(SampledSimulation, TheWindowsAreCutAsAsked) {
  const std::string args = "--scene builtin:ullner-cubes --width 32 --height 32";
  const auto full = rtsim::test::run_machine("ullner-peripheral", "sample-k-full", args);
  const auto all = rtsim::test::run_machine("ullner-peripheral", "sample-k-all",
                                            args + " --sample 2 --sample-window 1");
  ASSERT_FALSE(full.empty() || all.empty());
  // Windows of one row, every second in detail: half the rows, so half the frame simulated.
  const auto& s = all["sample"];
  EXPECT_EQ(s["windows"], 32);
  EXPECT_EQ(s["detailed_windows"], 16);
  EXPECT_LT(s["detailed_frame_s"].get<double>(), full["simulated_time_s"].get<double>());
}

TEST(SampledSimulation, BadUsesExitTwo) {
  for (const auto& [args, says] :
       {std::pair<std::string, std::string>{
            "--machine pxpl5-raytrace --scene builtin:default --width 32 --height 32 --sample 4",
            "does not take --sample"},
        {"--machine vax-750 --scene builtin:default --width 8 --height 8 --sample 4", "at least 3"},
        {"--machine vax-750 --scene builtin:default --width 32 --height 32 --sample-window 2",
         "give --sample too"}}) {
    const fs::path dir = scratch_dir("sample-bad");
    const auto r = run_rtsim("run " + args + " -q --out " + dir.string());
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir / "image.png"));
  }
}

}  // namespace
