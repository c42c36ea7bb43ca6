// vax-750's own tests: the frame time is Gaudet's formula.
#include <gtest/gtest.h>

#include <iostream>
#include <string>

#include "tests/test_support.hpp"

using rtsim::test::read_json;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;
using rtsim::test::shared_path;

namespace {

TEST(Vax750, FrameTimeIsGaudetsFormula) {
  // T_t = R_t (T_s + T_i O) (seed 001 L326) with the run's own ray count: pure arithmetic,
  // so the tolerance is rounding only (1e-9 relative).
  const auto dir = scratch_dir("vax");
  const auto r = run_rtsim("run --machine vax-750 --scene " + shared_path("scenes/balls-s1.nff") +
                           " --width 24 --height 24 -q --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = read_json(dir / "stats.json");
  const double rays = s["rays"]["total"].get<double>();
  const double objects = s["scene_stats"]["primitives"].get<double>();
  const double expected = rays * (710e-6 + 429e-6 * objects);
  const double got = s["simulated_time_s"].get<double>();
  std::cout << "vax-750: simulated " << got << " s, formula " << expected << " s\n";
  EXPECT_NEAR(got, expected, expected * 1e-9);
  EXPECT_EQ(s["intersection_tests"].get<double>(), rays * objects);
}

}  // namespace
