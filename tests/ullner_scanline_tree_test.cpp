// ullner-scanline-tree (platform/machines/ullner_scanline_tree/): its image is the functional
// twin's byte for byte and comes from the segments its links carry (a word corrupted on the way
// to the pixel conversion processor changes it); its time comes from its processors' interaction
// (a slower merging stage or link, or a slower broadcast, moves it through the model); its id
// image is the ray tracer's primary visibility within a pixel; a scene whose lines need more
// segments than the root delivers misses the beam.
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using rtsim::test::read_file;
using rtsim::test::run_machine;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;

const std::string kMachine = "ullner-scanline-tree";
const std::string kTeapot = "--scene builtin:spd-teapot --width 160 --height 120";

std::vector<float> read_channel(const fs::path& p) {
  rtsim::test::forget_cached_image(p.string());
  OIIO::ImageBuf buf(p.string());
  EXPECT_TRUE(buf.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << p;
  const auto& spec = buf.spec();
  std::vector<float> v(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  buf.get_pixels(buf.roi(), OIIO::TypeDesc::FLOAT, v.data());
  return v;
}

const nlohmann::ordered_json& tree(const nlohmann::ordered_json& s) { return s["scanline_tree"]; }

TEST(UllnerScanlineTree, TheImageIsTheTwinsWhateverTheTiming) {
  for (const std::string& scene : {kTeapot, std::string("--scene builtin:ullner-cubes --width 96 "
                                                        "--height 96")}) {
    SCOPED_TRACE(scene);
    const auto dir = scratch_dir("scanline-render");
    const auto r =
        run_rtsim("render --machine " + kMachine + " " + scene + " -q --out " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const std::string& p :
         {std::string(), std::string(" -p mp.stage_time=\"30 us\" -p mp.queue_depth=1"),
          std::string(" -p pcp.paced=false -p scp.link.bit_time=\"1 us\"")}) {
      SCOPED_TRACE(p);
      const auto s = run_machine(kMachine, "split", scene + p);
      ASSERT_FALSE(s.empty());
      EXPECT_EQ(read_file(s["image_png"].get<std::string>()), read_file(dir / "image.png"));
    }
  }
}

TEST(UllnerScanlineTree, ASplitRootsImageIsTheTwinsWhateverTheTiming) {
  // Root splitting (L1561-L1637) changes the image only by the rounding of the breaks at the
  // strips' edges; the twin splits the same way.
  for (const std::string& split_opts : {std::string(" -p tree.split_levels=2"),
                                  std::string(" -p tree.split_levels=5 -p tree.assignment=subvolume")}) {
    SCOPED_TRACE(split_opts);
    const auto dir = scratch_dir("scanline-split-render");
    const auto r = run_rtsim("render --machine " + kMachine + " " + kTeapot + split_opts + " -q --out " +
                             dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const std::string& p :
         {std::string(), std::string(" -p sp.stage_time=\"20 us\" -p sp.queue_depth=64"),
          std::string(" -p pcp.paced=false -p sp.link.bit_time=\"1 us\"")}) {
      SCOPED_TRACE(p);
      const auto s = run_machine(kMachine, "split-root", kTeapot + split_opts + p);
      ASSERT_FALSE(s.empty());
      EXPECT_EQ(read_file(s["image_png"].get<std::string>()), read_file(dir / "image.png"));
      // The seed's processor counts (L1594), and every strip painted by its own processor.
      const auto& split = tree(s)["split"];
      const int n = split["levels"].get<int>();
      EXPECT_EQ(split["splitting_processors"].get<int>(), n << n);
      EXPECT_EQ(split["extra_merging_processors"].get<int>(), (n - 1) * (1 << n) + 1);
      EXPECT_EQ(split["strips"].get<int>(), 1 << n);
    }
  }
}

TEST(UllnerScanlineTree, SplittingDoublesTheRootsBandwidthOnAScenesVisibleSegments) {
  // builtin:ullner-mosaic-N: 2N visible segments a line, none hidden. Unpaced, one root delivers
  // a segment every 3 us (the non-overlapping case); two roots twice that.
  const std::string mosaic = "--scene builtin:ullner-mosaic-32 --width 256 --height 32 "
                             "-p pcp.paced=false";
  double rate[2] = {0, 0};
  for (int n = 0; n < 2; ++n) {
    const auto s = run_machine(kMachine, "mosaic" + std::to_string(n),
                               mosaic + " -p tree.split_levels=" + std::to_string(n));
    ASSERT_FALSE(s.empty());
    const auto& out = tree(s)["scan_out"];
    rate[n] = out["root_segments"].get<double>() / out["time_s"].get<double>();
  }
  std::printf("segments a second: %.0f unsplit, %.0f split once (ratio %.2f)\n", rate[0], rate[1],
              rate[1] / rate[0]);
  EXPECT_GT(rate[1] / rate[0], 1.6);
}

TEST(UllnerScanlineTree, SplitterQueuesShorterThanALineDeadlockTheTreeAndSaySo) {
  // A line bringing more segments to a splitting processor than its queues hold stops the tree
  // (L1633-L1637): bad input, with the depth the run needed, and nothing written.
  const auto dir = scratch_dir("scanline-deadlock");
  const auto r = run_rtsim("run --machine " + kMachine + " " + kTeapot +
                           " -p tree.split_levels=1 -p sp.queue_depth=1 -q --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("sp.queue_depth"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("deadlocked"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "image.png"));
}

TEST(UllnerScanlineTree, FramesArePipelinedAndAVersionNotReadyInTimeIsRescanned) {
  // L1350-L1352: the T&C array transforms the next version while the scan converters scan the
  // last; a version not ready at a frame's start leaves the last on the screen again. Three
  // versions of a turning view: at 6.5 us an instruction the broadcast (26 ms) fits a frame
  // (33.3 ms); with 2000 more instructions a frame (39 ms) each version shows twice but the
  // last. The image is the last version's, the scene's own view, whatever the timing.
  const auto dir = scratch_dir("scanline-frames-render");
  const auto r = run_rtsim("render --machine " + kMachine + " " + kTeapot + " -q --out " +
                           dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string frames = kTeapot + " -p frames=3 -p camera.spin=10";
  const auto in_time = run_machine(kMachine, "frames-in-time", frames);
  const auto late = run_machine(kMachine, "frames-late", frames + " -p tc.motion_instructions=2000");
  ASSERT_FALSE(in_time.empty());
  ASSERT_FALSE(late.empty());
  const auto& a = tree(in_time)["frames"];
  const auto& b = tree(late)["frames"];
  std::printf("in time: %s\nlate: %s\n", a.dump().c_str(), b.dump().c_str());
  EXPECT_EQ(a["shown"].get<int>(), 3);
  EXPECT_EQ(a["rescans"].get<int>(), 0);
  EXPECT_EQ(b["version_by_frame"], nlohmann::json::parse("[0, 0, 1, 1, 2]"));
  EXPECT_EQ(b["rescans"].get<int>(), 2);
  EXPECT_EQ(b["rescanned_polygons"].get<int>(), 2 * tree(late)["polygons"].get<int>());
  for (const auto* s : {&in_time, &late})
    EXPECT_EQ(read_file((*s)["image_png"].get<std::string>()), read_file(dir / "image.png"));
}

TEST(UllnerScanlineTree, ACorruptedSegmentWordOnTheRootsLinkChangesTheImage) {
  const auto clean = run_machine(kMachine, "clean", kTeapot);
  // Segment 400 of the root's stream, its left x (word 1).
  const std::string word = std::to_string(400 * 11 + 1);
  const auto bad = run_machine(kMachine, "fault", kTeapot + " --fault root:" + word + ":0x800");
  ASSERT_FALSE(clean.empty() || bad.empty());
  EXPECT_NE(read_file(clean["image_png"].get<std::string>()),
            read_file(bad["image_png"].get<std::string>()));
  EXPECT_TRUE(tree(bad)["faults_in_flight"][0]["applied"].get<bool>());
  // A word past the root's stream: exit 2, saying so.
  const auto past =
      run_rtsim("run --machine " + kMachine + " " + kTeapot + " -q --fault root:99999999:1");
  EXPECT_EQ(past.exit_code, 2) << past.output;
  EXPECT_NE(past.output.find("fewer words"), std::string::npos) << past.output;
  // A fault point it does not have: exit 2, naming the one it has.
  const auto r = run_rtsim("run --machine " + kMachine + " " + kTeapot + " -q --fault roots:0:1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("root"), std::string::npos) << r.output;
}

TEST(UllnerScanlineTree, ItsTimeComesFromItsProcessorsInteraction) {
  const std::string free = kTeapot + " -p pcp.paced=false";
  const auto base = run_machine(kMachine, "base", free);
  const auto slow_mp = run_machine(kMachine, "slow-mp", free + " -p mp.stage_time=\"9 us\"");
  const auto narrow = run_machine(kMachine, "narrow", free + " -p mp.link.bit_time=\"1 us\"");
  const auto slow_tc = run_machine(kMachine, "slow-tc", free + " -p tc.instruction_time=\"7 us\"");
  ASSERT_FALSE(base.empty() || slow_mp.empty() || narrow.empty() || slow_tc.empty());
  const auto scan_out = [](const nlohmann::ordered_json& s) {
    return tree(s)["scan_out"]["time_s"].get<double>();
  };
  std::printf("scan-out: %.3f ms; 3x stages %.3f, 1 us bits %.3f; T&C %.3f -> %.3f ms\n",
              1e3 * scan_out(base), 1e3 * scan_out(slow_mp), 1e3 * scan_out(narrow),
              1e3 * tree(base)["tc"]["time_s"].get<double>(),
              1e3 * tree(slow_tc)["tc"]["time_s"].get<double>());
  EXPECT_GT(scan_out(slow_mp), 1.5 * scan_out(base));
  EXPECT_GT(scan_out(narrow), 1.5 * scan_out(base));
  // The broadcast: the program's instructions at the instruction time (lockstep, L1334).
  EXPECT_NEAR(tree(slow_tc)["tc"]["time_s"].get<double>(),
              tree(base)["tc"]["instructions"].get<double>() * 7e-6, 1e-9);
  EXPECT_EQ(scan_out(slow_tc), scan_out(base));
}

TEST(UllnerScanlineTree, ItsIdImageIsTheRayTracersPrimaryVisibilityWithinAPixel) {
  for (const std::string& scene : {kTeapot, std::string("--scene builtin:ullner-cubes --width 128 "
                                                        "--height 128")}) {
    SCOPED_TRACE(scene);
    const auto tree_dir = scratch_dir("scanline-id"), traced_dir = scratch_dir("traced-id");
    const auto a = run_rtsim("render --machine " + kMachine + " " + scene + " --aov id -q --out " +
                             tree_dir.string());
    const auto b = run_rtsim("render " + scene + " --aov id -q --out " + traced_dir.string());
    ASSERT_EQ(a.exit_code, 0) << a.output;
    ASSERT_EQ(b.exit_code, 0) << b.output;
    const auto ta = read_channel(tree_dir / "id.exr"), tb = read_channel(traced_dir / "id.exr");
    ASSERT_EQ(ta.size(), tb.size());
    const int w = std::stoi(scene.substr(scene.find("--width ") + 8));
    const int h = static_cast<int>(ta.size()) / w;
    std::size_t near = 0, exact = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float id = ta[static_cast<std::size_t>(y * w + x)];
        exact += id == tb[static_cast<std::size_t>(y * w + x)] ? 1 : 0;
        bool found = false;
        for (int dy = -1; dy <= 1 && !found; ++dy)
          for (int dx = -1; dx <= 1 && !found; ++dx) {
            const int u = x + dx, v = y + dy;
            if (u >= 0 && v >= 0 && u < w && v < h)
              found = tb[static_cast<std::size_t>(v * w + u)] == id;
          }
        near += found ? 1 : 0;
      }
    const double n = static_cast<double>(ta.size());
    std::printf("id image: %.2f%% the traced primitive, %.2f%% within a pixel\n", 100 * exact / n,
                100 * near / n);
    EXPECT_GE(near / n, 0.99);
  }
}

TEST(UllnerScanlineTree, LinesNeedingMoreSegmentsThanTheRootDeliversMissTheBeam) {
  // At 512 lines a line has 65 us (L1551), about 11 segments at the root's pace: the teapot's
  // lines need 14 on average and dozens round the teapot; four quads need at most four.
  const auto dir = scratch_dir("scanline-four-quads");
  fs::create_directories(dir);
  const auto nff = dir / "quads.nff";
  {
    std::ofstream f(nff);
    f << "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 512 512\n"
         "b 0.2 0.3 0.4\nl 0 0 10\nf 0.8 0.5 0.3 1 0 0 0 1\n";
    for (const char* q : {"-1.5 -1.5 0  -0.2 -1.5 0  -0.2 -0.2 0  -1.5 -0.2 0",
                          "0.2 -1.5 0  1.5 -1.5 0  1.5 -0.2 0  0.2 -0.2 0",
                          "-1.5 0.2 0  -0.2 0.2 0  -0.2 1.5 0  -1.5 1.5 0",
                          "0.2 0.2 0  1.5 0.2 0  1.5 1.5 0  0.2 1.5 0"})
      f << "p 4\n" << q << "\n";
  }
  const auto paced = run_machine(kMachine, "paced", "--scene builtin:spd-teapot");
  const auto sparse = run_machine(kMachine, "sparse", "--scene " + nff.string());
  ASSERT_FALSE(paced.empty() || sparse.empty());
  const auto& out = tree(paced)["scan_out"];
  const auto& few = tree(sparse)["scan_out"];
  std::printf(
      "teapot: %s late lines of 512, %.1f segments a line (max %s); four quads: %s late, "
      "max %s a line\n",
      out["late_lines"].dump().c_str(), out["segments_a_line_mean"].get<double>(),
      out["segments_a_line_max"].dump().c_str(), few["late_lines"].dump().c_str(),
      few["segments_a_line_max"].dump().c_str());
  EXPECT_GT(out["late_lines"].get<int>(), 100);
  EXPECT_GT(out["time_s"].get<double>(), 1.0 / 30.0);
  EXPECT_EQ(few["late_lines"].get<int>(), 0);
  EXPECT_NEAR(few["time_s"].get<double>(), 1.0 / 30.0, 1e-6);
}

TEST(UllnerScanlineTree, BadInputIsRefusedClearly) {
  const auto spp = run_rtsim("run --machine " + kMachine + " " + kTeapot + " --spp 4 -q");
  EXPECT_EQ(spp.exit_code, 2) << spp.output;
  EXPECT_NE(spp.output.find("one sample"), std::string::npos) << spp.output;
  const auto wide = run_rtsim("run --machine " + kMachine +
                              " --scene builtin:spd-teapot --width 5000 --height 16 -q");
  EXPECT_EQ(wide.exit_code, 2) << wide.output;
  EXPECT_NE(wide.output.find("12-bit"), std::string::npos) << wide.output;
  const auto big = run_rtsim("run --machine " + kMachine +
                             " --scene builtin:default -p mesh.sphere_segments=1024 -q");
  EXPECT_EQ(big.exit_code, 2) << big.output;
  EXPECT_NE(big.output.find("polygons"), std::string::npos) << big.output;
  // A run that would show more frames than it may (versions whose broadcast spans many
  // frames) is refused before it starts.
  const auto frames = run_rtsim("run --machine " + kMachine + " " + kTeapot +
                                " -p frames=1000 -p tc.motion_instructions=100000000 -q");
  EXPECT_EQ(frames.exit_code, 2) << frames.output;
  EXPECT_NE(frames.output.find("would show"), std::string::npos) << frames.output;
  // More polygons than the host can start a SystemC thread for (two a polygon): refused, not a
  // crash while the stacks are mapped.
  const auto threads = run_rtsim("run --machine " + kMachine +
                                 " --scene builtin:ullner-mosaic-751 --width 16 --height 16 -q");
  EXPECT_EQ(threads.exit_code, 2) << threads.output;
  EXPECT_NE(threads.output.find("at most 12000"), std::string::npos) << threads.output;
}

}  // namespace
