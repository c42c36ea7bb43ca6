// BusyTimeline: busy intervals kept in a bounded number of bins and resampled into windows of
// the frame (stats.json `utilization_windows`); the level steps, occupancy and kept intervals
// the traces' signals are drawn from. Plain arithmetic on sc_time, no simulation.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <optional>
#include <random>
#include <systemc>
#include <utility>

#include "modules/busy_timeline.hpp"
#include "modules/occupancy.hpp"

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

TEST(BusyTimeline, TurnsToBinsAfterItsSparseIntervalsAndKeepsTheLastOneExact) {
  // Back-to-back intervals extend the one recorded last: 5000 of them are one interval, and the
  // timeline stays sparse (no bins).
  BusyTimeline joined;
  for (std::uint64_t k = 0; k < 5000; ++k) joined.add(ps(k * 1'000), ps(1'000));
  EXPECT_EQ(joined.bins(), 0u);
  EXPECT_EQ(joined.total(), ps(5'000'000));
  const auto whole = joined.windows(ps(0), ps(5'000'000), 10);
  for (const double v : whole.values) EXPECT_NEAR(v, 1.0, 1e-12);
  // With gaps, exactly kSparseIntervals intervals stay sparse; the next one turns the timeline
  // to bins, with every interval in them, the last one recorded included.
  BusyTimeline gaps;
  const std::uint64_t n = BusyTimeline::kSparseIntervals;
  for (std::uint64_t k = 0; k < n; ++k) gaps.add(ps(2 * k * 1'000), ps(1'000));
  EXPECT_EQ(gaps.bins(), 0u);
  EXPECT_EQ(gaps.total(), ps(n * 1'000));
  EXPECT_NEAR(sum_busy_s(gaps.windows(ps(0), ps(2 * n * 1'000), 8)), n * 1e-9, 1e-15);
  gaps.add(ps(2 * n * 1'000), ps(1'000));
  EXPECT_GT(gaps.bins(), 0u);
  EXPECT_EQ(gaps.total(), ps((n + 1) * 1'000));
  EXPECT_NEAR(sum_busy_s(gaps.windows(ps(0), ps(2 * (n + 1) * 1'000), 8)), (n + 1) * 1e-9, 1e-15);
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

TEST(BusyTimeline, BackToBackPiecesGiveTheBinsOfEachPieceAddedAlone) {
  // A binned timeline holds an interval that starts where the one before ended and extends it
  // until another comes or the bins are read. Read after every add, each piece goes into the
  // bins alone (as before it was held); left alone, back-to-back pieces go in as one. The bins,
  // the total and the windows are the same either way, in every order of bursts, with bursts
  // reaching back before the first and far past the last (so pairs merge and bins grow left).
  std::mt19937_64 random(11);
  for (int trial = 0; trial < 40; ++trial) {
    BusyTimeline each, merged;
    std::uint64_t lo = ~std::uint64_t{0}, hi = 0;
    const int bursts = 1500 + static_cast<int>(random() % 1500);
    for (int b = 0; b < bursts; ++b) {
      std::uint64_t at = 1'000'000'000 + random() % (trial % 2 ? 400'000'000 : 4'000'000'000ull);
      if (b > 1200 && random() % 50 == 0) at /= 2;  // a burst before everything so far
      const int pieces = 1 + static_cast<int>(random() % 6);
      for (int k = 0; k < pieces; ++k) {
        const std::uint64_t d = 1 + random() % 50'000;
        each.add(ps(at), ps(d));
        ASSERT_GT(each.bins() + 1, 0u);  // read: the piece goes into the bins now
        merged.add(ps(at), ps(d));
        lo = std::min(lo, at);
        at += d;
        hi = std::max(hi, at);
      }
    }
    // The total and the windows first: they take the interval still held as they find it.
    EXPECT_EQ(merged.total(), each.total()) << trial;
    for (const auto& [begin, end] : {std::pair{lo, hi}, std::pair{lo + (hi - lo) / 3, hi - 7}}) {
      const auto a = each.windows(ps(begin), ps(end), 100);
      const auto m = merged.windows(ps(begin), ps(end), 100);
      ASSERT_EQ(m.values.size(), a.values.size());
      for (std::size_t j = 0; j < a.values.size(); ++j)
        ASSERT_EQ(m.values[j], a.values[j]) << trial << " window " << j;  // bit for bit
    }
    ASSERT_EQ(merged.bins(), each.bins()) << trial;
    EXPECT_EQ(merged.bin_width_ticks(), each.bin_width_ticks()) << trial;
  }
}

TEST(BusyTimeline, ThirtyTwoBitBinsWidenWhenTheyMustAndGiveTheSixtyFourBitBinsExactly) {
  // The bins are 32-bit until a bin would pass 2^32 - 1 ticks, then all 64-bit. Against
  // timelines that keep 64-bit bins from the start (WideBins), on random streams: back-to-back
  // and overlapping intervals, in any order, over spans from microseconds to a minute (bins of
  // up to 2^33 ticks, so full bins and merged pairs outgrow 32 bits), read or not between adds.
  // The total, the bins' width and count and every window are the same, bit for bit.
  std::mt19937_64 random(23);
  int widened = 0, narrow = 0;
  for (int trial = 0; trial < 60; ++trial) {
    BusyTimeline t;
    std::optional<BusyTimeline> wide;
    {
      const BusyTimeline::WideBins wide_bins;
      wide.emplace();
    }
    EXPECT_TRUE(wide->wide_bins());
    EXPECT_FALSE(t.wide_bins());
    // 1 us to 67 s in ticks of 1 ps; every second trial 17 s to 134 s, where bins are 2^31
    // ticks or wider.
    const std::uint64_t span = std::uint64_t{1'000'000}
                               << (trial % 2 ? random() % 27 : 24 + random() % 4);
    const bool overlapping = trial % 3 == 0;
    std::uint64_t lo = ~std::uint64_t{0}, hi = 0, at = random() % span;
    const int n = 1500 + static_cast<int>(random() % 3000);
    for (int k = 0; k < n; ++k) {
      if (random() % 4 == 0) at = random() % span;  // anywhere, earlier or later
      const std::uint64_t d = 1 + random() % std::max<std::uint64_t>(span / 200, 2);
      t.add(ps(at), ps(d));
      wide->add(ps(at), ps(d));
      if (random() % 8 == 0) {
        ASSERT_EQ(t.bins(), wide->bins()) << trial;  // read between adds
      }
      lo = std::min(lo, at);
      hi = std::max(hi, at + d);
      at += overlapping ? d / 2 : d;  // half of each interval under the next one
    }
    ASSERT_EQ(t.total(), wide->total()) << trial;
    ASSERT_EQ(t.bins(), wide->bins()) << trial;
    ASSERT_EQ(t.bin_width_ticks(), wide->bin_width_ticks()) << trial;
    for (const auto& [begin, end] : {std::pair{lo, hi}, std::pair{lo + (hi - lo) / 3, hi - 7}}) {
      const auto a = t.windows(ps(begin), ps(end), 100);
      const auto b = wide->windows(ps(begin), ps(end), 100);
      ASSERT_EQ(a.values.size(), b.values.size());
      for (std::size_t j = 0; j < a.values.size(); ++j)
        ASSERT_EQ(a.values[j], b.values[j]) << trial << " window " << j;  // bit for bit
    }
    (t.wide_bins() ? widened : narrow) += t.bins() > 0 ? 1 : 0;
  }
  // Both kinds of run happened: some stayed 32-bit, some had to widen.
  EXPECT_GT(widened, 5);
  EXPECT_GT(narrow, 5);
}

TEST(BusyTimeline, ABinOfMoreThanTwoToTheThirtyTwoTicksWidensAndKeepsItsTotal) {
  // Three intervals of 20 s (2e13 ticks) over the same time, after enough short ones to turn
  // the timeline to bins: bins of 2^32 ticks (the span of 40 s in at most 16384), each holding
  // three times its width.
  BusyTimeline t;
  for (std::uint64_t k = 0; k <= BusyTimeline::kSparseIntervals; ++k) t.add(ps(2 * k), ps(1));
  ASSERT_GT(t.bins(), 0u);
  EXPECT_FALSE(t.wide_bins());
  const std::uint64_t s = 20'000'000'000'000;
  for (int k = 0; k < 3; ++k) t.add(ps(s), ps(s));
  EXPECT_GE(t.bin_width_ticks(), std::uint64_t{1} << 31);
  EXPECT_TRUE(t.wide_bins());
  EXPECT_EQ(t.total(), ps(3 * s + BusyTimeline::kSparseIntervals + 1));
  const auto w = t.windows(ps(s), ps(2 * s), 10);
  // One bin width of error at each window edge (the edges need not fall on bins'), times 3.
  const double tol = 3.0 * 2.0 * static_cast<double>(t.bin_width_ticks()) / (s / 10.0);
  EXPECT_LT(tol, 0.02);
  for (const double v : w.values) EXPECT_NEAR(v, 3.0, tol);
}

TEST(BusyTimeline, EmptyOrDegenerateFrameGivesNoWindows) {
  BusyTimeline t;
  EXPECT_TRUE(t.windows(ps(0), ps(100), 10).values.size() == 10u);
  EXPECT_TRUE(t.windows(ps(100), ps(100), 10).values.empty());
  EXPECT_TRUE(t.windows(ps(0), ps(100), 0).values.empty());
  t.add(ps(5), ps(0));  // zero-length: nothing
  EXPECT_EQ(t.bins(), 0u);
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

// --- the traces' signals come from the same objects -------------------------------------------

TEST(LevelSteps, DownsGoFirstAndEachTimeGivesOneNetChange) {
  using rtsim::modules::LevelChange;
  // Up at 1, 3, 3; down at 3 (a hand-over: no spike to 3), 5, 9.
  const auto c = rtsim::modules::level_changes({1, 3, 3}, {3, 5, 9});
  ASSERT_EQ(c.size(), 4u);
  const std::vector<std::pair<std::uint64_t, long>> want = {{1, 1}, {3, 2}, {5, 1}, {9, 0}};
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_EQ(c[i].t, want[i].first);
    EXPECT_EQ(c[i].level, want[i].second);
  }
  // A put and a get at the same time of an empty queue: no change at all.
  EXPECT_TRUE(rtsim::modules::level_changes({4}, {4}).empty());
}

TEST(Occupancy, DepthChangesIntegrateToTheSummary) {
  rtsim::modules::Occupancy q;
  for (std::uint64_t t : {10, 5, 12, 12, 30}) q.put(ps(t));
  for (std::uint64_t t : {20, 12, 31, 35, 40}) q.got(ps(t));
  const auto s = q.summarize(ps(0), ps(50));
  long double area = 0;
  long level = 0, max = 0;
  std::uint64_t last = 0;
  for (const auto& c : q.depth_changes()) {
    area += static_cast<long double>(level) * static_cast<long double>(c.t - last);
    last = c.t;
    level = c.level;
    max = std::max(max, level);
  }
  area += static_cast<long double>(level) * static_cast<long double>(50 - last);
  EXPECT_EQ(level, 0);
  EXPECT_DOUBLE_EQ(static_cast<double>(area / 50), s.mean);
  EXPECT_EQ(max, s.max);
}

TEST(BusyTimeline, KeepsItsIntervalsOnlyWhileATraceAsksAndTheyAddUpToTheTotal) {
  BusyTimeline plain;
  EXPECT_FALSE(plain.keeps_intervals());
  plain.add(ps(0), ps(5));
  EXPECT_TRUE(plain.level_changes().empty());
  {
    BusyTimeline::KeepIntervals keep;
    BusyTimeline t;
    EXPECT_TRUE(t.keeps_intervals());
    t.add(ps(10), ps(5));  // [10, 15)
    t.add(ps(15), ps(5));  // back to back: [10, 20) is one busy stretch
    t.add(ps(30), ps(10));
    t.add(ps(35), ps(10));  // overlapping: level 2 over [35, 40)
    t.add(ps(2), ps(3));    // earlier than the rest
    const auto c = t.level_changes();
    const std::vector<std::pair<std::uint64_t, long>> want = {{2, 1},  {5, 0},  {10, 1}, {20, 0},
                                                              {30, 1}, {35, 2}, {40, 1}, {45, 0}};
    ASSERT_EQ(c.size(), want.size());
    std::uint64_t busy = 0, last = 0;
    long level = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
      EXPECT_EQ(c[i].t, want[i].first);
      EXPECT_EQ(c[i].level, want[i].second);
      busy += static_cast<std::uint64_t>(level) * (c[i].t - last);
      last = c[i].t;
      level = c[i].level;
    }
    EXPECT_EQ(busy, t.total().value());
  }
  EXPECT_FALSE(BusyTimeline().keeps_intervals());
}
