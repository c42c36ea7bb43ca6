// ullner-array's intersection unit (platform/machines/ullner_array/intersection_pipeline.hpp):
// run_pipeline looks at the stages once a moment where a second look could change nothing, and
// gives what looking until nothing changes gives, field for field, on random streams and timings
// (zero times included, where it must look again). DESIGN.md: a shortcut is allowed where a test
// shows it identical to the structural run, stalls included.
#include "platform/machines/ullner_array/intersection_pipeline.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace {

using rtsim::platform::ullner_array::FetchPriority;
using rtsim::platform::ullner_array::PipelineLooks;
using rtsim::platform::ullner_array::PipelineRun;
using rtsim::platform::ullner_array::PipelineTest;
using rtsim::platform::ullner_array::PipelineTiming;
using rtsim::platform::ullner_array::run_pipeline;

/// A random stream of `n` tests in a few lists, as a search makes them: each list's bound the
/// end of the ray's part in its subvolume, each test's immediate bound the closest hit before it
/// in its list.
std::vector<PipelineTest> random_stream(std::mt19937_64& rng, std::size_t n) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<PipelineTest> tests;
  std::uint32_t list = 0;
  double bound = 10.0, best = 10.0;
  const bool shadow = unit(rng) < 0.25;
  for (std::size_t k = 0; k < n; ++k) {
    const bool new_list = k == 0 || unit(rng) < 0.25;
    if (new_list) {
      if (k > 0) ++list;
      bound = 2.0 + 8.0 * unit(rng);
      best = bound;
    }
    PipelineTest T;
    T.t = 12.0 * unit(rng);
    T.t_in_range = unit(rng) < 0.8 && T.t < bound;
    T.u_valid = unit(rng) < 0.6;
    T.v_valid = unit(rng) < 0.6;
    T.bound = bound;
    T.immediate_bound = best;
    T.list = list;
    T.first_of_list = new_list;
    T.any_hit = shadow;
    if (T.t_in_range && T.t < best && T.u_valid && T.v_valid && !shadow) best = T.t;
    tests.push_back(T);
  }
  return tests;
}

void expect_same(const PipelineRun& a, const PipelineRun& b, const std::string& what) {
  EXPECT_EQ(a.memory_end, b.memory_end) << what;
  EXPECT_EQ(a.done, b.done) << what;
  EXPECT_EQ(a.memory_busy, b.memory_busy) << what;
  EXPECT_EQ(a.words, b.words) << what;
  EXPECT_EQ(a.wasted_words, b.wasted_words) << what;
}

TEST(IntersectionPipeline, OneLookAMomentGivesWhatLookingUntilSettledGives) {
  std::mt19937_64 rng(20261206);
  std::uniform_int_distribution<int> length(1, 24), cycle_ps(0, 4000), stage_ps(0, 40000);
  int zero_times = 0, wasted = 0;
  for (int round = 0; round < 6000; ++round) {
    const auto tests = random_stream(rng, static_cast<std::size_t>(length(rng)));
    // A zero memory cycle or stage time in one round of eight each.
    const auto cycle = static_cast<std::uint64_t>(round % 8 == 3 ? 0 : cycle_ps(rng));
    const auto stage = static_cast<std::uint64_t>(round % 8 == 5 ? 0 : stage_ps(rng));
    zero_times += cycle == 0 || stage == 0;
    const PipelineTiming timing{
        .memory_cycle = sc_core::sc_time::from_value(cycle),
        .stage_time = sc_core::sc_time::from_value(stage),
        .priority = round % 2 == 0 ? FetchPriority::kLaterStages : FetchPriority::kEarlierStages};
    const sc_core::sc_time start =
        sc_core::sc_time::from_value(977u * static_cast<unsigned>(round));
    const PipelineRun once = run_pipeline(tests, start, timing);
    const PipelineRun settled = run_pipeline(tests, start, timing, PipelineLooks::kUntilSettled);
    expect_same(once, settled, "round " + std::to_string(round));
    wasted += settled.wasted_words > 0;
  }
  std::printf("6000 streams compared: %d with a zero time, %d fetching u or v for nothing\n",
              zero_times, wasted);
  // The streams reach the pipeline's feedback (a hit's bound arriving late), or the comparison
  // leaves its hardest case out.
  EXPECT_GT(wasted, 300);
}

}  // namespace
