// End-to-end tests of `rtsim run` (the SystemC machines): outputs and keys, the image equal
// to the machine's functional twin, agreement with the plain functional renderer, quantum
// independence of the image, bad input. A machine's own keys are its test's.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "platform/machine_registry.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::test::compare_images;
using rtsim::test::read_file;
using rtsim::test::read_json;
using rtsim::test::run_ok;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;
using rtsim::test::shared_path;

TEST(RunCli, ImageEqualsTheMachinesFunctionalTwinByteForByte) {
  struct Case {
    const char* tag;
    std::string machine_args;
  };
  const std::vector<Case> cases = {
      {"brute", "--machine ullner-peripheral --scene builtin:ullner-cubes"},
      {"grid",
       "--machine ullner-peripheral --scene builtin:ullner-cubes "
       "-p peripheral.grid.divisions=6"},
      {"printed",
       "--machine ullner-peripheral --scene builtin:ullner-cubes "
       "-p peripheral.grid.divisions=6 -p peripheral.grid.dda=as-printed"},
      {"tetra", "--machine ullner-peripheral --scene " + shared_path("scenes/tetra-s3.nff")},
      {"vax", "--machine vax-750 --scene " + shared_path("scenes/balls-s1.nff")},
  };
  for (const auto& c : cases) {
    const std::string size = " --width 48 --height 40 --aov id ";
    const auto run = run_ok(std::string("twin-run-") + c.tag, "run " + c.machine_args + size);
    const auto render =
        run_ok(std::string("twin-render-") + c.tag, "render " + c.machine_args + size);
    EXPECT_EQ(read_file(run / "image.png"), read_file(render / "image.png")) << c.tag;
    EXPECT_EQ(read_file(run / "image.exr"), read_file(render / "image.exr")) << c.tag;
    EXPECT_EQ(read_file(run / "id.exr"), read_file(render / "id.exr")) << c.tag;
  }
}

TEST(RunCli, MachinesAgreeWithThePlainFunctionalRenderer) {
  // Ullner's quads versus the renderer's triangles, and the grid versus the shell hierarchy:
  // different kernels and searches, the same picture. Tolerance: pixels over 2/255 at most
  // 0.5% (rays through polygon edges may be decided differently by the two kernels).
  for (const std::string& scene :
       {std::string("builtin:ullner-cubes"), shared_path("scenes/tetra-s3.nff")}) {
    const std::string size = " --width 64 --height 64 --scene " + scene;
    const auto run = run_ok("agree-run", "run --machine ullner-peripheral" + size);
    const auto plain = run_ok("agree-plain", "render" + size);
    const auto cr =
        compare_images((run / "image.png").string(), (plain / "image.png").string(), 2.0f / 255.0f);
    std::cout << scene << ": peripheral vs functional: " << cr.nfail
              << " of 4096 pixels over 2/255, max error " << cr.maxerror << "\n";
    EXPECT_LE(cr.nfail, 20u);
  }
}

TEST(RunCli, ImageDoesNotDependOnTheQuantumAndRunsAreDeterministic) {
  const std::string base =
      "run --machine ullner-peripheral --scene builtin:ullner-cubes --width 32 --height 32 "
      "-p peripheral.grid.divisions=5";
  const auto a = run_ok("quantum-0a", base + " --quantum 0");
  const auto b = run_ok("quantum-0b", base + " --quantum 0");
  const auto c = run_ok("quantum-1ms", base + " --quantum \"1 ms\"");
  EXPECT_EQ(read_file(a / "image.png"), read_file(b / "image.png"));
  EXPECT_EQ(read_file(a / "image.exr"), read_file(c / "image.exr"));
  auto sa = read_json(a / "stats.json");
  auto sb = read_json(b / "stats.json");
  EXPECT_EQ(sa["simulated_time_s"], sb["simulated_time_s"]);
  EXPECT_EQ(sa["modules"], sb["modules"]);
  EXPECT_EQ(sa["ray_latency_s"], sb["ray_latency_s"]);
}

TEST(RunCli, BadMachineSceneOrQuantumIsBadInputAndWritesNothing) {
  const auto dir = scratch_dir("run-bad");
  // A machine's name with its first letter dropped: the message suggests the name.
  const std::string name = rtsim::platform::default_machine().name();
  auto r = run_rtsim("run --machine " + name.substr(1) + " --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(name), std::string::npos) << r.output;
  r = run_rtsim("run --machine ullner-peripheral --scene " + shared_path("scenes/balls-s1.nff") +
                " --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("polygons only"), std::string::npos) << r.output;
  r = run_rtsim("run --quantum 5 --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = run_rtsim("run -p peripheral.adder_stages=2 --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;  // 1 or 3 only
  EXPECT_FALSE(fs::exists(dir));
}

TEST(RunCli, ListsMachinesAndTheirParameters) {
  auto r = run_rtsim("list machines");
  EXPECT_EQ(r.exit_code, 0);
  // Every machine the program registers (as JSON, the same registry).
  const auto all = rtsim::test::registered_machines();
  EXPECT_GE(all.size(), 7u);
  for (const auto& m : all) EXPECT_NE(r.output.find(m.name), std::string::npos) << m.name;
  r = run_rtsim("list params --machine ullner-peripheral");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* name :
       {"peripheral.intersect_interval", "peripheral.adder_stages", "peripheral.grid.divisions",
        "peripheral.grid.dda", "peripheral.grid.step_time", "host.clock", "quantum"})
    EXPECT_NE(r.output.find(name), std::string::npos) << name;
  EXPECT_NE(r.output.find("333.333 ns"), std::string::npos);
  EXPECT_NE(r.output.find("Ullner 1983, line 654"), std::string::npos);  // seed 000 L654
}

TEST(RunCli, TracesOpenAsPerfettoJsonAndVcd) {
  const auto dir = run_ok("traces",
                          "run --machine ullner-peripheral --scene builtin:ullner-cubes "
                          "--width 24 --height 24 -p peripheral.grid.divisions=4 "
                          "--trace vcd,perfetto");
  ASSERT_TRUE(fs::exists(dir / "trace.json"));
  ASSERT_TRUE(fs::exists(dir / "trace.vcd"));
  const auto trace = read_json(dir / "trace.json");
  std::map<std::string, int> threads;  // tid -> track name
  std::map<std::string, int> slices;   // track name -> slices
  std::map<int, std::string> names;
  for (const auto& e : trace["traceEvents"])
    if (e["ph"] == "M" && e["name"] == "thread_name")
      names[e["tid"].get<int>()] = e["args"]["name"].get<std::string>();
  for (const auto& e : trace["traceEvents"]) {
    if (e["ph"] != "X") continue;
    EXPECT_GE(e["dur"].get<double>(), 0.0);
    slices[names[e["tid"].get<int>()]]++;
  }
  for (const char* track : {"host", "peripheral.pipeline", "peripheral.aux"})
    EXPECT_GT(slices[track], 0) << track;
  const std::string vcd = read_file(dir / "trace.vcd");
  EXPECT_NE(vcd.find("$var wire 1"), std::string::npos);
  // stats.json's module names as scopes: the host's busy flag, the peripheral's ray queue.
  EXPECT_NE(vcd.find("$scope module host $end\n$var wire 1 ! busy $end"), std::string::npos);
  EXPECT_NE(vcd.find("$scope module ray_queue $end\n$var integer 32"), std::string::npos);
  EXPECT_NE(vcd.find("$enddefinitions"), std::string::npos);
}

TEST(RunCli, ListParamsFiltersByPatternAndChangedAndSuggestsNames) {
  // A shell pattern whose '*' also matches dots.
  auto r = run_rtsim("list params --machine gaudet-pert 'pert.shell.*'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("pert.shell.rays_in_flight"), std::string::npos);
  EXPECT_EQ(r.output.find("pert.prim."), std::string::npos);
  EXPECT_EQ(r.output.find("pert_count"), std::string::npos);
  // --changed: only what differs from the default, with where it was set.
  r = run_rtsim("list params --machine gaudet-pert --changed -p pert_count=8");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("pert_count  8      -p"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("broadcast."), std::string::npos);
  r = run_rtsim("list params --machine gaudet-pert --changed");
  EXPECT_NE(r.output.find("every parameter is at its default"), std::string::npos) << r.output;
  // Near misses: the machine, the subcommand's word, a pattern nothing matches.
  r = run_rtsim("list params --machine gaudet");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("did you mean 'gaudet-pert'?"), std::string::npos) << r.output;
  r = run_rtsim("list param");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("did you mean 'params'?"), std::string::npos) << r.output;
  r = run_rtsim("list params --machine ullner-peripheral 'peripheral.grid.divison'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("did you mean 'peripheral.grid.divisions'?"), std::string::npos)
      << r.output;
  // A pattern with a mistyped part: the part corrected, the wildcard kept.
  r = run_rtsim("list params --machine ullner-array 'arry.*'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("did you mean 'array.*'?"), std::string::npos) << r.output;
  r = run_rtsim("list params --machine gaudet-pert 'pert.shel.*'");
  EXPECT_NE(r.output.find("did you mean 'pert.shell.*'?"), std::string::npos) << r.output;
}

TEST(RunCli, ListsAsJson) {
  const auto scenes = run_rtsim("list scenes --format json");
  ASSERT_EQ(scenes.exit_code, 0) << scenes.output;
  const auto s = nlohmann::json::parse(scenes.output);
  ASSERT_TRUE(s.is_array());
  EXPECT_TRUE(std::any_of(s.begin(), s.end(), [](const nlohmann::json& e) {
    return e["scene"] == "builtin:ullner-cubes" && !e["description"].get<std::string>().empty();
  }));
  const auto params = run_rtsim("list params --machine gaudet-pert --format json");
  ASSERT_EQ(params.exit_code, 0) << params.output;
  const auto p = nlohmann::json::parse(params.output);
  std::size_t image = 0;
  for (const auto& e : p) image += e["affects_image"].get<bool>() ? 1 : 0;
  EXPECT_GT(image, 0u);
  EXPECT_LT(image, p.size());
  const auto machines = run_rtsim("list machines --format json");
  ASSERT_EQ(machines.exit_code, 0) << machines.output;
  EXPECT_TRUE(nlohmann::json::parse(machines.output).is_array());
}

TEST(RunCli, ConfigExamplesHoldEachMachinesPresetValues) {
  // configs/examples/MACHINE.toml: a commented copy of the preset's main knobs, so a run with it
  // is the default run (render.toml: the functional renderer's).
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(fs::path(RTSIM_SOURCE_DIR) / "configs/examples")) {
    if (e.path().extension() != ".toml") continue;
    ++files;
    const std::string stem = e.path().stem().string();
    const std::string machine = stem == "render" ? "" : " --machine " + stem;
    const auto set = run_rtsim("list params" + machine + " --config " + e.path().string());
    ASSERT_EQ(set.exit_code, 0) << e.path() << "\n" << set.output;
    EXPECT_NE(set.output.find(e.path().filename().string() + ":"), std::string::npos)
        << e.path() << " sets nothing";
    const auto changed =
        run_rtsim("list params" + machine + " --changed --config " + e.path().string());
    EXPECT_NE(changed.output.find("every parameter is at its default"), std::string::npos)
        << e.path() << " changes a preset value:\n"
        << changed.output;
  }
  EXPECT_EQ(files, 12u);  // one a machine, and the functional renderer's
}

TEST(RunCli, RunSppIsRenderSpp) {
  const auto dir =
      run_ok("run-spp", "run --machine ullner-peripheral --width 16 --height 16 --spp 2");
  const auto stats = read_json(dir / "stats.json");
  EXPECT_EQ(stats["spp"], 2);
  EXPECT_EQ(stats["params"]["render.spp"], "2");
}

TEST(RunCli, ARunIntoAFolderRemovesTheEarlierRunsOutputsItDoesNotWrite) {
  const auto dir = run_ok("rerun", "run --width 16 --height 16 --trace perfetto");
  ASSERT_TRUE(fs::exists(dir / "trace.json"));
  const auto r = run_rtsim("run --width 16 --height 16 -q --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(dir / "trace.json")) << "a trace of the earlier run beside this one's";
  EXPECT_TRUE(fs::exists(dir / "stats.json"));
}
