// pixelflow (platform/machines/pixelflow/): its image is the functional twin's byte for byte and
// comes from the records the composition network carries (a word corrupted in flight changes
// it); its time comes from its nodes' interaction (a slower rasterizer, a narrower network, fewer
// shaders move it through the model); a region costs what it holds; a scene without lights or
// without the alley's shader skips those passes.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tests/test_support.hpp"

namespace {

using rtsim::test::read_file;
using rtsim::test::run_machine;
using rtsim::test::run_rtsim;

const std::string kBowling = "--scene builtin:bowling --width 256 --height 192";

double pass_time(const nlohmann::ordered_json& s, const char* pass) {
  return s["pixelflow"]["passes"][pass]["time_s"].get<double>();
}

double frame_time(const nlohmann::ordered_json& s) { return s["simulated_time_s"].get<double>(); }

TEST(Pixelflow, TheImageIsTheTwinsWhateverTheSplitAndTiming) {
  const auto dir = rtsim::test::scratch_dir("pixelflow-render");
  const auto r =
      run_rtsim("render --machine pixelflow " + kBowling + " --spp 2 -q --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const std::string& p :
       {std::string(), std::string(" -p nodes.rasterizers=1 -p nodes.shaders=5"),
        std::string(" -p nodes.rasterizers=7 -p composition.link.bit_rate=\"10 Mbit/s\""),
        std::string(" -p shader.table.write_time=\"10 ms\" -p rasterizer.buffered_regions=1")}) {
    SCOPED_TRACE(p);
    const auto s = run_machine("pixelflow", "split", kBowling + " --spp 2" + p);
    ASSERT_FALSE(s.empty());
    EXPECT_EQ(read_file(s["image_png"].get<std::string>()), read_file(dir / "image.png"));
  }
}

TEST(Pixelflow, ACorruptedRecordOnTheCompositionNetworkChangesTheImage) {
  const auto clean = run_machine("pixelflow", "clean", kBowling);
  // Region-sample 3 (a region of pins), the depth word and shader id of a record near its
  // middle: 69,632 words a region-sample, record 4100 starts at byte 139,400.
  const std::string word = std::to_string(3 * 69632 + 139400 / 4 + 1);
  const auto bad =
      run_machine("pixelflow", "fault", kBowling + " --fault composition:" + word + ":0xffff00ff");
  ASSERT_FALSE(clean.empty() || bad.empty());
  EXPECT_NE(read_file(clean["image_png"].get<std::string>()),
            read_file(bad["image_png"].get<std::string>()));
  ASSERT_TRUE(bad["pixelflow"].contains("faults_in_flight"));
  EXPECT_TRUE(bad["pixelflow"]["faults_in_flight"][0]["applied"].get<bool>());
  // A word past the camera pass's records: exit 2, saying how many there are.
  const auto past =
      run_rtsim("run --machine pixelflow " + kBowling + " -q --fault composition:99999999999:1");
  EXPECT_EQ(past.exit_code, 2) << past.output;
  EXPECT_NE(past.output.find("words of records"), std::string::npos) << past.output;
  // A fault point the machine does not have: exit 2, naming the one it has.
  const auto r = run_rtsim("run --machine pixelflow " + kBowling + " -q --fault compositor:0:1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("composition"), std::string::npos) << r.output;
}

TEST(Pixelflow, ItsTimeComesFromItsNodesInteraction) {
  const auto base = run_machine("pixelflow", "base", kBowling);
  const auto slow_raster =
      run_machine("pixelflow", "slow-raster", kBowling + " -p rasterizer.triangle_time=\"5 us\"");
  const auto narrow =
      run_machine("pixelflow", "narrow", kBowling + " -p composition.link.bit_rate=\"20 Mbit/s\"");
  const auto few = run_machine("pixelflow", "few", kBowling + " -p nodes.shaders=1");
  ASSERT_FALSE(base.empty() || slow_raster.empty() || narrow.empty() || few.empty());
  // The frame: a slower pass ahead of the camera's lets the camera's overlap it more, so the
  // camera pass alone can shrink while the frame grows.
  const double t = frame_time(base);
  std::printf("frame: %.3f ms; slow rasterizers %.3f, narrow network %.3f, one shader %.3f\n",
              1e3 * t, 1e3 * frame_time(slow_raster), 1e3 * frame_time(narrow),
              1e3 * frame_time(few));
  EXPECT_GT(frame_time(slow_raster), 1.05 * t);
  EXPECT_GT(frame_time(narrow), 1.05 * t);
  EXPECT_GT(frame_time(few), 1.05 * t);
  EXPECT_GT(pass_time(slow_raster, "camera") + pass_time(slow_raster, "reflection"),
            pass_time(base, "camera") + pass_time(base, "reflection"));
  // The map passes are their table writes (8 of 760 us each, seed 004 L126), whatever the nodes.
  for (const auto* s : {&base, &few}) {
    EXPECT_GE(pass_time(*s, "shadow0"), 8 * 760e-6 * 0.999);
    EXPECT_LT(pass_time(*s, "shadow0"), 7e-3);
  }
}

TEST(Pixelflow, InstructionCountedShadingTakesFig6sTimesAndLeavesTheImage) {
  const std::string counted = kBowling + " -p shader.cost.model=instructions";
  const auto parts = run_machine("pixelflow", "parts", kBowling);
  const auto parts_slow =
      run_machine("pixelflow", "parts-slow", kBowling + " -p shader.simd.mul_short=\"1 us\"");
  const auto instructions = run_machine("pixelflow", "instructions", counted);
  const auto slow =
      run_machine("pixelflow", "instr-slow", counted + " -p shader.simd.mul_short=\"1 us\"");
  ASSERT_FALSE(parts.empty() || parts_slow.empty() || instructions.empty() || slow.empty());
  const auto shading = [](const nlohmann::ordered_json& s) {
    return s["pixelflow"]["passes"]["camera"]["shade_s"].get<double>();
  };
  const auto light = [](const nlohmann::ordered_json& s) {
    return s["pixelflow"]["shading_programs"]["light"]["time_s"].get<double>();
  };
  std::printf("camera shading: parts %.3f ms, instructions %.3f ms, slower shorts %.3f ms\n",
              1e3 * shading(parts), 1e3 * shading(instructions), 1e3 * shading(slow));
  // The instruction model times the nodes: a slower short multiply slows the shading.
  EXPECT_NE(shading(instructions), shading(parts));
  EXPECT_GT(shading(slow), 1.05 * shading(instructions));
  EXPECT_GT(light(slow), light(instructions));
  // Fig. 9's parts time them by default: Fig. 6 moves only the programs' report.
  EXPECT_EQ(shading(parts_slow), shading(parts));
  EXPECT_GT(light(parts_slow), light(parts));
  // The image is the shading code's, whichever model times it.
  EXPECT_EQ(read_file(instructions["image_png"].get<std::string>()),
            read_file(parts["image_png"].get<std::string>()));
  // The costliest shading holds all three functions (seed 004 L150-L152).
  const auto& w = instructions["pixelflow"]["worst_shading"];
  for (const char* f : {"pin", "alley", "ball"}) EXPECT_GT(w["pixels"][f].get<int>(), 0) << f;
  EXPECT_GT(w["instructions"].get<int>(), 0);
  // A model it does not have: exit 2, naming the ones it has.
  const auto bad =
      run_rtsim("run --machine pixelflow " + kBowling + " -q -p shader.cost.model=simd");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("instructions"), std::string::npos) << bad.output;
}

TEST(Pixelflow, ARegionCostsWhatItHolds) {
  // The same frame's worst region-sample holds all three shading functions (seed 004 L150-L152).
  const auto s = run_machine("pixelflow", "worst", kBowling);
  ASSERT_FALSE(s.empty());
  const auto& w = s["pixelflow"]["worst_region"];
  EXPECT_GT(w["pixels"]["pin"].get<int>(), 0);
  EXPECT_LE(w["time_s"].get<double>(), 910e-6 * 1.0001);
  EXPECT_GT(w["lookup_pixels"]["label"].get<int>(), 0);
  // A frame of background: one triangle far outside the view. Nothing is set up or shaded.
  const auto dir = rtsim::test::scratch_dir("pixelflow-empty-scene");
  std::filesystem::create_directories(dir);
  const auto nff = dir / "empty.nff";
  {
    std::ofstream f(nff);
    f << "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 256 192\n"
         "b 0.2 0.3 0.4\nl 0 0 10\nf 1 1 1 1 0 0 0 1\np 3\n100 100 0\n101 100 0\n100 101 0\n";
  }
  const auto empty = run_machine("pixelflow", "empty", "--scene " + nff.string());
  ASSERT_FALSE(empty.empty());
  const auto& cam = empty["pixelflow"]["passes"]["camera"];
  EXPECT_EQ(cam["triangles_set_up"].get<int>(), 0);
  EXPECT_EQ(cam["shade_s"].get<double>(), 0.0);
  EXPECT_EQ(empty["hits"].get<int>(), 0);
}

TEST(Pixelflow, AScenePaysOnlyForThePassesItNeeds) {
  // builtin:default: two lights, no alley: two shadow maps, no reflection map.
  const auto d =
      run_machine("pixelflow", "default", "--scene builtin:default --width 64 --height 64");
  ASSERT_FALSE(d.empty());
  const auto& p = d["pixelflow"]["passes"];
  EXPECT_TRUE(p.contains("shadow0") && p.contains("shadow1") && p.contains("camera"));
  EXPECT_FALSE(p.contains("reflection"));
  // No light: the camera pass only, and no shadow test.
  const auto dark =
      run_machine("pixelflow", "dark", "--scene builtin:ullner-sheets-100 --width 64 --height 64");
  ASSERT_FALSE(dark.empty());
  EXPECT_EQ(dark["pixelflow"]["passes"].size(), 1u);
  EXPECT_EQ(dark["rays"]["shadow"].get<int>(), 0);
  // NFF spheres, cones and patches are tessellated: the teapot's patches render.
  const auto teapot = run_machine("pixelflow", "patches",
                                  "--scene builtin:spd-teapot-patches "
                                  "--width 64 --height 64");
  ASSERT_FALSE(teapot.empty());
  EXPECT_GT(teapot["pixelflow"]["triangles"].get<int>(), 4000);
}

TEST(Pixelflow, SamplingIsRefusedBeforeAnythingRuns) {
  const auto dir = rtsim::test::scratch_dir("pixelflow-sample");
  std::filesystem::remove_all(dir);
  const auto r = run_rtsim("run --machine pixelflow " + kBowling + " --sample-error 1% -q --out " +
                           dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("does not sample"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir));
}

}  // namespace
