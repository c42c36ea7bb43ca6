// Numerical stability of the whole renderer: a scene scaled by 1e-6 and by 1e6 must render the
// same picture as the original (every length scales, angles do not), with no NaN or inf in
// any pixel or statistic.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "scenes/nff_reader.hpp"
#include "scenes/scene_writer.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::Vec3;

namespace {

rtsim::scenes::Scene scaled(rtsim::scenes::Scene s, double k) {
  s.camera.from *= k;
  s.camera.at *= k;
  s.camera.hither *= k;
  for (auto& l : s.lights) l.position *= k;
  for (auto& sp : s.spheres) {
    sp.center *= k;
    sp.radius *= k;
  }
  for (auto& p : s.polygons)
    for (auto& v : p.vertices) v *= k;
  for (auto& c : s.cones) {
    c.base *= k;
    c.apex *= k;
    c.base_radius *= k;
    c.apex_radius *= k;
  }
  return s;
}

struct Rendered {
  fs::path dir;
  nlohmann::json stats;
};

Rendered render_nff(const rtsim::scenes::Scene& scene, const std::string& tag) {
  const auto dir = rtsim::test::scratch_dir("scale-" + tag);
  fs::create_directories(dir);
  const auto file = dir / "scene.nff";
  std::ofstream(file) << rtsim::scenes::write_nff(scene);
  const auto out = dir / "out";
  const auto r =
      rtsim::test::run_rtsim("render --scene " + file.string() +
                             " --width 96 --height 96 --aov id -q --out " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return {out, nlohmann::json::parse(rtsim::test::read_file(out / "stats.json"))};
}

class ScaleTest : public ::testing::TestWithParam<const char*> {};

}  // namespace

TEST_P(ScaleTest, ScaledScenesRenderTheSamePicture) {
  const auto base = rtsim::scenes::read_nff(rtsim::test::shared_path(GetParam()));
  const auto ref = render_nff(base, "ref");
  for (double k : {1e-6, 1e6}) {
    const auto got = render_nff(scaled(base, k), k < 1 ? "small" : "large");
    EXPECT_EQ(got.stats["image"]["nonfinite_values"], 0);
    const auto cr = rtsim::test::compare_images((ref.dir / "image.png").string(),
                                                (got.dir / "image.png").string(), 2.0f / 255);
    std::cout << GetParam() << " scaled by " << k << ": max error " << cr.maxerror << ", "
              << cr.nfail << " of 9216 pixels over 2/255\n";
    // Edge pixels may flip where a primary ray grazes a silhouette: allow 0.5%.
    EXPECT_LE(cr.nfail, 46u);
  }
}

INSTANTIATE_TEST_SUITE_P(Spd, ScaleTest,
                         ::testing::Values("scenes/balls-s2.nff", "scenes/tetra-s3.nff",
                                           "scenes/teapot-s2.nff"));
