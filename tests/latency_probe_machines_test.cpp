// `--latency-probe` on every registered machine (the kit's minimal one included): it follows
// some rays (or samples, on pxpl5-raytrace, which says so), changes nothing else (image and
// every other stats.json key identical to a run without it), attributes every interval of a
// journey to a stage (unattributed ~ 0), and, where the machine has a ray latency, covers the
// same rays over the same window. A machine that follows none fails the run instead of printing
// "0 rays".
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/test_support.hpp"

namespace {

using json = nlohmann::ordered_json;
using rtsim::test::read_file;
using rtsim::test::run_kit;
using rtsim::test::scratch_dir;

/// Unattributed time per journey relative to the end-to-end mean: the rounding of summing
/// picosecond parts as doubles in seconds (~1e-16); a stage a machine forgot is far above it.
constexpr double kUnattributedTolerance = 1e-12;

json run_ok(const std::string& tag, const std::string& args, std::filesystem::path& dir) {
  dir = scratch_dir(tag);
  const auto r = run_kit("run " + args + " --width 16 --height 16 -q --out " + dir.string());
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.output;
  return r.exit_code == 0 ? json::parse(read_file(dir / "stats.json")) : json();
}

json without_wall_clock(json s) {
  s.erase("wall_time_s");
  s.erase("rays_per_second");
  return s;
}

class LatencyProbeMachines : public testing::TestWithParam<rtsim::test::MachineInfo> {};

TEST_P(LatencyProbeMachines, FollowsItsRaysAndAttributesEveryInterval) {
  const std::string& machine = GetParam().name;
  const std::string args = "--machine " + machine + " " + GetParam().small_run();
  std::filesystem::path off_dir, on_dir;
  const json off = run_ok("probe-off-" + machine, args, off_dir);
  const json on = run_ok("probe-on-" + machine, args + " --latency-probe", on_dir);
  ASSERT_FALSE(off.is_null());
  ASSERT_FALSE(on.is_null());
  EXPECT_EQ(read_file(off_dir / "image.png"), read_file(on_dir / "image.png"));
  json rest = on;
  rest.erase("latency_probe");
  EXPECT_EQ(without_wall_clock(rest), without_wall_clock(off));

  const json& probe = on["latency_probe"];
  const double journeys = probe["rays"].get<double>();
  const double e2e = probe["end_to_end_s"]["mean"].get<double>();
  const double unattributed = probe["unattributed_s"].get<double>();
  std::cout << machine << ": " << journeys << " " << probe["unit"].get<std::string>()
            << "s, end-to-end mean " << e2e << " s, unattributed " << unattributed << " s, "
            << probe["stages"].size() << " stages\n";
  EXPECT_GT(journeys, 0);
  EXPECT_GT(probe["stages"].size(), 0u);
  EXPECT_LE(std::abs(unattributed), kUnattributedTolerance * e2e);
  double sum = 0.0;
  for (const auto& [name, st] : probe["stages"].items())
    for (const char* p : {"queueing_s", "service_s", "transfer_s"}) {
      EXPECT_GE(st[p].get<double>(), 0.0) << name << " " << p;
      sum += st[p].get<double>();
    }
  EXPECT_NEAR(sum + unattributed, e2e, 1e-12 * e2e);
  const json& lat = on["ray_latency_s"];
  if (lat["count"].get<double>() > 0) {
    // The same rays over the same window as the machine's own ray latency, sample for sample.
    EXPECT_EQ(probe["unit"], "ray");
    EXPECT_EQ(probe["end_to_end_s"], lat);
  } else {
    // No ray latency of its own: the probe says what it follows and over what window.
    EXPECT_TRUE(probe.contains("scope")) << probe.dump();
  }
}

INSTANTIATE_TEST_SUITE_P(Machines, LatencyProbeMachines,
                         testing::ValuesIn(rtsim::test::kit_machines()),
                         rtsim::test::machine_param_name);

}  // namespace
