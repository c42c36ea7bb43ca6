// BusyTimeline: busy intervals kept in a bounded number of bins and resampled into windows of
// the frame (stats.json `utilization_windows`). Plain arithmetic on sc_time, no simulation.
#include <gtest/gtest.h>

#include <numeric>
#include <systemc>

#include "modules/busy_timeline.hpp"
#include "modules/occupancy.hpp"
#include "modules/stats_registry.hpp"

extern "C" int sc_main(int, char*[]) { return 0; }

using rtsim::modules::BusyTimeline;
using sc_core::sc_time;

namespace {
sc_time ps(std::uint64_t v) { return sc_time::from_value(v); }
double sum_busy_s(const rtsim::modules::UtilizationWindows& w) {
  return std::accumulate(w.values.begin(), w.values.end(), 0.0) * w.window_s;
}
}  // namespace

TEST(BusyTimeline, BackToBackIntervalsAreFullyBusyInEveryWindow) {
  // A VAX-like module: 256 rays of 0.306 s each, back to back from 0 (the span outgrows the
  // bins many times over, so pairs merge all along).
  BusyTimeline t;
  const std::uint64_t ray = 306'456'375'000ull;  // ps
  for (std::uint64_t i = 0; i < 256; ++i) t.add(ps(i * ray), ps(ray));
  EXPECT_LE(t.bins(), BusyTimeline::kMaxBins);
  EXPECT_EQ(t.total(), ps(256 * ray));
  const auto w = t.windows(ps(0), ps(256 * ray), 100);
  ASSERT_EQ(w.values.size(), 100u);
  for (std::size_t j = 0; j < w.values.size(); ++j) EXPECT_NEAR(w.values[j], 1.0, 1e-9) << j;
  EXPECT_NEAR(w.window_s, 256 * ray * 1e-12 / 100, 1e-12);
}

TEST(BusyTimeline, HalfBusyFrameShowsTheEdgeWithinOneBin) {
  // Busy over [0, 1 ms) in 1 us slices every other microsecond, then idle until 2 ms: 50% in
  // the first half, 0 in the second. The edge at 1 ms falls inside one window of 20 us.
  BusyTimeline t;
  for (std::uint64_t k = 0; k < 500; ++k) t.add(ps(2 * k * 1'000'000), ps(1'000'000));
  const auto w = t.windows(ps(0), ps(2'000'000'000), 100);
  ASSERT_EQ(w.values.size(), 100u);
  for (std::size_t j = 0; j < 50; ++j) EXPECT_NEAR(w.values[j], 0.5, 0.013) << j;
  for (std::size_t j = 50; j < 100; ++j) EXPECT_NEAR(w.values[j], 0.0, 1e-12) << j;
  EXPECT_NEAR(sum_busy_s(w), 500e-6, 1e-12);
}

TEST(BusyTimeline, IntervalsInAnyOrderAndWindowsOfASubRange) {
  // Recorded late first, then earlier (a temporally decoupled thread may do that); windows
  // over [10 us, 30 us) only: the interval before 10 us is left out.
  BusyTimeline t;
  t.add(ps(20'000'000), ps(10'000'000));  // [20, 30) us
  t.add(ps(12'000'000), ps(3'000'000));   // [12, 15) us
  t.add(ps(0), ps(5'000'000));            // [0, 5) us
  EXPECT_EQ(t.total(), ps(18'000'000));
  const auto w = t.windows(ps(10'000'000), ps(30'000'000), 4);  // 5 us windows
  ASSERT_EQ(w.values.size(), 4u);
  EXPECT_NEAR(w.begin_s, 10e-6, 1e-18);
  EXPECT_NEAR(w.window_s, 5e-6, 1e-18);
  // The bins (2 ns here) need not fall on the window edges: one bin width of error per edge.
  const double tol = 2.0 * static_cast<double>(t.bin_width_ticks()) / 5e6;
  EXPECT_LT(tol, 0.002);
  EXPECT_NEAR(w.values[0], 0.6, tol);  // [12, 15) in [10, 15)
  EXPECT_NEAR(w.values[1], 0.0, tol);
  EXPECT_NEAR(w.values[2], 1.0, tol);
  EXPECT_NEAR(w.values[3], 1.0, tol);
  EXPECT_NEAR(sum_busy_s(w), 13e-6, 1e-15);  // everything after 10 us
}

TEST(BusyTimeline, EmptyOrDegenerateFrameGivesNoWindows) {
  BusyTimeline t;
  EXPECT_TRUE(t.windows(ps(0), ps(100), 10).values.size() == 10u);
  EXPECT_TRUE(t.windows(ps(100), ps(100), 10).values.empty());
  EXPECT_TRUE(t.windows(ps(0), ps(100), 0).values.empty());
  t.add(ps(5), ps(0));  // zero-length: nothing
  EXPECT_EQ(t.bins(), 0u);
}

TEST(StatsRegistry, WritesUtilizationWindowsOnlyWhenRecorded) {
  rtsim::modules::StatsRegistry reg;
  BusyTimeline t;
  t.add(ps(0), ps(500));
  auto& a = reg.module("a");
  a.busy = ps(500);
  a.windows = t.windows(ps(0), ps(1000), 2);
  reg.module("b").busy = ps(10);
  const auto j = reg.to_json(ps(1000));
  ASSERT_TRUE(j["a"].contains("utilization_windows"));
  EXPECT_EQ(j["a"]["utilization_windows"]["values"].size(), 2u);
  EXPECT_DOUBLE_EQ(j["a"]["utilization_windows"]["values"][0].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j["a"]["utilization_windows"]["values"][1].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(j["a"]["utilization_windows"]["window_s"].get<double>(), 500e-12);
  EXPECT_FALSE(j["b"].contains("utilization_windows"));
}

TEST(Occupancy, PutsStampedOutOfOrderGiveTheTimeWeightedMean) {
  // A producer may stamp a put earlier than its previous one (a ray with no intersections
  // answered before the previous ray leaves the pipe). Items in [10, 30) and [5, 20) over
  // [0, 40): area 20 + 15 = 35, mean 35 / 40; at most 2 at once.
  rtsim::modules::Occupancy q;
  q.put(ps(10));
  q.put(ps(5));
  q.got(ps(20));
  q.got(ps(30));
  const auto s = q.summarize(ps(0), ps(40));
  EXPECT_DOUBLE_EQ(s.mean, 35.0 / 40.0);
  EXPECT_EQ(s.max, 2);
}
