// The global quantum (docs/quantum.md) on every machine: a run at a quantum > 0 finishes (no
// thread waits for a notification it missed while it caught up with simulated time), draws the
// same image as the reference (quantum 0) and has its frame time within the documented error.
// The cases include the ones that once went wrong: ullner-pipeline's host slept until its next
// answer while the chain freed the slot it wanted (15x the frame time at 10 us); ullner-array
// and gaudet-pert stopped with work outstanding at 1 ms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "tests/test_support.hpp"

using rtsim::test::read_file;

namespace {

/// docs/quantum.md "Every machine": the largest frame-time error measured at 1 ms is ullner-array's
/// (its nodes decide on their queues' state "now"): -2.0% on this 64x64 frame of 0.11 s, -0.9% at
/// 128x128. gaudet-pert's is under 0.6%, the other machines' 0.
constexpr double kFrameTimeTolerance = 0.03;

/// The frame of docs/quantum.md's measurements.
constexpr const char* kSize = " --width 64 --height 64";

class Quantum : public testing::TestWithParam<rtsim::test::MachineInfo> {};

TEST_P(Quantum, FinishesWithTheSameImageAndAFrameTimeWithinTheError) {
  const std::string& machine = GetParam().name;
  const std::string args = GetParam().small_run() + kSize;
  {
    SCOPED_TRACE(machine);
    const auto reference = rtsim::test::run_machine(machine, "quantum-0", args);
    ASSERT_FALSE(reference.empty());
    const double t0 = reference["simulated_time_s"].get<double>();
    for (const auto& [quantum, tag] :
         {std::pair{"10 us", "quantum-10us"}, {"1 ms", "quantum-1ms"}}) {
      SCOPED_TRACE(quantum);
      const auto run =
          rtsim::test::run_machine(machine, tag, args + " --quantum \"" + quantum + "\"");
      ASSERT_FALSE(run.empty());
      const double t = run["simulated_time_s"].get<double>();
      std::printf("%-18s quantum %-5s frame time %.6g s against %.6g s at 0 (%+.3f%%)\n",
                  machine.c_str(), quantum, t, t0, 100 * (t / t0 - 1));
      EXPECT_LE(std::abs(t / t0 - 1), kFrameTimeTolerance);
      EXPECT_EQ(read_file(reference.at("image_png").get<std::string>()),
                read_file(run.at("image_png").get<std::string>()));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Machines, Quantum, testing::ValuesIn(rtsim::test::kit_machines()),
                         rtsim::test::machine_param_name);

}  // namespace
