// Adaptive square subdivision (firmware/tasks/adaptive_sampling.hpp): VOL2's Fig. 8 (seed 004
// L358), a curve boundary across a square refined three levels, takes 51 samples with the
// conventional scheme and 29 with partial subdivision; the fill between samples.
#include "firmware/tasks/adaptive_sampling.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <set>
#include <utility>

namespace {

using rtsim::tasks::AdaptiveSquare;
using rtsim::tasks::Subdivision;

/// Samples a square of side 8 refined to 1 (three levels, as in Fig. 8) whose value is 1 inside
/// the region `inside` and 0 outside; the criterion: two samples differ if their values do.
std::size_t samples(Subdivision scheme, const std::function<bool(double, double)>& inside,
                    std::set<std::pair<int, int>>* where = nullptr) {
  AdaptiveSquare<double> sq(8, 1, scheme);
  sq.run(
      [&](int x, int y) {
        if (where) {
          EXPECT_TRUE(where->insert({x, y}).second) << "sampled twice: " << x << "," << y;
        }
        return inside(x, y) ? 1.0 : 0.0;
      },
      [](double a, double b) { return a != b; });
  return sq.samples();
}

TEST(AdaptiveSampling, Fig8CurveBoundary51Against29) {
  // A gently curved boundary across the square (a circle of radius 11 centred off its corner):
  // "the curve boundary triggers the subdivision criterion" (L358).
  const auto arc = [](double x, double y) { return (x + 4) * (x + 4) + (y + 4) * (y + 4) < 121; };
  std::set<std::pair<int, int>> conv, part;
  const std::size_t c = samples(Subdivision::kConventional, arc, &conv);
  const std::size_t p = samples(Subdivision::kPartial, arc, &part);
  std::printf("Fig. 8: conventional %zu samples (seed 51), partial %zu (seed 29)\n", c, p);
  EXPECT_EQ(c, 51u);
  EXPECT_EQ(p, 29u);
  // Partial takes a subset of the conventional scheme's samples.
  for (const auto& s : part) EXPECT_TRUE(conv.count(s)) << s.first << "," << s.second;
}

TEST(AdaptiveSampling, AStraightBoundaryAlwaysCostsPartialHalfPlusFour) {
  // Every straight boundary that crosses the square: partial = (conventional + 7) / 2 (Fig. 8's
  // pair satisfies it: (51 + 7) / 2 = 29). Lines y = k x + m over slopes and offsets.
  int crossing = 0;
  for (int k10 = -30; k10 <= 30; ++k10)
    for (int m10 = -80; m10 < 160; m10 += 3) {
      const double k = k10 / 10.0, m = m10 / 10.0;
      const auto above = [&](double x, double y) { return y > k * x + m; };
      const std::size_t c = samples(Subdivision::kConventional, above);
      const std::size_t p = samples(Subdivision::kPartial, above);
      if (c == 4) {
        EXPECT_EQ(p, 4u);  // four alike corners: nothing to refine
        continue;
      }
      ++crossing;
      EXPECT_EQ(2 * p, c + 7) << "y = " << k << " x + " << m;
    }
  EXPECT_GT(crossing, 1000);
}

TEST(AdaptiveSampling, AlikeCornersAreFilledBetweenAndRefinementStopsAtTheFinest) {
  // A smooth value whose corners never differ by more than the threshold: 4 samples, the rest
  // bilinear between them.
  AdaptiveSquare<double> smooth(16, 4, Subdivision::kPartial);
  smooth.run([](int x, int y) { return 0.01 * x + 0.02 * y; },
             [](double a, double b) { return std::abs(a - b) > 1.0; });
  EXPECT_EQ(smooth.samples(), 4u);
  EXPECT_EQ(smooth.positions(), 5);
  EXPECT_NEAR(smooth.value(2, 1), 0.01 * 8 + 0.02 * 4, 1e-12);
  EXPECT_FALSE(smooth.sampled(2, 1));
  // Everything differs: both schemes sample every position once (5 x 5 at 16 / 4).
  for (const Subdivision s : {Subdivision::kConventional, Subdivision::kPartial}) {
    AdaptiveSquare<double> all(16, 4, s);
    all.run([](int x, int y) { return static_cast<double>(x * 17 + y); },
            [](double a, double b) { return a != b; });
    EXPECT_EQ(all.samples(), 25u);
    EXPECT_TRUE(all.sampled(3, 3));
  }
  EXPECT_THROW(AdaptiveSquare<double>(12, 4, Subdivision::kPartial), std::invalid_argument);
}

}  // namespace
