// Issue 11's defects, each reproduced first: crashes, hangs and dishonest exit statuses on input
// a hostile user can give. Each test names the defect it guards.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using rtsim::test::read_file;
using rtsim::test::run_rtsim;
using rtsim::test::run_shell;
using rtsim::test::scratch_dir;

// Defect 1: when threads cannot be created (here: too little address space for their stacks),
// the render aborted with "terminate called without an active exception". It now renders with
// the threads it could start, says so, and the image is the one a single thread renders.
TEST(BadInputRuns, ThreadsTheSystemRefusesDoNotAbortTheRender) {
  const fs::path dir = scratch_dir("threads");
  const std::string args = "render --scene builtin:default --width 16 --height 16 -q --out ";
  const auto one = run_rtsim(args + (dir / "one").string() + " --threads 1");
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const auto many = run_shell("ulimit -v 1500000; " + std::string(RTSIM_BINARY) + " " + args +
                              (dir / "many").string() + " --threads 256");
  std::cout << many.output;
  ASSERT_EQ(many.exit_code, 0) << many.output;
  EXPECT_NE(many.output.find("would start only"), std::string::npos) << many.output;
  EXPECT_EQ(read_file(dir / "one" / "image.exr"), read_file(dir / "many" / "image.exr"));
  // More than the cap is a usage error.
  const auto capped = run_rtsim(args + (dir / "cap").string() + " --threads 1024");
  EXPECT_EQ(capped.exit_code, 2) << capped.output;
  fs::remove_all(dir);
}

// Defect 3: gaudet-pert on a scene whose primitives are all degenerate exited 1 with "internal
// error: the twin's tracer is not a shell search". It is bad input for the PERT (its data sets
// would be empty): exit 2 with the reason and no output; vax-750 renders the empty scene.
TEST(BadInputRuns, AllDegenerateScenesAreRejectedByThePertWithTheReason) {
  const fs::path dir = scratch_dir("degenerate");
  fs::create_directories(dir);
  const std::string head =
      "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 8 8\n"
      "l 1 1 1\nf 1 0 0 1 0 0 0 0\n";
  const std::string bodies[] = {"s 0 0 0 1e-300\n",
                                "p 3\n0 0 0\n1 0 0\n2 0 0\np 4\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n"};
  int k = 0;
  for (const auto& body : bodies) {
    const fs::path scene = dir / ("degenerate" + std::to_string(k++) + ".nff");
    { std::ofstream(scene) << head << body; }
    for (const char* command : {"run", "render"}) {
      const fs::path out = dir / "out";
      const auto r = run_rtsim(std::string(command) + " --machine gaudet-pert --scene " +
                               scene.string() + " -q --out " + out.string());
      EXPECT_EQ(r.exit_code, 2) << command << " " << scene << "\n" << r.output;
      EXPECT_NE(r.output.find("no primitive of this scene survives"), std::string::npos)
          << r.output;
      EXPECT_FALSE(fs::exists(out)) << "no output for bad input";
    }
    const auto vax = run_rtsim("run --machine vax-750 --scene " + scene.string() + " -q --out " +
                               (dir / "vax").string());
    EXPECT_EQ(vax.exit_code, 0) << vax.output;
  }
  fs::remove_all(dir);
}

// Defect 6: config and sweep files had no guard against files that are not regular: /dev/zero
// grew to 4.3 GB and died with bad_alloc, a FIFO hung. They are refused before any read, as
// scene files are (exit 2). The FIFO is opened by nobody else: a read would block for ever, so
// `timeout` turns a regression into a failure instead of a hung suite.
TEST(BadInputRuns, ConfigAndSweepFilesMustBeRegularFiles) {
  const fs::path dir = scratch_dir("nonregular");
  fs::create_directories(dir);
  const fs::path fifo = dir / "fifo";
  ASSERT_EQ(run_shell("mkfifo " + fifo.string()).exit_code, 0);
  const std::string rtsim = "timeout 20 " + std::string(RTSIM_BINARY);
  for (const std::string& file : {std::string("/dev/zero"), fifo.string()}) {
    for (const std::string& args :
         {"list params --machine vax-750 --config " + file, "sweep " + file + " --list"}) {
      const auto r = run_shell(rtsim + " " + args);
      EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
      EXPECT_NE(r.output.find("not a regular file"), std::string::npos) << r.output;
    }
  }
  fs::remove_all(dir);
}

// Defect 7: one parameter set twice in a config file (a quoted dotted key, then a table) was
// accepted, the later value silently winning. Both lines are named, exit 2.
TEST(BadInputRuns, AParameterSetTwiceInAConfigFileIsRejected) {
  const fs::path dir = scratch_dir("duplicate");
  fs::create_directories(dir);
  const fs::path config = dir / "twice.toml";
  { std::ofstream(config) << "\"vax.ray_time\" = \"400 ns\"\n[vax]\nray_time = \"500 ns\"\n"; }
  const auto r = run_rtsim("list params --machine vax-750 --config " + config.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(config.string() + ":3"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("line 1"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

// Defect 4: grid limits the parameter check accepted, then "internal error", exit 1. The
// divisions' bounds are now the grid's real limit (512^3 = 2^27 subvolumes), and a scene whose
// subvolume references outgrow the grid's 32-bit offsets is bad input with what to change.
TEST(BadInputRuns, GridLimitsAreTheParametersBoundsAndTooBigAScene) {
  const fs::path dir = scratch_dir("grid-limits");
  fs::create_directories(dir);
  const auto over = run_rtsim(
      "render --scene builtin:default -p render.accel=grid "
      "-p render.grid.divisions=513 -q --out " +
      (dir / "a").string());
  EXPECT_EQ(over.exit_code, 2) << over.output;
  EXPECT_NE(over.output.find("from 0 to 512"), std::string::npos) << over.output;
  const auto periph = run_rtsim(
      "run --machine ullner-peripheral -p peripheral.grid.divisions=1024 "
      "-q --out " +
      (dir / "b").string());
  EXPECT_EQ(periph.exit_code, 2) << periph.output;
  // 60,000 identical spheres: every one in every subvolume of the grid chosen for 60,000.
  const fs::path scene = dir / "same-sphere.nff";
  {
    std::ofstream f(scene);
    f << "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 8 8\n"
         "l 1 1 1\nf 1 0 0 1 0 0 0 0\n";
    for (int i = 0; i < 60000; ++i) f << "s 0 0 0 1\n";
  }
  const auto big = run_rtsim("render --scene " + scene.string() +
                             " -p render.accel=grid -q --out " + (dir / "c").string());
  EXPECT_EQ(big.exit_code, 2) << big.output;
  EXPECT_NE(big.output.find("32-bit offsets"), std::string::npos) << big.output;
  EXPECT_FALSE(fs::exists(dir / "c"));
  fs::remove_all(dir);
}

// Defect 5: with out/stats.json a non-empty folder and an old image.png in out/, a render
// replaced image.png and image.exr, then failed on stats.json (exit 1): a half-written set.
// Every destination is checked before the first file moves; nothing is replaced, exit 2.
TEST(BadInputRuns, AnOutputSetThatCannotBeCompletedReplacesNothing) {
  const fs::path dir = scratch_dir("half-written");
  fs::create_directories(dir / "stats.json" / "inside");
  { std::ofstream(dir / "image.png") << "old"; }
  const auto r =
      run_rtsim("render --scene builtin:default --width 8 --height 8 -q --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("nothing was replaced"), std::string::npos) << r.output;
  EXPECT_EQ(read_file(dir / "image.png"), "old");
  EXPECT_FALSE(fs::exists(dir / "image.exr"));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().rfind(".rtsim-partial", 0), std::string::npos)
        << "the staging folder is removed";
  fs::remove_all(dir);
}

// Defect 10: output paths that cannot be used were "internal error", exit 1, found after the
// whole render. They are bad input, exit 2, found before any work: --out naming a file, the
// filesystem root, and sweep --out naming a file.
TEST(BadInputRuns, UnusableOutputPathsAreBadInputFoundFirst) {
  const fs::path dir = scratch_dir("out-paths");
  fs::create_directories(dir);
  const fs::path file = dir / "a-file";
  { std::ofstream(file) << "x"; }
  for (const std::string& args :
       {"render --scene builtin:default --width 8 --height 8 -q --out " + file.string(),
        "run --machine vax-750 --scene builtin:npp-412 --width 4 --height 4 -q --out " +
            file.string(),
        std::string("render --scene builtin:default --width 8 --height 8 -q --out /"),
        "sweep " + std::string(RTSIM_TEST_DATA_DIR) + "/../../configs/sweeps/fig2-18-grid.toml" +
            " -q --out " + file.string()}) {
    const auto r = run_rtsim(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
  }
  EXPECT_EQ(read_file(file), "x");
  // A folder with files rtsim did not write is not the run's to fill.
  const fs::path theirs = dir / "theirs";
  fs::create_directories(theirs);
  { std::ofstream(theirs / "notes.txt") << "mine"; }
  for (const std::string& command :
       {std::string("render --scene builtin:default --width 8 --height 8 -q"),
        std::string("sweep ") + RTSIM_TEST_DATA_DIR +
            "/../../configs/sweeps/fig2-18-grid.toml -q"}) {
    const auto r = run_rtsim(command + " --out " + theirs.string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("holds files rtsim did not write ('notes.txt')"), std::string::npos)
        << r.output;
  }
  EXPECT_EQ(read_file(theirs / "notes.txt"), "mine");
  EXPECT_EQ(std::distance(fs::directory_iterator(theirs), fs::directory_iterator()), 1);
  // A folder an earlier run filled is the run's: it is filled again.
  const fs::path again = dir / "again";
  for (int i = 0; i < 2; ++i) {
    const auto r =
        run_rtsim("render --scene builtin:default --width 8 --height 8 -q --out " + again.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
  }
  fs::remove_all(dir);
}

// Defect 5 (the rest): Ctrl-C or SIGTERM left the staging folder .rtsim-partial-PID behind, and
// the output folder the run had created. Both go; the process still ends by the signal.
TEST(BadInputRuns, AnInterruptedRunLeavesNoPartialOutputs) {
  const fs::path dir = scratch_dir("interrupt");
  fs::create_directories(dir);
  struct Case {
    std::string signal;
    std::string args;
    int status;
  };
  for (const Case& c :
       {Case{"INT", "render --scene builtin:npp-412 --width 512 --height 512 --spp 16 --threads 1",
             130},
        Case{"TERM", "run --machine gaudet-pert --scene builtin:npp-412 --width 256 --height 256",
             143}}) {
    const fs::path out = dir / ("out-" + c.signal);
    // Job control on (set -m), so the background job does not start with SIGINT ignored.
    const std::string script = "set -m; " + std::string(RTSIM_BINARY) + " " + c.args +
                               " -q --out " + out.string() +
                               " & pid=$!; for i in $(seq 600); do "
                               "ls -a " +
                               out.string() +
                               " 2>/dev/null | grep -q rtsim-partial && break; sleep 0.05; done; "
                               "kill -" +
                               c.signal + " $pid; wait $pid; echo \"status $?\"";
    const auto r = run_shell("bash -c '" + script + "'");
    EXPECT_NE(r.output.find("status " + std::to_string(c.status)), std::string::npos)
        << c.signal << "\n"
        << r.output;
    EXPECT_NE(r.output.find("rtsim: interrupted (" + c.signal + ")"), std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.signal << ": " << out;
  }
  fs::remove_all(dir);
}

// The minor ones: "no primitives" had no line; "+1 us" was rejected in parameters though scene
// files accept +1; builtin:ullner-random-0 said "unknown builtin scene" instead of the range.
TEST(BadInputRuns, MinorMessagesSayWhereAndWhat) {
  const fs::path dir = scratch_dir("minor");
  fs::create_directories(dir);
  const fs::path scene = dir / "empty.nff";
  {
    std::ofstream(scene) << "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\n"
                            "resolution 8 8\n";
  }
  const auto empty =
      run_rtsim("render --scene " + scene.string() + " -q --out " + (dir / "a").string());
  EXPECT_EQ(empty.exit_code, 2) << empty.output;
  EXPECT_NE(empty.output.find(scene.string() + ":7: no primitives"), std::string::npos)
      << empty.output;
  const auto plus = run_rtsim(
      "run --machine vax-750 --scene builtin:npp-412 --width 4 --height 4 "
      "-p \"vax.ray_time=+710 us\" -q --out " +
      (dir / "b").string());
  EXPECT_EQ(plus.exit_code, 0) << plus.output;
  const auto zero =
      run_rtsim("render --scene builtin:ullner-random-0 -q --out " + (dir / "c").string());
  EXPECT_EQ(zero.exit_code, 2) << zero.output;
  EXPECT_NE(zero.output.find("takes N from 4 to"), std::string::npos) << zero.output;
  fs::remove_all(dir);
}

// Defect 2: simulated time wrapped silently past 2^64 ps (213 days): vax-750 with
// vax.ray_time = 1e6 s reported 1.355e7 s instead of 3.2e7 s, exit 0. Time arithmetic now stops
// at the end of SystemC's time and the run exits 2 saying so, with no output; just below the
// end the frame time is exact.
TEST(BadInputRuns, SimulatedTimeNeverWraps) {
  const fs::path dir = scratch_dir("time-wrap");
  for (const std::string& args :
       {std::string("run --machine vax-750 --scene builtin:npp-412 --width 4 --height 4 "
                    "-p \"vax.ray_time=1e6 s\""),
        std::string("run --machine ullner-peripheral --scene builtin:ullner-cubes "
                    "-p \"host.clock=1 Hz\""),
        std::string("run --machine gaudet-pert --scene builtin:npp-412 --width 4 --height 4 "
                    "-p \"control.load_word_time=1e6 s\"")}) {
    const auto r = run_rtsim(args + " -q --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("2^64 ps"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "out"));
  }
  // 16 rays of 1e5 s + 16 x 768 objects x 429 us: 1,600,005.27 s, well inside the range.
  const auto ok = run_rtsim(
      "run --machine vax-750 --scene builtin:npp-412 --width 4 --height 4 "
      "-p \"vax.ray_time=1e5 s\" -q --out " +
      (dir / "ok").string());
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  const auto stats = rtsim::test::read_json(dir / "ok" / "stats.json");
  const double rays = stats["rays"]["total"].get<double>();
  EXPECT_NEAR(stats["simulated_time_s"].get<double>(), rays * (1e5 + 768 * 429e-6), 1e-3);
  fs::remove_all(dir);
}

// Defect 8: sweep range arithmetic. A step of 1e-300 said "-9223372036854775808 values" (a
// float-to-integer overflow); integer ranges near 2^63 were rounded through doubles and named
// values not in the file; a log range from 1e-308 to 1e308 computed inf. Now: the count is said as
// counted, integer ranges count and step in integers (exact to 2^63), and log ranges interpolate
// in logarithms.
TEST(BadInputRuns, SweepRangesCountWhatTheyCanRepresent) {
  const fs::path dir = scratch_dir("sweep-ranges");
  fs::create_directories(dir);
  // `rtsim sweep --list` of a sweep on vax-750 whose one axis is `axis` (from line 4 on).
  auto list_axis = [&](const std::string& axis) {
    const fs::path file = dir / "sweep.toml";
    {
      std::ofstream(file) << "machine = \"vax-750\"\nscene = \"builtin:npp-412\"\n[[axes]]\n"
                          << axis;
    }
    return run_shell("timeout 20 " + std::string(RTSIM_BINARY) + " sweep " + file.string() +
                     " --list");
  };
  auto list = [&](const std::string& param, const std::string& range) {
    return list_axis("param = \"" + param + "\"\nrange = " + range + "\n");
  };
  const auto tiny = list("shade.ambient", "{ start = 0.0, stop = 1.0, step = 1e-300 }");
  EXPECT_EQ(tiny.exit_code, 2) << tiny.output;
  EXPECT_NE(tiny.output.find("e+299 values, more than 100000"), std::string::npos) << tiny.output;
  const auto huge = list("scene.seed", "{ start = 0, stop = 9223372036854775807, step = 1 }");
  EXPECT_EQ(huge.exit_code, 2) << huge.output;
  EXPECT_NE(huge.output.find("has 9223372036854775808 values, more than 100000"), std::string::npos)
      << huge.output;
  // Near 2^63: exactly the values the range names, each once.
  const auto top =
      list("scene.seed", "{ start = 9223372036854775800, stop = 9223372036854775807, step = 3 }");
  EXPECT_EQ(top.exit_code, 0) << top.output;
  for (const char* v : {"9223372036854775800", "9223372036854775803", "9223372036854775806"})
    EXPECT_NE(top.output.find(v), std::string::npos) << v << "\n" << top.output;
  EXPECT_EQ(top.output.find("9223372036854775807"), std::string::npos) << top.output;
  EXPECT_EQ(top.output.find("9223372036854775808"), std::string::npos) << top.output;
  const auto spread =
      list("scene.seed", "{ start = 9223372036854775000, stop = 9223372036854775807, count = 4 }");
  EXPECT_EQ(spread.exit_code, 0) << spread.output;
  for (const char* v :
       {"9223372036854775000", "9223372036854775269", "9223372036854775538", "9223372036854775807"})
    EXPECT_NE(spread.output.find(v), std::string::npos) << v << "\n" << spread.output;
  // One value written two ways is one point: compared as values, not as texts.
  const auto twice =
      list_axis("param = \"vax.ray_time\"\nvalues = [\"1 us\", \"2 us\", \"1000 ns\"]\n");
  EXPECT_EQ(twice.exit_code, 2) << twice.output;
  EXPECT_NE(
      twice.output.find("sweep.toml:5: the axis of 'vax.ray_time' lists '1000 ns' and '1 us'"),
      std::string::npos)
      << twice.output;
  const auto wide =
      list("shade.ambient", "{ start = 1e-308, stop = 1e308, count = 3, scale = \"log\" }");
  EXPECT_EQ(wide.output.find("inf"), std::string::npos) << wide.output;
  EXPECT_NE(wide.output.find("1e+308"), std::string::npos) << wide.output;
  fs::remove_all(dir);
}

}  // namespace
