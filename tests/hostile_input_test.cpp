// A hostile user's inputs over every subcommand and every machine, as one table
// (tests/hostile_table.hpp): the arguments (passed without a shell), the exit statuses allowed
// (0: it ran; 2: refused as bad input; never 1, a signal or a hang) and what must or must not be
// on disk afterwards. Issue 30's defects are rows here, each marked with its item; a machine's
// own rows (its parameters, its memories) are in its test file; the cases that need several steps
// (a sweep resumed, an output set that cannot be committed) are tests of their own below the
// table. Rows that need "a machine" take the registry's first, so none is named here.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <sstream>
#include <string>
#include <vector>

#include "tests/child_processes.hpp"
#include "tests/hostile_table.hpp"
#include "tests/limited_run.hpp"
#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using rtsim::test::absent;
using rtsim::test::hostile_run;
using rtsim::test::HostileCase;
using rtsim::test::LimitedRun;
using rtsim::test::present;
using rtsim::test::run_limited;
using rtsim::test::says;

constexpr double kTimeoutS = 60.0;

/// The machine the rows that need one use, and a scene it holds: the first registered machine
/// and the scene of its small run.
struct AnyMachine {
  std::string name, scene;
};
const AnyMachine& any_machine() {
  static const AnyMachine any = [] {
    const auto all = rtsim::test::registered_machines();
    EXPECT_FALSE(all.empty());
    const std::string& run = all.front().small_run();  // "--scene SCENE ..."
    const std::size_t begin = run.find("--scene ") + 8;
    return AnyMachine{all.front().name, run.substr(begin, run.find(' ', begin) - begin)};
  }();
  return any;
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

/// The parts one after the other (appends: `"literal" + std::string&&` trips GCC 12's
/// -Wrestrict, bug 105651).
std::string join(std::initializer_list<std::string> parts) {
  std::string out;
  for (const auto& p : parts) out += p;
  return out;
}

std::string repeat(const std::string& s, std::size_t n) {
  std::string out;
  out.reserve(s.size() * n);
  for (std::size_t i = 0; i < n; ++i) out += s;
  return out;
}

const std::string kViewHead =
    "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 8 8\n"
    "l 1 1 5\nf 1 0 0 1 0 0 0 0\n";

/// A {101/50} star: one polygon whose every edge crosses others.
std::string star_scene() {
  std::string s = kViewHead + "p 101\n";
  for (int i = 0; i < 101; ++i) {
    const double a = 2 * M_PI * static_cast<double>(i * 50 % 101) / 101.0;
    char line[64];
    std::snprintf(line, sizeof line, "%.9f %.9f 0\n", std::cos(a), std::sin(a));
    s += line;
  }
  return s;
}

/// Every file a case may use, written once into the test's folder.
void write_inputs(const fs::path& d) {
  write(d / "star.nff", star_scene());
  write(d / "degenerate.nff",
        kViewHead + "s 0 0 0 0\np 3\n0 0 0\n1 0 0\n2 0 0\np 4\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n");
  write(d / "upper.nff", "V\nfrom 0 0 5\n");
  write(d / "deep-key.toml", join({repeat("a.", 31249), "a = 1\n"}));
  write(d / "deep-header.toml", join({"[", repeat("a.", 99), "a]\nx = 1\n"}));
  write(d / "deep-array.toml", join({"a = ", repeat("[", 300), repeat("]", 300), "\n"}));
  write(d / "deep-inline.toml",
        join({"a = ", repeat("{b.c.d = ", 40), "1", repeat("}", 40), "\n"}));
  const std::string sweep_head =
      join({"name = \"h\"\nmachine = \"", any_machine().name, "\"\nscene = \"", any_machine().scene,
            "\"\nwidth = 8\nheight = 8\n"});
  write(d / "sweep-deep.toml", join({sweep_head, "[params]\n", repeat("a.", 40000), "a = 1\n"}));
  write(d / "sweep-dblmax.toml",
        join({sweep_head, "[[axes]]\nparam = \"shade.contribution_threshold\"\n",
              "range = { start = -1.7e308, stop = 1.7e308, count = 5 }\n"}));
  write(d / "sweep-count1.toml", join({sweep_head, "[[axes]]\nparam = \"shade.max_depth\"\n",
                                       "range = { start = 1, stop = 4, count = 1 }\n"}));
  write(d / "sweep-devzero.toml", sweep_head + "configs = [\"/dev/zero\"]\n");
  write(d / "deep.json", join({repeat("{\"a\":", 50000), "1", repeat("}", 50000)}));
  write(d / "array.json", "[]");
  write(d / "number.json", "5");
  write(d / "string.json", "\"x\"");
  write(d / "width.json", "{\"width\":\"abc\"}");
  write(d / "huge.json", "1e400");
  write(d / "a-file", "not a folder\n");
}

std::vector<HostileCase> cases() {
  std::vector<HostileCase> c;
  const auto run = [](const std::string& machine, const std::string& scene,
                      const std::vector<std::string>& more = {}) {
    return hostile_run(machine, scene, more);
  };
  const std::string any = any_machine().name, any_scene = any_machine().scene;
  // Item 1: describe's --out reaches no shell; odd and bad folders.
  c.push_back({"describe: a path with a quote and a command",
               {"describe", any, "--out", "o/x';touch PWNED;'"},
               {0},
               [any](const fs::path& d, const LimitedRun&) {
                 const std::string e = absent(d / "PWNED");
                 return e.empty() ? present(d / "o/x';touch PWNED;'" / (any + ".dot")) : e;
               }});
  c.push_back({"describe: a folder with an apostrophe",
               {"describe", any, "--out", "John's diagrams"},
               {0},
               [any](const fs::path& d, const LimitedRun&) {
                 return present(d / "John's diagrams" / (any + ".svg"));
               }});
  for (const char* out : {"/", "/proc/rtsim-no-such", "/dev/null", "a-file"})
    c.push_back({std::string("describe --out ") + out, {"describe", any, "--out", out}, {2}});
  // Items 2 and 5 (a machine's corrupted words, memories at their bounds) are its own test's rows.
  // Item 3: TOML nested without bound.
  for (const char* f : {"deep-key.toml", "deep-header.toml", "deep-array.toml", "deep-inline.toml"})
    c.push_back(
        {std::string("config ") + f, {"list", "params", "--machine", any, "--config", f}, {2}});
  c.push_back({"sweep file with a deep key", {"sweep", "sweep-deep.toml", "--list"}, {2}});
  // Item 4: JSON that is no stats.json.
  for (const char* f :
       {"deep.json", "array.json", "number.json", "string.json", "width.json", "huge.json"})
    c.push_back({std::string("diff of ") + f, {"diff", f, f}, {2}});
  c.push_back(
      {"diff --tolerance nan", {"diff", "array.json", "array.json", "--tolerance", "nan"}, {2}});
  // Item 6: a self-crossing polygon, one rule everywhere.
  c.push_back({"render a self-crossing star",
               {"render", "--scene", "star.nff", "-q", "--out", "out/render-star"},
               {0},
               [](const fs::path& d, const LimitedRun&) {
                 const auto s = rtsim::test::read_json(d / "out/render-star/stats.json");
                 return s["geometry"]["rejected"] == 1 ? "" : "the star was not rejected";
               }});
  const auto all_machines = rtsim::test::kit_machines();
  EXPECT_GE(all_machines.size(), 7u);
  for (const auto& machine : all_machines) {
    const std::string& m = machine.name;
    c.push_back({m + " on a self-crossing star", run(m, "star.nff"), {0, 2}});
    // Item 8: every machine on a scene where nothing survives.
    c.push_back({m + " on an all-degenerate scene", run(m, "degenerate.nff"), {0, 2}});
  }
  // Item 7: duplicate trace formats are one file each.
  c.push_back({"--trace vcd,vcd",
               run(any, any_scene, {"--trace", "vcd,vcd"}),
               {0},
               [any](const fs::path& d, const LimitedRun&) {
                 return present(d / "out" / any / "trace.vcd");
               }});
  c.push_back({"--trace perfetto,perfetto",
               run(any, any_scene, {"--trace", "perfetto,perfetto"}),
               {0},
               [any](const fs::path& d, const LimitedRun&) {
                 return present(d / "out" / any / "trace.json");
               }});
  // Items 8 and 9 on times that overflow outside the simulation are the machines' own rows (and
  // every parameter at its bounds is ParamBounds' test).
  // The threshold's bounds refuse the points; the message must name them as the file does.
  c.push_back({"sweep range near DBL_MAX",
               {"sweep", "sweep-dblmax.toml", "--list"},
               {2},
               [](const fs::path&, const LimitedRun& r) {
                 return r.output.find("nan") == std::string::npos &&
                                r.output.find("inf") == std::string::npos
                            ? says(r, "1.7e+308")
                            : "a point is not a number the file names";
               }});
  c.push_back({"sweep count = 1 between two values",
               {"sweep", "sweep-count1.toml", "--list"},
               {2},
               [](const fs::path&, const LimitedRun& r) { return says(r, "start alone"); }});
  c.push_back({"sweep configs = /dev/zero",
               {"sweep", "sweep-devzero.toml", "--list"},
               {2},
               [](const fs::path&, const LimitedRun& r) { return says(r, "not a regular file"); }});
  c.push_back({"NFF keywords in capitals are refused",
               {"render", "--scene", "upper.nff", "-q", "--out", "out/upper"},
               {2}});
  // The rest of the surface: names, numbers and paths a user mistypes.
  c.push_back({"no such subcommand", {"rnu"}, {2}});
  c.push_back({"no such machine",
               run(any + "x", "builtin:default"),
               {2},
               [any](const fs::path&, const LimitedRun& r) { return says(r, any); }});
  c.push_back({"no such parameter", run(any, any_scene, {"-p", "rendr.spp=2"}), {2}});
  c.push_back({"--width 0", run(any, any_scene, {"--width", "0"}), {2}});
  c.push_back({"--quantum nan", run(any, any_scene, {"--quantum", "nan s"}), {2}});
  c.push_back({"--sample 1", run(any, any_scene, {"--sample", "1"}), {2}});
  c.push_back({"--scene that is a folder", run(any, "."), {2}});
  c.push_back({"--scene /dev/zero", run(any, "/dev/zero"), {2}});
  c.push_back(
      {"--out an existing file", {"render", "--scene", "builtin:default", "--out", "a-file"}, {2}});
  c.push_back({"validate an unknown figure", {"validate", "--only", "Z99", "--list"}, {2}});
  c.push_back({"list params of an unknown machine", {"list", "params", "--machine", "x"}, {2}});
  return c;
}

TEST(HostileInput, EveryRowExitsAsAllowedWithinItsMemory) {
  rtsim::test::run_hostile_table(rtsim::test::scratch_dir("hostile"), cases(), write_inputs,
                                 kTimeoutS);
}

// Item 4: a resumed sweep takes a point's stats.json only if it is one rtsim could have written;
// anything else (a list, a JSON 50,000 levels deep) sends the point to run again.
TEST(HostileInput, AResumedSweepRunsAgainAPointWhoseStatsAreNotStats) {
  const fs::path dir = rtsim::test::scratch_dir("hostile-resume");
  fs::remove_all(dir);
  write(
      dir / "s.toml",
      join({"name = \"r\"\nmachine = \"", any_machine().name, "\"\nscene = \"", any_machine().scene,
            "\"\nwidth = 8\nheight = 8\n[[axes]]\nparam = \"render.spp\"\nvalues = [1]\n"}));
  const std::vector<std::string> sweep = {"sweep", "s.toml", "--out", "sw", "--jobs", "1", "-q"};
  ASSERT_EQ(run_limited(sweep, dir, kTimeoutS).exit_code, 0);
  fs::path stats;
  for (const auto& e : fs::recursive_directory_iterator(dir / "sw" / "points"))
    if (e.path().filename() == "stats.json") stats = e.path();
  ASSERT_FALSE(stats.empty());
  for (const std::string& bad :
       {std::string("[1,2,3]"), join({repeat("[", 50000), repeat("]", 50000)})}) {
    write(stats, bad);
    const LimitedRun r = run_limited(sweep, dir, kTimeoutS);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    // Run again: the file is a stats.json once more.
    EXPECT_EQ(rtsim::test::read_json(stats)["command"], "run");
  }
  fs::remove_all(dir);
}

// Item 7: an output set that cannot be put in place replaces nothing. An immutable stats.json
// (chattr +i: not even root may rename it) stops the second render; the first one's files stay
// as they were and nothing of the second is left.
TEST(HostileInput, AnOutputSetThatCannotBeCommittedReplacesNothing) {
  const fs::path dir = rtsim::test::scratch_dir("hostile-commit");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto render = [&](const char* width) {
    return run_limited({"render", "--scene", "builtin:default", "--width", width, "--height", "8",
                        "-q", "--out", "out"},
                       dir, kTimeoutS);
  };
  ASSERT_EQ(render("8").exit_code, 0);
  const std::string png = rtsim::test::read_file(dir / "out/image.png");
  const std::string stats = rtsim::test::read_file(dir / "out/stats.json");
  const std::string lock = "chattr +i " + (dir / "out/stats.json").string();
  if (rtsim::test::run_shell(lock).exit_code != 0) {
    fs::remove_all(dir);
    GTEST_SKIP() << "chattr +i is not supported here";
  }
  const LimitedRun r = render("16");
  rtsim::test::run_shell("chattr -i " + (dir / "out/stats.json").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("nothing was replaced"), std::string::npos) << r.output;
  EXPECT_EQ(rtsim::test::read_file(dir / "out/image.png"), png);
  EXPECT_EQ(rtsim::test::read_file(dir / "out/stats.json"), stats);
  for (const auto& e : fs::directory_iterator(dir / "out"))
    EXPECT_EQ(e.path().filename().string().find(".rtsim-partial"), std::string::npos) << e.path();
  fs::remove_all(dir);
}

// Item 9: an interrupted validate left its temporary folder with the runs in it
// (/tmp/rtsim-validate-*/runs-*). It removes them.
TEST(HostileInput, AnInterruptedValidateLeavesNoFolders) {
  const fs::path dir = rtsim::test::scratch_dir("hostile-validate");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const pid_t v = rtsim::test::start_rtsim({"validate", "--quick", "--jobs", "1"}, dir);
  bool started = false;
  for (int i = 0; i < 200 && !started; ++i) {  // until its temporary folder has runs in it
    ::usleep(50000);
    for (const auto& e : fs::recursive_directory_iterator(dir))
      if (e.path().filename().string().rfind("runs-", 0) == 0) started = true;
  }
  ASSERT_TRUE(started) << "validate made no run folder under TMPDIR";
  ::kill(v, SIGTERM);
  int status = 0;
  ::waitpid(v, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
  ::usleep(200000);  // its runs end with it (parent-death signal)
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
  EXPECT_TRUE(left.empty()) << "left behind: " << left.front();
  fs::remove_all(dir);
}

}  // namespace
