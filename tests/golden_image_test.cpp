// Golden-image tests: `rtsim render` of every shared scene and the built-in scenes, compared
// with the reviewed images in tests/golden/ by OpenImageIO's image comparison.
// Tolerance: a pixel fails if any channel differs by more than 2/255; at most 0.2% of the
// pixels may fail. Renders are deterministic, so on one machine the difference is zero; the
// tolerance absorbs a different libm or compiler rounding a handful of edge pixels.
// To accept a deliberate change: RTSIM_UPDATE_GOLDEN=1 ctest -R Golden, then look at the
// images in tests/golden/ before committing them.
#include <gtest/gtest.h>

#include <cstdlib>

#include "tests/test_support.hpp"

namespace fs = std::filesystem;

namespace {

struct GoldenCase {
  const char* name;
  std::string scene;
  const char* extra;
};

std::vector<GoldenCase> cases() {
  using rtsim::test::shared_path;
  return {
      {"balls-s1", shared_path("scenes/balls-s1.nff"), ""},
      {"balls-s2", shared_path("scenes/balls-s2.nff"), ""},
      {"balls-s3", shared_path("scenes/balls-s3.nff"), ""},
      {"tetra-s3", shared_path("scenes/tetra-s3.nff"), ""},
      {"teapot-s2", shared_path("scenes/teapot-s2.nff"), ""},
      {"teapot-bpt", shared_path("scenes/teapot.bpt"), ""},
      {"default", "builtin:default", ""},
      {"npp-412", "builtin:npp-412", ""},
      {"ullner-cubes", "builtin:ullner-cubes", ""},
  };
}

void PrintTo(const GoldenCase& c, std::ostream* os) { *os << c.name; }

constexpr int kSize = 128;
constexpr float kPixelTolerance = 2.0f / 255.0f;
constexpr double kMaxFailFraction = 0.002;

class GoldenImage : public ::testing::TestWithParam<GoldenCase> {};

}  // namespace

TEST_P(GoldenImage, MatchesReviewedImage) {
  const GoldenCase& c = GetParam();
  const auto dir = rtsim::test::scratch_dir(std::string("golden-") + c.name);
  const auto r = rtsim::test::run_rtsim(
      "render --scene " + c.scene + " --width " + std::to_string(kSize) + " --height " +
      std::to_string(kSize) + " -q " + c.extra + " --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const fs::path golden =
      fs::path(RTSIM_TEST_DATA_DIR).parent_path() / "golden" / (std::string(c.name) + ".png");
  if (std::getenv("RTSIM_UPDATE_GOLDEN")) {
    fs::create_directories(golden.parent_path());
    fs::copy_file(dir / "image.png", golden, fs::copy_options::overwrite_existing);
    GTEST_SKIP() << "updated " << golden;
  }
  ASSERT_TRUE(fs::exists(golden)) << golden << " missing (see the header of this file)";
  const auto cr =
      rtsim::test::compare_images((dir / "image.png").string(), golden.string(), kPixelTolerance);
  ASSERT_FALSE(cr.error) << "could not compare " << golden;
  const double fail_fraction = static_cast<double>(cr.nfail) / (kSize * kSize);
  std::cout << c.name << ": max error " << cr.maxerror << " (tolerance " << kPixelTolerance << "), "
            << cr.nfail << " failing pixels = " << 100.0 * fail_fraction << "% (limit "
            << 100.0 * kMaxFailFraction << "%)\n";
  EXPECT_LE(fail_fraction, kMaxFailFraction);
}

INSTANTIATE_TEST_SUITE_P(Scenes, GoldenImage, ::testing::ValuesIn(cases()), [](const auto& info) {
  return rtsim::test::gtest_param_name(info.param.name);
});
