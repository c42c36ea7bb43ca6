// A hostile user's inputs over every subcommand and every machine, as one table: the arguments
// (passed without a shell), the exit statuses allowed (0: it ran; 2: refused as bad input; never
// 1, a signal or a hang) and what must or must not be on disk afterwards. Issue 30's defects are
// rows here, each marked with its item; the cases that need several steps (a sweep resumed, an
// output set that cannot be committed) are tests of their own below the table.
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

#include "tests/limited_run.hpp"
#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using rtsim::test::LimitedRun;
using rtsim::test::run_limited;

constexpr double kTimeoutS = 60.0;
constexpr std::uint64_t kAddressSpace = std::uint64_t{8} << 30;
constexpr long kMaxRssKib = 2L << 20;

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
      "name = \"h\"\nmachine = \"vax-750\"\nscene = \"builtin:default\"\nwidth = 8\nheight = 8\n";
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

struct Case {
  std::string name;
  std::vector<std::string> args;
  std::vector<int> allowed;
  /// After the run, in the test's folder: "" if all is well, else what is wrong.
  std::function<std::string(const fs::path&, const LimitedRun&)> check = nullptr;
};

std::string present(const fs::path& p) { return fs::exists(p) ? "" : p.string() + " is missing"; }
std::string absent(const fs::path& p) { return fs::exists(p) ? p.string() + " exists" : ""; }
std::string says(const LimitedRun& r, const std::string& text) {
  return r.output.find(text) != std::string::npos ? "" : "output lacks '" + text + "'";
}

std::vector<Case> cases() {
  std::vector<Case> c;
  const auto run = [](const std::string& machine, const std::string& scene,
                      std::vector<std::string> more = {}) {
    std::vector<std::string> a = {"run", "--machine", machine, "--scene",
                                  scene, "--width",   "8",     "--height",
                                  "8",   "-q",        "--out", "out/" + machine};
    a.insert(a.end(), more.begin(), more.end());
    return a;
  };
  // Item 1: describe's --out reaches no shell; odd and bad folders.
  c.push_back({"describe: a path with a quote and a command",
               {"describe", "vax-750", "--out", "o/x';touch PWNED;'"},
               {0},
               [](const fs::path& d, const LimitedRun&) {
                 const std::string e = absent(d / "PWNED");
                 return e.empty() ? present(d / "o/x';touch PWNED;'/vax-750.dot") : e;
               }});
  c.push_back({"describe: a folder with an apostrophe",
               {"describe", "vax-750", "--out", "John's diagrams"},
               {0},
               [](const fs::path& d, const LimitedRun&) {
                 return present(d / "John's diagrams/vax-750.svg");
               }});
  for (const char* out : {"/", "/proc/rtsim-no-such", "/dev/null", "a-file"})
    c.push_back({std::string("describe --out ") + out, {"describe", "vax-750", "--out", out}, {2}});
  c.push_back(
      {"describe: a 32 x 32 array is drawn with its class cut short",
       {"describe", "ullner-array", "-p", "array.rows=32", "-p", "array.cols=32", "--out", "big"},
       {0},
       [](const fs::path& d, const LimitedRun&) {
         std::ifstream f(d / "big/ullner-array.dot");
         const std::string dot((std::istreambuf_iterator<char>(f)), {});
         return dot.find("1016 more node") != std::string::npos
                    ? present(d / "big/ullner-array.svg")
                    : "the DOT file does not count the nodes it leaves out";
       }});
  // Item 2: corrupted ID list words on gaudet-pert.
  for (const char* memory : {"shell_bus.memory", "prim_bus.memory"})
    for (const char* word : {"0", "1", "2", "3", "6", "9"})
      for (const char* mask : {"0xFFFFFFFF", "0x80000000"})
        c.push_back({std::string("gaudet-pert --fault ") + memory + ":" + word + ":" + mask,
                     run("gaudet-pert", "builtin:npp-412",
                         {"--fault", std::string(memory) + ":" + word + ":" + mask}),
                     {0, 2}});
  c.push_back({"--fault past the memory's end",
               run("gaudet-pert", "builtin:npp-412", {"--fault", "prim_bus.memory:99999999:0x1"}),
               {2}});
  c.push_back({"--fault on no memory",
               run("gaudet-pert", "builtin:npp-412", {"--fault", "prim_bus.memroy:0:0x1"}),
               {2},
               [](const fs::path&, const LimitedRun& r) { return says(r, "did you mean"); }});
  // Item 3: TOML nested without bound.
  for (const char* f : {"deep-key.toml", "deep-header.toml", "deep-array.toml", "deep-inline.toml"})
    c.push_back({std::string("config ") + f,
                 {"list", "params", "--machine", "vax-750", "--config", f},
                 {2}});
  c.push_back({"sweep file with a deep key", {"sweep", "sweep-deep.toml", "--list"}, {2}});
  // Item 4: JSON that is no stats.json.
  for (const char* f :
       {"deep.json", "array.json", "number.json", "string.json", "width.json", "huge.json"})
    c.push_back({std::string("diff of ") + f, {"diff", f, f}, {2}});
  c.push_back(
      {"diff --tolerance nan", {"diff", "array.json", "array.json", "--tolerance", "nan"}, {2}});
  // Item 5: a memory the bounds allow but the computer cannot hold.
  c.push_back({"ullner-array node.memory_words at its bound",
               run("ullner-array", "builtin:ullner-cubes", {"-p", "node.memory_words=1000000000"}),
               {0, 2}});
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
               run("ullner-peripheral", "builtin:ullner-cubes", {"--trace", "vcd,vcd"}),
               {0},
               [](const fs::path& d, const LimitedRun&) {
                 return present(d / "out/ullner-peripheral/trace.vcd");
               }});
  c.push_back(
      {"--trace perfetto,perfetto",
       run("vax-750", "builtin:default", {"--trace", "perfetto,perfetto"}),
       {0},
       [](const fs::path& d, const LimitedRun&) { return present(d / "out/vax-750/trace.json"); }});
  // Item 8: times that overflow outside the simulation.
  for (const char* p : {"array.load.word_time=1e6 s", "array.readout.pixel_time=1e6 s"})
    c.push_back({std::string("ullner-array ") + p,
                 run("ullner-array", "builtin:ullner-cubes", {"-p", p}),
                 {2}});
  for (const char* p : {"pipeline.culler.delay=1e6 s", "pipeline.cycle_time=1e6 s"})
    c.push_back(
        {std::string("wang-bezier ") + p, run("wang-bezier", "builtin:teapot", {"-p", p}), {2}});
  // Item 9: leftovers.
  c.push_back(
      {"a nested --out of a run refused while it runs leaves no folder",
       {"run", "--machine", "ullner-array", "--scene", "builtin:ullner-cubes", "--width", "8",
        "--height", "8", "-q", "--out", "nest/a/b", "-p", "array.load.word_time=1e6 s"},
       {2},
       [](const fs::path& d, const LimitedRun&) { return absent(d / "nest"); }});
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
               run("ullner-arary", "builtin:default"),
               {2},
               [](const fs::path&, const LimitedRun& r) { return says(r, "ullner-array"); }});
  c.push_back({"no such parameter", run("vax-750", "builtin:default", {"-p", "rendr.spp=2"}), {2}});
  c.push_back({"--width 0", run("vax-750", "builtin:default", {"--width", "0"}), {2}});
  c.push_back({"--quantum nan", run("vax-750", "builtin:default", {"--quantum", "nan s"}), {2}});
  c.push_back({"--sample 1", run("vax-750", "builtin:default", {"--sample", "1"}), {2}});
  c.push_back({"--scene that is a folder", run("vax-750", "."), {2}});
  c.push_back({"--scene /dev/zero", run("vax-750", "/dev/zero"), {2}});
  c.push_back(
      {"--out an existing file", {"render", "--scene", "builtin:default", "--out", "a-file"}, {2}});
  c.push_back({"validate an unknown figure", {"validate", "--only", "Z99", "--list"}, {2}});
  c.push_back({"list params of an unknown machine", {"list", "params", "--machine", "x"}, {2}});
  return c;
}

TEST(HostileInput, EveryRowExitsAsAllowedWithinItsMemory) {
  const fs::path dir = rtsim::test::scratch_dir("hostile");
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_inputs(dir);
  // A run folder for `diff`'s other side.
  const std::vector<Case> table = cases();
  std::size_t failures = 0;
  for (const Case& c : table) {
    const LimitedRun r = run_limited(c.args, dir, kTimeoutS, kAddressSpace);
    const bool status_ok =
        std::find(c.allowed.begin(), c.allowed.end(), r.exit_code) != c.allowed.end();
    std::string problem = status_ok ? "" : "status " + r.status();
    if (problem.empty() && r.max_rss_kib >= kMaxRssKib)
      problem = "peak memory " + std::to_string(r.max_rss_kib / 1024) + " MiB";
    if (problem.empty() && c.check) problem = c.check(dir, r);
    if (!problem.empty()) ++failures;
    EXPECT_TRUE(problem.empty()) << c.name << ": " << problem << "\n" << r.output;
  }
  std::printf("%zu rows, %zu failed\n", table.size(), failures);
  fs::remove_all(dir);
}

// Item 4: a resumed sweep takes a point's stats.json only if it is one rtsim could have written;
// anything else (a list, a JSON 50,000 levels deep) sends the point to run again.
TEST(HostileInput, AResumedSweepRunsAgainAPointWhoseStatsAreNotStats) {
  const fs::path dir = rtsim::test::scratch_dir("hostile-resume");
  fs::remove_all(dir);
  write(dir / "s.toml",
        "name = \"r\"\nmachine = \"vax-750\"\nscene = \"builtin:default\"\nwidth = 8\n"
        "height = 8\n[[axes]]\nparam = \"render.spp\"\nvalues = [1]\n");
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

/// Starts RTSIM_BINARY with `args` in `cwd` (output to /dev/null, TMPDIR=`cwd`); its pid.
pid_t start_rtsim(const std::vector<std::string>& args, const fs::path& cwd) {
  std::vector<std::string> text = {RTSIM_BINARY};
  text.insert(text.end(), args.begin(), args.end());
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(cwd.c_str()) != 0) ::_exit(127);
    ::setenv("TMPDIR", cwd.c_str(), 1);
    const int null = ::open("/dev/null", O_RDWR);
    ::dup2(null, STDIN_FILENO);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    std::vector<char*> argv;
    for (auto& a : text) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return pid;
}

/// The pids whose parent is `pid` (from /proc).
std::vector<pid_t> children_of(pid_t pid) {
  std::vector<pid_t> out;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(e.path() / "stat");
    std::string line;
    std::getline(stat, line);
    // pid (comm) state ppid ...: the command may hold spaces, the last ')' ends it.
    const std::size_t close = line.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(line.substr(close + 2));
    char state = 0;
    pid_t ppid = 0;
    rest >> state >> ppid;
    if (ppid == pid) out.push_back(static_cast<pid_t>(std::stoi(name)));
  }
  return out;
}

bool alive(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  std::getline(stat, line);
  const std::size_t close = line.rfind(')');
  return close != std::string::npos && line.size() > close + 2 && line[close + 2] != 'Z';
}

// Item 9: SIGTERM to a run whose --sample-error pilot (a fork) is running ended the run and left
// the pilot running. The pilot now ends with its parent.
TEST(HostileInput, ThePilotOfSampleErrorEndsWithItsRun) {
  const fs::path dir = rtsim::test::scratch_dir("hostile-pilot");
  fs::remove_all(dir);
  fs::create_directories(dir);
  // A pilot of about 4 s (a 32 x 32 array on a 512 x 512 frame): it is still running when its
  // run is ended.
  const pid_t run =
      start_rtsim({"run", "--machine", "ullner-array", "--scene", "builtin:ullner-cubes", "-p",
                   "array.rows=32", "-p", "array.cols=32", "--width", "512", "--height", "512",
                   "-q", "--sample-error", "1%", "--out", "out"},
                  dir);
  std::vector<pid_t> pilots;
  for (int i = 0; i < 200 && pilots.empty(); ++i) {  // up to 10 s for the pilot to start
    ::usleep(50000);
    pilots = children_of(run);
  }
  ASSERT_FALSE(pilots.empty()) << "the pilot never started";
  ::usleep(500000);
  ::kill(run, SIGTERM);
  int status = 0;
  ::waitpid(run, &status, 0);
  bool gone = false;
  for (int i = 0; i < 10 && !gone; ++i) {  // up to 0.5 s: the pilot itself runs for seconds
    gone = std::none_of(pilots.begin(), pilots.end(), alive);
    if (!gone) ::usleep(50000);
  }
  EXPECT_TRUE(gone) << "the pilot outlived its run";
  for (const pid_t p : pilots) ::kill(p, SIGKILL);
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

// Item 9: an interrupted validate left its temporary folder with the runs in it
// (/tmp/rtsim-validate-*/runs-*). It removes them.
TEST(HostileInput, AnInterruptedValidateLeavesNoFolders) {
  const fs::path dir = rtsim::test::scratch_dir("hostile-validate");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const pid_t v = start_rtsim({"validate", "--quick", "--jobs", "1"}, dir);
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
