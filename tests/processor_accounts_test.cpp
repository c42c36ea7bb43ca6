// modules::Processor accounts every moment of a processor's frame: busy, waiting for data,
// waiting for work, blocked on output. On every machine the four add up to no more than the
// frame (a frame may end with a transfer no processor waits for: ullner-array's last message).
// gaudet-pert's processing + latency + pipeline wait + starved cut the same total.
#include <gtest/gtest.h>

#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/test_support.hpp"

namespace {

using rtsim::test::read_file;
using rtsim::test::run_kit;
using rtsim::test::scratch_dir;

class ProcessorAccounts : public testing::TestWithParam<rtsim::test::MachineInfo> {};

TEST_P(ProcessorAccounts, AddUpToTheFrame) {
  const std::string& machine = GetParam().name;
  const auto dir = scratch_dir("accounts-" + machine);
  const auto r = run_kit("run --machine " + machine + " " + GetParam().small_run() +
                         " --width 16 --height 16 -q --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto stats = nlohmann::json::parse(read_file(dir / "stats.json"));
  const double frame = stats.at("simulated_time_s").get<double>();
  std::size_t processors = 0;
  for (const auto& [name, m] : stats.at("modules").items()) {
    if (!m.contains("waiting_for_data_s")) continue;
    ++processors;
    const double sum = m.at("busy_s").get<double>() + m.at("waiting_for_data_s").get<double>() +
                       m.at("waiting_for_work_s").get<double>() + m.at("blocked_s").get<double>();
    std::cout << machine << " " << name << ": busy + waiting + blocked = " << sum << " s, frame "
              << frame << " s\n";
    EXPECT_LE(sum, frame * (1 + 1e-9)) << name;
    // gaudet-pert's split (L1045) plus starvation is the same time cut differently.
    if (m.contains("starved_s")) {
      const double split = m.at("busy_s").get<double>() + m.at("latency_s").get<double>() +
                           m.at("pipeline_wait_s").get<double>() + m.at("starved_s").get<double>();
      EXPECT_NEAR(split, sum, 1e-9 * frame) << name;
      EXPECT_GE(m.at("starved_s").get<double>(), 0.0) << name;
      EXPECT_GE(m.at("pipeline_wait_s").get<double>(), 0.0) << name;
    }
  }
  EXPECT_GT(processors, 0u);
}

INSTANTIATE_TEST_SUITE_P(Machines, ProcessorAccounts,
                         testing::ValuesIn(rtsim::test::kit_machines()),
                         rtsim::test::machine_param_name);

}  // namespace
