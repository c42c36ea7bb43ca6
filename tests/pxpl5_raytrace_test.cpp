// pxpl5-raytrace (seed 004 VOL2): the image, built from the samples that crossed the token ring,
// equals the functional render whatever the scheme, order, node counts and ring; a sample
// changed on the ring changes it; the scene must fit a GP's memory; the ring carries every
// message and the casters share the work.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::test::read_file;
using rtsim::test::read_json;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;
using rtsim::test::shared_path;

namespace {

nlohmann::ordered_json run_pxpl5(const std::string& tag, const std::string& args) {
  return rtsim::test::run_machine("pxpl5-raytrace", tag, args);
}

TEST(Pxpl5Raytrace, ImageEqualsTheFunctionalRenderForEverySchemeAndSize) {
  for (const std::string& scene :
       {std::string("builtin:default"), shared_path("scenes/balls-s1.nff")}) {
    const std::string base = "--scene " + scene + " --width 80 --height 60";
    const fs::path golden = scratch_dir("pxpl5-golden");
    const auto g =
        run_rtsim("render --machine pxpl5-raytrace " + base + " -q --out " + golden.string());
    ASSERT_EQ(g.exit_code, 0) << g.output;
    const std::string want = read_file(golden / "image.png");
    fs::remove_all(golden);
    for (const char* variant :
         {"", " -p assign.scheme=rows", " -p assign.square=16 -p assign.order=screen",
          " -p caster_count=1 -p compositor_count=1", " -p caster_count=5 -p compositor_count=3",
          " -p ring.service=one_packet -p ring.max_packet_bytes=64",
          " -p frames=3 -p camera.spin=10"}) {
      const auto s = run_pxpl5("image", base + variant + " --overhead");
      ASSERT_FALSE(s.empty());
      EXPECT_TRUE(s.at("functional_image_identical").get<bool>()) << base << variant;
      EXPECT_EQ(read_file(s.at("image_png").get<std::string>()), want) << base << variant;
    }
  }
}

TEST(Pxpl5Raytrace, ASampleChangedOnTheRingChangesTheImage) {
  const std::string base = "--scene builtin:default --width 128 --height 128";
  const auto clean = run_pxpl5("clean", base);
  const auto bad = run_pxpl5("bad", base + " -p fault.corrupt_samples=3");
  ASSERT_FALSE(clean.empty() || bad.empty());
  EXPECT_EQ(clean["pxpl5"]["samples_messages"], 4);
  EXPECT_NE(read_file(clean.at("image_png").get<std::string>()),
            read_file(bad.at("image_png").get<std::string>()));
}

TEST(Pxpl5Raytrace, TheRingCarriesEveryMessageAndTheCastersShareTheWork) {
  const auto s = run_pxpl5("ring", "--scene builtin:default --width 128 --height 128");
  ASSERT_FALSE(s.empty());
  const auto& p = s["pxpl5"];
  const auto& ring = s["modules"]["ring"];
  // Nodes: host, master, 16 casters, 4 compositors, 1 renderer (128 x 128), frame buffer.
  EXPECT_EQ(p["ring_nodes"], 1 + 1 + 16 + 4 + 1 + 1);
  EXPECT_EQ(p["regions_per_frame"], 4);  // 64 x 64 squares
  // Every sample crossed the ring three times (to a compositor, a renderer, the frame buffer):
  // 128 x 128 x (8 + 8 + 4) bytes plus headers and control.
  const double samples = 128.0 * 128.0;
  EXPECT_GE(ring["bytes.samples"].get<double>(), samples * 8);
  EXPECT_GE(ring["bytes.band"].get<double>(), samples * 8);
  EXPECT_GE(ring["bytes.pixels"].get<double>(), samples * 4);
  EXPECT_GT(ring["utilization"].get<double>(), 0.0);
  double regions = 0;
  for (int k = 0; k < 16; ++k)
    regions += s["modules"]["caster" + std::to_string(k)]["regions"].get<double>();
  EXPECT_EQ(regions, 4);
  EXPECT_GT(s["simulated_time_s"].get<double>(), 0.0);
  EXPECT_GT(p["frames_per_second"].get<double>(), 0.0);
}

// VOL2 is a pipelined renderer (L270): with two frames in flight the casters work on the next
// frame while the back end finishes this one. The images are the same; the frames come faster
// (here the renderers take 300 ms a frame, a third of the casters' time or so).
TEST(Pxpl5Pipeline, FramesInFlightOverlapTheStagesAndChangeNoImage) {
  const std::string base =
      "--scene builtin:default --width 160 --height 128 -p frames=5 -p camera.spin=4 "
      "-p update.fraction=50 -p renderer.tile_time=\"300 ms\"";
  const auto serial = run_pxpl5("serial", base + " -p pipeline.frames_in_flight=1");
  const auto piped = run_pxpl5("piped", base + " -p pipeline.frames_in_flight=2");
  const auto deep = run_pxpl5("deep", base + " -p pipeline.frames_in_flight=5");
  // The casters take the next frame's regions as soon as this frame's are all given out.
  const auto eager = run_pxpl5("eager", base + " -p master.next_frame=after_handing_out");
  ASSERT_FALSE(serial.empty() || piped.empty() || deep.empty() || eager.empty());
  const auto rate = [](const nlohmann::ordered_json& s) {
    return s["frame_sequence"]["steady_frames_per_second"].get<double>();
  };
  std::printf("steady frames/s: serialised %.4g, two in flight %.4g, five %.4g\n", rate(serial),
              rate(piped), rate(deep));
  EXPECT_GT(rate(piped), 1.2 * rate(serial));
  EXPECT_GE(rate(deep), rate(piped) * 0.999);
  EXPECT_NE(rate(eager), rate(piped));
  // Serialised, each frame starts when the host hears the one before was displayed.
  const auto& per = serial["frame_sequence"]["per_frame"];
  ASSERT_EQ(per.size(), 5u);
  for (std::size_t f = 1; f < per.size(); ++f) {
    EXPECT_GT(per[f]["start_s"].get<double>(), per[f - 1]["display_s"].get<double>());
    EXPECT_GE(per[f]["latency_s"].get<double>(), per[f]["interval_s"].get<double>() * 0.5);
  }
  // Two in flight: the second frame starts with the first.
  EXPECT_EQ(piped["frame_sequence"]["per_frame"][1]["start_s"].get<double>(), 0.0);
  for (const auto* s : {&piped, &deep, &eager}) {
    EXPECT_EQ(read_file(s->at("image_png").get<std::string>()),
              read_file(serial.at("image_png").get<std::string>()));
    EXPECT_EQ((*s)["rays"], serial["rays"]);
  }
}

// --latency-probe follows every sample from its caster to the display of its frame, through the
// compositor, the renderer of its pixel and the frame buffer: each sample's journey ends when its
// frame is displayed, so the mean end-to-end lies between the shortest and the longest frame
// latency, and a slower renderer shows in the renderers' share.
TEST(Pxpl5Raytrace, TheLatencyProbeFollowsEachSampleToTheDisplay) {
  const std::string base =
      "--scene builtin:default --width 160 --height 128 -p frames=3 -p camera.spin=3 "
      "--latency-probe";
  const auto fast = run_pxpl5("probe-fast", base);
  const auto slow = run_pxpl5("probe-slow", base + " -p renderer.tile_time=\"50 ms\"");
  ASSERT_FALSE(fast.empty() || slow.empty());
  const auto& p = fast["latency_probe"];
  EXPECT_EQ(p["unit"], "sample");
  // Every sample of every frame: 160 x 128 positions, three frames.
  EXPECT_EQ(p["rays"].get<double>(), 3.0 * 160 * 128);
  EXPECT_LT(std::abs(p["unattributed_s"].get<double>()), 1e-9);
  for (const char* stage :
       {"caster*", "ring", "compositor*.inbox", "compositor*", "renderer*", "frame_buffer"})
    EXPECT_TRUE(p["stages"].contains(stage)) << stage;
  double shortest = 1e9, longest = 0;
  for (const auto& f : fast["frame_sequence"]["per_frame"]) {
    shortest = std::min(shortest, f["latency_s"].get<double>());
    longest = std::max(longest, f["latency_s"].get<double>());
  }
  const double mean = p["end_to_end_s"]["mean"].get<double>();
  EXPECT_LE(mean, longest);
  EXPECT_GT(mean, 0.2 * shortest);  // a sample starts with its region, after its frame does
  const auto renderers = [](const nlohmann::ordered_json& s) {
    return s["latency_probe"]["stages"]["renderer*"]["service_s"].get<double>();
  };
  std::printf("per sample: end to end %.4g ms; renderer service %.4g ms, at 50 ms a tile %.4g ms\n",
              mean * 1e3, renderers(fast) * 1e3, renderers(slow) * 1e3);
  EXPECT_NEAR(renderers(slow), 0.050, 1e-9);  // every sample's tile took 50 ms
  EXPECT_NEAR(renderers(fast), 0.001, 1e-9);
}

double frame_s(const nlohmann::ordered_json& s) {
  return s.empty() ? 0.0 : s["pxpl5"]["frame_times_s"].back().get<double>();
}

// By-pass code (seed 004 L333-L350): with every node by-passed only messages remain, and the
// pipeline's rate does not depend on how many casters there are (Fig. 4, L344).
TEST(Pxpl5Bypass, AllBypassedTheRateIsIndependentOfTheCasters) {
  const std::string base = "--scene builtin:default --width 320 --height 256 -p bypass=all";
  std::vector<double> t;
  for (const int casters : {4, 16, 48}) {
    const auto s = run_pxpl5("bypass-all", base + " -p caster_count=" + std::to_string(casters));
    ASSERT_FALSE(s.empty());
    t.push_back(frame_s(s));
    std::printf("all by-passed, %2d casters: frame %.4g ms\n", casters, t.back() * 1e3);
  }
  for (const double x : t) EXPECT_NEAR(x, t[0], 0.1 * t[0]);
}

// All but the master GP by-passed: the frame rate rises with the casters until the master's
// rate caps it (Fig. 5, L347). Sample rows: 256 assignments a frame at 320 x 256.
TEST(Pxpl5Bypass, AllButTheMasterTheMasterCapsTheRate) {
  const std::string base =
      "--scene builtin:default --width 320 --height 256 "
      "-p bypass=all-but-master -p assign.scheme=rows";
  double previous = 0;
  double master = 0;
  for (const int casters : {1, 4, 16, 48}) {
    const auto s = run_pxpl5("bypass-master", base + " -p caster_count=" + std::to_string(casters));
    ASSERT_FALSE(s.empty());
    const double t = frame_s(s);
    master = s["modules"]["master"]["utilization"].get<double>();
    std::printf("all but the master by-passed, %2d casters: frame %.4g ms, master busy %.0f%%\n",
                casters, t * 1e3, 100 * master);
    if (previous > 0) {
      EXPECT_LT(t, previous * 1.001);
    }
    previous = t;
  }
  EXPECT_GT(master, 0.85);  // the master GP sets the pace
}

// With the casters and the master by-passed, the back end (compositing, resampling, display)
// depends on the image's resolution, not on the node count or the content (Fig. 6, L350).
TEST(Pxpl5Bypass, TheBackEndDependsOnResolutionOnly) {
  const std::string base = " -p bypass=casters-and-master";
  const auto small =
      run_pxpl5("be-small", "--scene builtin:default --width 320 --height 256" + base);
  const auto many = run_pxpl5(
      "be-many", "--scene builtin:default --width 320 --height 256 -p caster_count=40" + base);
  const auto other = run_pxpl5("be-content", "--scene " + shared_path("scenes/balls-s2.nff") +
                                                 " --width 320 --height 256" + base);
  const auto large =
      run_pxpl5("be-large", "--scene builtin:default --width 640 --height 512" + base);
  std::printf("back end: 320x256 %.4g ms (40 casters %.4g, balls-s2 %.4g), 640x512 %.4g ms\n",
              frame_s(small) * 1e3, frame_s(many) * 1e3, frame_s(other) * 1e3,
              frame_s(large) * 1e3);
  EXPECT_NEAR(frame_s(many), frame_s(small), 0.05 * frame_s(small));
  EXPECT_NEAR(frame_s(other), frame_s(small), 0.05 * frame_s(small));
  EXPECT_GT(frame_s(large), 2.0 * frame_s(small));  // four times the pixels
  // By-passed casters send samples of no radiance: a black image.
  EXPECT_EQ(small["hits"], 0);
}

TEST(Pxpl5Raytrace, AScenePastAGpsMemoryIsBadInput) {
  const fs::path dir = scratch_dir("pxpl5-big");
  const auto r = run_rtsim(
      "run --machine pxpl5-raytrace --scene builtin:default --width 8 "
      "--height 8 -p gp.memory=\"1 KiB\" -q --out " +
      dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("cannot be replicated"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "image.png"));
}

}  // namespace
