// `rtsim diff` (app/run_diff.hpp): parameters that differ, statistics by relative change,
// wall-clock numbers apart, and the command on two real runs.
#include "app/run_diff.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/test_support.hpp"

using rtsim::app::diff_runs;
using rtsim::app::format_run_diff;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;
using Json = nlohmann::ordered_json;

namespace {

Json run_stats(double frame, double util, int grid) {
  return Json::parse(R"({"machine": "a-machine", "scene": "builtin:ullner-cubes",
    "width": 64, "height": 64, "spp": 1, "simulated_time_s": )" +
                     std::to_string(frame) + R"(, "wall_time_s": 0.08,
    "ray_latency_s": {"mean": 0.0028, "p99": 0.0029},
    "modules": {"peripheral.pipeline": {"utilization": )" +
                     std::to_string(util) + R"(, "busy_s": 1.0}, "host": {"busy_s": 0.3}},
    "params": {"peripheral.grid.divisions": ")" +
                     std::to_string(grid) + R"(", "render.spp": "1"}})");
}

}  // namespace

TEST(RunDiff, ParametersAndStatisticsLargestChangeFirst) {
  const auto d = diff_runs(run_stats(1.388, 1.0, 0), run_stats(0.2677, 0.2795, 6));
  ASSERT_EQ(d.params.size(), 1u);
  EXPECT_EQ(d.params[0].name, "peripheral.grid.divisions");
  ASSERT_EQ(d.stats.size(), 2u);                   // busy_s, latency and the host are the same
  EXPECT_EQ(d.stats[0].name, "simulated_time_s");  // -80.7% before -72.0%
  EXPECT_NEAR(*d.stats[0].relative, -0.8071, 1e-4);
  EXPECT_EQ(d.stats[1].name, "modules.peripheral.pipeline.utilization");
  ASSERT_EQ(d.wall_clock.size(), 0u);  // the same wall time here
  const std::string text = format_run_diff(d, "A", "B");
  std::cout << text;
  EXPECT_NE(text.find("peripheral.grid.divisions  0 -> 6"), std::string::npos);
  EXPECT_NE(text.find("frame time: 1.388 s -> 267.7 ms   -80.7%"), std::string::npos);
  EXPECT_NE(text.find("statistics that changed (2 of 8)"), std::string::npos) << text;
  // A utilisation as the module tables show it: a percentage.
  EXPECT_NE(text.find("modules.peripheral.pipeline.utilization  100.0% -> 28.0%   -72.0%"),
            std::string::npos)
      << text;
}

TEST(RunDiff, WallClockApartAndToleranceAndNewStatistics) {
  auto a = run_stats(1.0, 0.5, 0);
  auto b = run_stats(1.0 + 1e-12, 0.5, 0);
  b["wall_time_s"] = 0.5;
  b["accel"] = {{"dda_steps", 18447}};
  auto d = diff_runs(a, b, 1e-9);
  EXPECT_TRUE(d.params.empty());
  ASSERT_EQ(d.stats.size(), 1u);  // the frame time is the same within 1e-9
  EXPECT_EQ(d.stats[0].name, "accel.dda_steps");
  EXPECT_TRUE(d.stats[0].a.is_null());
  ASSERT_EQ(d.wall_clock.size(), 1u);
  EXPECT_EQ(d.wall_clock[0].name, "wall_time_s");
  const std::string text = format_run_diff(d, "A", "B");
  EXPECT_NE(text.find("accel.dda_steps  - -> 18447   new"), std::string::npos) << text;
  EXPECT_NE(text.find("wall clock (differs between any two runs):"), std::string::npos);
  d = diff_runs(a, a);
  EXPECT_NE(format_run_diff(d, "A", "A").find("statistics: the same"), std::string::npos);
}

TEST(RunDiff, CommandComparesTwoRunFoldersAndRefusesOthers) {
  const auto a = scratch_dir("diff-a"), b = scratch_dir("diff-b");
  ASSERT_EQ(run_rtsim("run --width 24 --height 24 -q --out " + a.string()).exit_code, 0);
  ASSERT_EQ(
      run_rtsim("run --width 24 --height 24 -p peripheral.grid.divisions=4 -q --out " + b.string())
          .exit_code,
      0);
  const auto r = run_rtsim("diff " + a.string() + " " + (b / "stats.json").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("peripheral.grid.divisions  0 -> 4"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("frame time: "), std::string::npos);
  EXPECT_NE(r.output.find("intersection_tests"), std::string::npos);
  const auto bad = run_rtsim("diff " + a.string() + " /nonexistent/run");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("/nonexistent/run"), std::string::npos) << bad.output;
}
