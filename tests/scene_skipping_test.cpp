// A run skips what its scene does not need, on every machine, measured by the machine's own
// counts and by stats.json `simulation` (the SystemC processes' activations,
// modules/activations.hpp):
// - a scene without lights sends no shadow work, and costs fewer events than the same scene lit;
// - a scene without patches starts no Bézier jobs (wang-bezier's pipeline never runs);
// - an idle module costs no events: slowing the machine's ray source (or its slowest stage)
//   tenfold lengthens the frame, so the other modules wait far longer, and the activations stay
//   as they were (a module that polled or ticked while idle would wake in proportion to the
//   frame's length).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>

#include "tests/test_support.hpp"

namespace {

using rtsim::test::MachineInfo;
using rtsim::test::run_machine;

class SceneSkipping : public testing::TestWithParam<MachineInfo> {};

// The same 100 quads, with no light and with one at the eye (builtin scenes, rtsim list scenes).
const std::string kDark = "--scene builtin:ullner-sheets-100 --width 24 --height 24";
const std::string kLit = "--scene builtin:ullner-sheets-lit-100 --width 24 --height 24";

std::uint64_t activations(const nlohmann::ordered_json& stats) {
  return stats["simulation"]["process_activations"].get<std::uint64_t>();
}

/// Machines that shade nothing (a hidden-line drawing): no light makes work for them.
const std::set<std::string> kUnlit = {"ullner-hidden-line"};

TEST_P(SceneSkipping, NoLightsSendNoShadowWork) {
  const std::string& machine = GetParam().name;
  const auto dark = run_machine(machine, "dark", kDark + " --image none");
  const auto lit = run_machine(machine, "lit", kLit + " --image none");
  ASSERT_FALSE(dark.empty() || lit.empty());
  std::printf("%-18s shadow rays %s / %s, activations %llu / %llu (dark / lit)\n", machine.c_str(),
              dark["rays"]["shadow"].dump().c_str(), lit["rays"]["shadow"].dump().c_str(),
              static_cast<unsigned long long>(activations(dark)),
              static_cast<unsigned long long>(activations(lit)));
  EXPECT_EQ(dark["rays"]["shadow"].get<std::uint64_t>(), 0u);
  if (kUnlit.count(machine)) {
    // It draws lines: a light is nothing to it, and the lit scene costs what the dark one does.
    EXPECT_EQ(lit["rays"]["shadow"].get<std::uint64_t>(), 0u);
    EXPECT_EQ(activations(dark), activations(lit));
    EXPECT_EQ(dark["simulated_time_s"], lit["simulated_time_s"]);
    return;
  }
  EXPECT_GT(lit["rays"]["shadow"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(dark["rays"]["primary"], lit["rays"]["primary"]);
  // The shadow rays cost events where they are sent, and none where they are not.
  EXPECT_LE(activations(dark), activations(lit));
  EXPECT_GT(dark["simulation"]["delta_cycles"].get<std::uint64_t>(), 0u);
}

TEST_P(SceneSkipping, NoPatchesStartNoBezierJobs) {
  const std::string& machine = GetParam().name;
  const auto dark = run_machine(machine, "no-patches", kDark + " --image none");
  ASSERT_FALSE(dark.empty());
  EXPECT_EQ(dark["patch_subdivisions"].get<std::uint64_t>(), 0u);
  if (machine != "wang-bezier") return;
  // The Bézier pipeline: no job, and none of its processes ever ran; on the teapot it does.
  const auto teapot =
      run_machine(machine, "patches", "--scene builtin:teapot --width 24 --height 24 --image none");
  ASSERT_FALSE(teapot.empty());
  auto pipeline_runs = [](const nlohmann::ordered_json& stats) {
    std::uint64_t n = 0;
    for (const auto& [process, count] : stats["simulation"]["activations"].items())
      if (process.rfind("pipeline", 0) == 0) n += count.get<std::uint64_t>();
    return n;
  };
  std::printf(
      "wang-bezier: jobs %s / %s, pipeline activations %llu / %llu (no patches / "
      "teapot)\n",
      dark["wang"]["jobs"].dump().c_str(), teapot["wang"]["jobs"].dump().c_str(),
      static_cast<unsigned long long>(pipeline_runs(dark)),
      static_cast<unsigned long long>(pipeline_runs(teapot)));
  EXPECT_EQ(dark["wang"]["jobs"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(pipeline_runs(dark), 0u);
  EXPECT_GT(teapot["wang"]["jobs"].get<std::uint64_t>(), 0u);
  EXPECT_GT(pipeline_runs(teapot), 0u);
}

// The module each machine's test slows tenfold: where the rays come from, or the stage the
// others wait on. A new machine names its own here.
const std::map<std::string, std::string> kSlowed = {
    {"vax-750", "-p vax.intersection_time=\"4290 us\""},
    {"kit-minimal", "-p host.ray_time=\"200 us\""},
    {"ullner-peripheral", "-p host.clock=\"0.5 MHz\""},
    {"ullner-pipeline", "-p host.clock=\"0.5 MHz\""},
    {"ullner-array", "-p node.clock=\"0.8 MHz\""},
    {"gaudet-pert", "-p pert.prim.clock=\"0.5 MHz\""},
    {"pxpl5-raytrace", "-p gp.clock=\"4 MHz\""},
    {"wang-bezier", "-p host.clock=\"35 MHz\""},
    {"pixelflow", "-p rasterizer.triangle_time=\"8.5 us\""},
    {"ullner-scanline-tree", "-p tc.instruction_time=\"65 us\""},
    {"sort-first", "-p renderer.triangle_time=\"40 us\""},
    {"ullner-hidden-line", "-p pipe.link.bit_time=\"5 us\""},
};

TEST_P(SceneSkipping, AnIdleModuleCostsNoEvents) {
  const std::string& machine = GetParam().name;
  const auto slowed = kSlowed.find(machine);
  ASSERT_NE(slowed, kSlowed.end()) << machine
                                   << ": name the module this test slows in kSlowed (its ray "
                                      "source or the stage the others wait on)";
  const auto base = run_machine(machine, "idle-base", kDark + " --image none");
  const auto slow = run_machine(machine, "idle-slow", kDark + " --image none " + slowed->second);
  ASSERT_FALSE(base.empty() || slow.empty());
  const double longer =
      slow["simulated_time_s"].get<double>() / base["simulated_time_s"].get<double>();
  const double more =
      static_cast<double>(activations(slow)) / static_cast<double>(activations(base));
  std::printf("%-18s %s: frame x%.2f, activations %llu -> %llu (x%.3f)\n", machine.c_str(),
              slowed->second.c_str(), longer, static_cast<unsigned long long>(activations(base)),
              static_cast<unsigned long long>(activations(slow)), more);
  EXPECT_GT(longer, 1.2) << "the slowed module does not set the frame: choose another";
  // Interleavings change with the timing (gaudet-pert's packets meet differently): 10%.
  EXPECT_NEAR(more, 1.0, 0.10);
  // Process by process: none wakes in proportion to the frame, which would add (longer - 1)
  // times its count. A process may wake a little more where the slowed one makes others wait
  // more often: gaudet-pert's ShellProcessor, woken by puts and takes it cannot act on while
  // its one search waits for room in the slow PrimProcessor's queue, gains 1,713 activations at
  // a frame 5.8 times longer whether it waits after each computation or not, +31% of its count
  // now that it does not. A quarter, or a tenth of the frame's growth if that is more.
  const double allowed = std::max(0.25, 0.1 * (longer - 1.0));
  for (const auto& [process, count] : slow["simulation"]["activations"].items()) {
    const double before = base["simulation"]["activations"].value(process, 0.0);
    EXPECT_LE(count.get<double>(), (1.0 + allowed) * before + 20) << process;
  }
}

INSTANTIATE_TEST_SUITE_P(Machines, SceneSkipping, testing::ValuesIn(rtsim::test::kit_machines()),
                         rtsim::test::machine_param_name);

}  // namespace
