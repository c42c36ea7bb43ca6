// ullner-peripheral's own tests: the data path (a word of the parameter memories corrupted on
// its way in changes the image) and --fault on its memories.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "firmware/kernels/ullner_quad_words.hpp"
#include "tests/data_path_support.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::test::read_file;
using rtsim::test::read_json;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;

namespace {

// The intersection pipeline tests the twenty parameters, pole thresholds and flags it read out
// of its parameter memories. Flipping the sign of d_p (the plane's offset, word 3) of the
// polygon the centre ray hits moves that polygon's plane: the centre pixel changes, while with no
// fault the image equals the functional twin's.
TEST(UllnerPeripheral, ParameterMemoryWordChangesTheImage) {
  rtsim::test::data_path::expect_centre_polygon_fault_shows(
      "ullner-peripheral", "peripheral.parameter_memories", rtsim::kernels::kUllnerStoredWords);
}

// `rtsim run --fault` names a memory and a word; a memory the machine does not have, or a word
// past its end, is bad input (exit 2).
TEST(UllnerPeripheral, FaultOnTheCommandLine) {
  const fs::path dir = rtsim::test::scratch_dir("fault-cli");
  const std::string base =
      "run --machine ullner-peripheral --scene builtin:ullner-cubes "
      "--width 16 --height 16 -q --out ";
  auto r =
      run_rtsim(base + (dir / "a").string() + " --fault peripheral.parameter_memorys:3:0x80000000");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("did you mean 'peripheral.parameter_memories'"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "a"));
  r = run_rtsim(base + (dir / "b").string() + " --fault peripheral.parameter_memories:99999999:1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("holds"), std::string::npos) << r.output;
  r = run_rtsim(base + (dir / "c").string() + " --fault peripheral.parameter_memories:3");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = run_rtsim(base + (dir / "d").string() +
                " --fault peripheral.parameter_memories:3:0x80000000");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const auto stats = rtsim::test::read_json(dir / "d" / "stats.json");
  ASSERT_TRUE(stats.contains("faults")) << stats.dump();
  EXPECT_EQ(stats["faults"][0]["applied"], 1);
  fs::remove_all(dir);
}

// Sampled simulation (--sample, --sample-error) on the peripheral's rows of vision rays.
TEST(UllnerPeripheral, SampledWindowsAreCutAsAsked) {
  const std::string args = "--scene builtin:ullner-cubes --width 32 --height 32";
  const auto full = rtsim::test::run_machine("ullner-peripheral", "sample-k-full", args);
  const auto all = rtsim::test::run_machine("ullner-peripheral", "sample-k-all",
                                            args + " --sample 2 --sample-window 1");
  ASSERT_FALSE(full.empty() || all.empty());
  // Windows of one row: the warm-up after window 0 (the windows holding 512 rays, at most an
  // eighth of the frame: 3), then every second: windows 0-3 and 4, 6, ..., 30.
  const auto& s = all["sample"];
  EXPECT_EQ(s["windows"], 32);
  EXPECT_EQ(s["warmup_windows"], 3);
  EXPECT_EQ(s["detailed_windows"], 18);
  EXPECT_LT(s["detailed_frame_s"].get<double>(), full["simulated_time_s"].get<double>());
  // No warm-up: every second window, half the frame.
  const auto none = rtsim::test::run_machine("ullner-peripheral", "sample-k-none",
                                             args + " --sample 2 --sample-warmup 0");
  ASSERT_FALSE(none.empty());
  EXPECT_EQ(none["sample"]["warmup_windows"], 0);
  EXPECT_EQ(none["sample"]["detailed_windows"], 16);
}

TEST(UllnerPeripheral, ATargetErrorRunsAPilotAndHoldsTheFullFrame) {
  const std::string args = "--scene builtin:ullner-sheets-1000 --width 64 --height 64";
  const auto full = rtsim::test::run_machine("ullner-peripheral", "sample-e-full", args);
  const auto sampled =
      rtsim::test::run_machine("ullner-peripheral", "sample-e-1", args + " --sample-error 1%");
  ASSERT_FALSE(full.empty() || sampled.empty());
  const auto& s = sampled["sample"];
  ASSERT_TRUE(s.contains("plan")) << s.dump();
  const int k = s["plan"]["every"].get<int>();
  const double t = full["simulated_time_s"].get<double>();
  std::printf(
      "--sample-error 1%%: K = %d from a pilot at K = %d; estimate %.6g s (+-%.3f%%), "
      "full %.6g s\n",
      k, s["plan"]["pilot_every"].get<int>(), s["estimate_s"].get<double>(),
      100 * s["half_width_relative"].get<double>(), t);
  ASSERT_GE(k, 2);  // this scene's rows are alike: a sample reaches 1%
  EXPECT_EQ(s["every"], k);
  EXPECT_LE(s["half_width_relative"].get<double>(), 0.01 * 1.5);
  EXPECT_LE(s["ci99_7_s"][0].get<double>(), t);
  EXPECT_GE(s["ci99_7_s"][1].get<double>(), t);
  EXPECT_EQ(read_file(full.at("image_png").get<std::string>()),
            read_file(sampled.at("image_png").get<std::string>()));
}

TEST(UllnerPeripheral, RunWritesTheDocumentedStats) {
  const auto dir = scratch_dir("run-keys");
  const auto r = run_rtsim(
      "run --machine ullner-peripheral --scene builtin:ullner-cubes --width 40 --height 30 "
      "--overhead --aov id,depth -q --out " +
      dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"image.png", "image.exr", "stats.json", "id.exr", "depth.exr"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  const auto s = read_json(dir / "stats.json");
  for (const char* key : {"machine", "scene", "width", "height", "simulated_time_s", "wall_time_s",
                          "functional_wall_time_s", "overhead_ratio", "rays", "intersection_tests",
                          "modules", "ray_latency_s"})
    EXPECT_TRUE(s.contains(key)) << key;
  EXPECT_EQ(s["machine"], "ullner-peripheral");
  EXPECT_EQ(s["width"], 40);
  EXPECT_EQ(s["rays"]["primary"], 40 * 30);
  for (const char* k : {"total", "primary", "shadow", "reflected", "refracted"})
    EXPECT_TRUE(s["rays"].contains(k)) << k;
  for (const char* k : {"mean", "p50", "p99"}) EXPECT_GT(s["ray_latency_s"][k].get<double>(), 0);
  for (const char* m : {"host", "peripheral.pipeline"}) {
    ASSERT_TRUE(s["modules"].contains(m)) << m;
    EXPECT_TRUE(s["modules"][m].contains("busy_s"));
    EXPECT_TRUE(s["modules"][m].contains("utilization"));
  }
  // A queue has a depth, no busy time (docs/stats.md).
  const auto& q = s["modules"]["peripheral.ray_queue"];
  for (const char* k : {"messages", "bits", "waits", "waited_s"}) EXPECT_TRUE(q.contains(k)) << k;
  for (const char* k : {"capacity", "mean_occupancy", "max_occupancy"})
    EXPECT_TRUE(q["queue"].contains(k)) << k;
  EXPECT_FALSE(q.contains("busy_s"));
  EXPECT_TRUE(s["functional_image_identical"].get<bool>());
  EXPECT_GT(s["simulated_time_s"].get<double>(), 0.0);
}

}  // namespace
