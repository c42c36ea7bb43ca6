// ullner-hidden-line (platform/machines/ullner_hidden_line/, firmware/hiddenline/): the drawing a
// run makes from what reaches its divider is the twin's, image and SVG, whatever the timing;
// its time comes from its modules (a slower multiplier, link or divider, a longer pipe moves
// it); an intersection corrupted on its way to the divider changes the drawing; the pipe has
// the seed's processors; a pipe too short for the scene is refused.
#include <gtest/gtest.h>

#include <string>

#include "tests/test_support.hpp"

namespace {

using rtsim::test::read_file;
using rtsim::test::run_machine;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;

const std::string kMachine = "ullner-hidden-line";
const std::string kCubes = "--scene builtin:ullner-cubes --width 128 --height 128";

std::string drawing_of(const nlohmann::ordered_json& s) {
  const std::filesystem::path png = s["image_png"].get<std::string>();
  return read_file(png.parent_path() / "drawing.svg");
}

double hl(const nlohmann::ordered_json& s, const std::string& key) {
  return s["hidden_line"][key].get<double>();
}

TEST(UllnerHiddenLine, TheDrawingIsTheTwinsWhateverTheTiming) {
  for (const std::string& scene : {kCubes, std::string("--scene builtin:spd-teapot --width 96 "
                                                       "--height 72")}) {
    const auto dir = scratch_dir("hidden-line-render");
    const auto r =
        run_rtsim("render --machine " + kMachine + " " + scene + " -q --out " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string svg = read_file(dir / "drawing.svg");
    EXPECT_NE(svg.find("<line "), std::string::npos);
    for (const std::string& p :
         {std::string(""), std::string(" -p pp.multipliers=1 -p cp.multiplication_time=\"20 us\""),
          std::string(" -p pipe.link.lanes=1 -p divider.division_time=\"100 us\""),
          std::string(" -p pipe.plane_processors=5000 -p pipe.link.latency=\"1 us\"")}) {
      SCOPED_TRACE(scene + p);
      const auto s = run_machine(kMachine, "image", scene + p);
      ASSERT_FALSE(s.empty());
      EXPECT_EQ(read_file(s["image_png"].get<std::string>()), read_file(dir / "image.png"));
      EXPECT_EQ(drawing_of(s), svg);
    }
  }
}

TEST(UllnerHiddenLine, TimeComesFromTheModules) {
  const auto base = run_machine(kMachine, "base", kCubes);
  const auto one_multiplier = run_machine(
      kMachine, "mult", kCubes + " -p pp.multipliers=1 -p pp.multiplication_time=\"20 us\"");
  const auto slow_link = run_machine(kMachine, "link", kCubes + " -p pipe.link.bit_time=\"1 us\"");
  const auto slow_divider =
      run_machine(kMachine, "divider", kCubes + " -p divider.division_time=\"200 us\"");
  const auto longer = run_machine(kMachine, "longer", kCubes + " -p pipe.plane_processors=4000");
  ASSERT_FALSE(base.empty() || one_multiplier.empty() || slow_link.empty() ||
               slow_divider.empty() || longer.empty());
  const double frame = hl(base, "frame_time_s");
  std::printf(
      "frame %.4g s; one 20 us multiplier %.4g, 1 us a bit %.4g, 200 us a division %.4g, "
      "4000 plane processors %.4g\n",
      frame, hl(one_multiplier, "frame_time_s"), hl(slow_link, "frame_time_s"),
      hl(slow_divider, "frame_time_s"), hl(longer, "frame_time_s"));
  // Six multiplications of 20 us on one multiplier: 120 us a segment, fifteen message times.
  EXPECT_GT(hl(one_multiplier, "frame_time_s"), frame * 1.5);
  // Twice the bit time: every message takes twice as long.
  EXPECT_GT(hl(slow_link, "frame_time_s"), frame * 1.6);
  EXPECT_GT(hl(slow_divider, "frame_time_s"), frame + 0.05);
  // 4000 - 2490 idle plane processors: the first segment passes each in one message time.
  const double idle = hl(longer, "idle_plane_processors");
  EXPECT_EQ(idle, 4000 - hl(base, "planes"));
  const double first = base["hidden_line"]["segment_latency_s"]["first"].get<double>();
  const double first_longer = longer["hidden_line"]["segment_latency_s"]["first"].get<double>();
  EXPECT_NEAR(first_longer - first, idle * 8e-6, idle * 8e-6 * 0.05);
  // The message time: 16 bits of 500 ns, on six wires.
  EXPECT_DOUBLE_EQ(base["hidden_line"]["message_time_s"]["segment"].get<double>(), 8e-6);
  EXPECT_DOUBLE_EQ(base["hidden_line"]["message_time_s"]["intersection"].get<double>(), 8e-6);
}

TEST(UllnerHiddenLine, ThePipeHasAPlaneProcessorAPlaneAndACleanupProcessorAPolygon) {
  const auto s = run_machine(kMachine, "counts", kCubes + " -p pipe.trailing_cleanups=7");
  ASSERT_FALSE(s.empty());
  // 83 cubes: 498 squares, each 4 edge planes and its own (Fig. 3-28).
  EXPECT_EQ(hl(s, "polygons"), 498);
  EXPECT_EQ(hl(s, "planes"), 498 * 5);
  EXPECT_EQ(hl(s, "plane_processors"), 498 * 5);
  EXPECT_EQ(hl(s, "cleanup_processors"), 498 + 7);
  // Shared edges once; every one sent, and those not hidden whole come out.
  EXPECT_EQ(hl(s, "segments"), s["modules"]["host"]["segments"].get<double>());
  EXPECT_EQ(hl(s, "segments_out"), s["modules"]["pipe.divider"]["segments"].get<double>());
  EXPECT_LT(hl(s, "segments_out"), hl(s, "segments"));
  EXPECT_GT(s["modules"]["pipe"]["suppressed_segments"].get<double>(), 0);
  // Six multiplications a segment at every plane processor, and comparisons on top.
  EXPECT_GE(s["modules"]["pipe"]["multiplications"].get<double>(),
            6.0 * hl(s, "segments_out") * hl(s, "planes") * 0.5);
  // The plane path: 2,490 planes of 65 bits on five wires, 8 us each.
  EXPECT_NEAR(hl(s, "plane_load_s"), 2490 * 8e-6, 1e-9);
}

TEST(UllnerHiddenLine, AnIntersectionCorruptedInFlightChangesTheDrawing) {
  const auto good = run_machine(kMachine, "good", kCubes);
  ASSERT_FALSE(good.empty());
  const std::string image = read_file(good["image_png"].get<std::string>());
  // t_n of an intersection on its way to the divider, its low bits flipped: the hidden part it
  // ends moves, unless it is one no polygon marked.
  int changed = 0;
  for (const int w : {0, 5, 40, 200}) {
    const auto bad = run_machine(kMachine, "fault",
                                 kCubes + " --fault intersection:" + std::to_string(w) + ":0x3fff");
    ASSERT_FALSE(bad.empty());
    EXPECT_TRUE(bad["hidden_line"]["faults_in_flight"][0]["applied"].get<bool>());
    changed += read_file(bad["image_png"].get<std::string>()) != image ? 1 : 0;
  }
  EXPECT_GT(changed, 0);
  // An index past what the last link carried: exit 2, and no output.
  const auto dir = scratch_dir("hidden-line-past");
  const auto r = run_rtsim("run --machine " + kMachine + " " + kCubes +
                           " -q --fault intersection:99999999:1 --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("fewer intersections"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "image.png"));
}

TEST(UllnerHiddenLine, APipeTooShortForTheSceneIsRefused) {
  const auto dir = scratch_dir("hidden-line-short");
  const auto r = run_rtsim("run --machine " + kMachine + " " + kCubes +
                           " -p pipe.plane_processors=100 -q --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("pipe.plane_processors"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("2490"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "image.png"));
}

}  // namespace
