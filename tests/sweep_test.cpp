// The sweep file (platform/sweep): the schema (lists, linear and log ranges, units, zipped
// axes, the product and its order), the points' command lines and hashes, the checks against the
// machines' registries, every bad-input case with its line and message (and, through the binary,
// exit status 2 and no output), and the results table built from outcomes.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "common/input_error.hpp"
#include "modules/stat_classes.hpp"
#include "params/registry.hpp"
#include "platform/machine_registry.hpp"
#include "platform/sweep/image_sharing.hpp"
#include "platform/sweep/results_table.hpp"
#include "platform/sweep/sweep_check.hpp"
#include "platform/sweep/sweep_file.hpp"
#include "platform/sweep/sweep_points.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::InputError;
using namespace rtsim::sweep;

namespace {

/// The machines the sweeps here name, from the registry (none is written here): the default
/// machine, whose peripheral.grid.divisions the axes sweep, and another that does not declare
/// it but has render.grid.divisions (the name a sweep that sets it on that machine is pointed to).
struct Machines {
  std::string first, other;
};
const Machines& machines() {
  static const Machines m = [] {
    Machines out{rtsim::platform::default_machine().name(), ""};
    for (const auto* machine : rtsim::platform::machines()) {
      rtsim::params::ParamRegistry r;
      rtsim::platform::declare_params_of(machine, r);
      if (!r.contains("peripheral.grid.divisions") && r.contains("render.grid.divisions")) {
        out.other = machine->name();
        break;
      }
    }
    EXPECT_FALSE(out.other.empty());
    return out;
  }();
  return m;
}
const std::string& m1() { return machines().first; }
const std::string& m2() { return machines().other; }

/// A sweep of the first machine on builtin:ullner-cubes: lines 1 and 2.
std::string head() { return "machine = \"" + m1() + "\"\nscene = \"builtin:ullner-cubes\"\n"; }

SweepFile parse(const std::string& text) { return parse_sweep(text, "s.toml", "/base"); }

std::vector<std::string> texts(const AxisMember& m) {
  std::vector<std::string> out;
  for (const auto& v : m.values) out.push_back(v.text);
  return out;
}

std::vector<std::string> axis_texts(const std::string& axis_body) {
  const SweepFile f = parse(head() + "[[axes]]\n" + axis_body);
  EXPECT_EQ(f.axes.size(), 1u);
  return texts(f.axes.at(0).members.at(0));
}

/// The error of reading and checking `text`: "line: message".
std::string error_of(const std::string& text) {
  try {
    const SweepFile f = parse(text);
    check_sweep(f, expand_points(f));
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "s.toml");
    return std::to_string(e.line()) + ": " + e.message();
  }
  return "(no error)";
}

using Strings = std::vector<std::string>;

/// `name` with two letters in the middle swapped: a machine that does not exist, one edit away.
std::string misspelt(std::string name) {
  const std::size_t k = name.size() / 2;
  std::swap(name[k], name[k + 1]);
  return name;
}

}  // namespace

TEST(SweepFile, ExplicitValuesKeepTheirTypes) {
  const SweepFile f = parse(head() +
                            "[[axes]]\nparam = \"peripheral.grid.divisions\"\n"
                            "values = [1, 2.5, \"400 ns\", true]\n");
  const auto& m = f.axes.at(0).members.at(0);
  EXPECT_EQ(texts(m), (Strings{"1", "2.5", "400 ns", "true"}));
  EXPECT_TRUE(m.values[0].json.is_number_integer());
  EXPECT_TRUE(m.values[1].json.is_number_float());
  EXPECT_TRUE(m.values[2].json.is_string());
  EXPECT_TRUE(m.values[3].json.is_boolean());
  EXPECT_EQ(m.values[0].line, 5u);
}

// The run flags a sweep may set or vary: passed to each point's `rtsim run` as the flags are,
// "off" values adding nothing, traces capped unless the file caps them; a varied flag is a column.
TEST(SweepFile, RunFlagsAreFixedOrAxesAndBecomeTheRunsFlags) {
  const SweepFile f = parse(head() +
                            "image = \"none\"\nlatency-probe = true\ntrace = \"vcd\"\n"
                            "sample-work-stride = 4\nsample-warmup = 1\n"
                            "[[axes]]\nparam = \"sample\"\nvalues = [0, 4]\n");
  const auto points = expand_points(f);
  ASSERT_EQ(points.size(), 2u);
  const auto has = [](const Point& p, const Strings& seq) {
    return std::search(p.args.begin(), p.args.end(), seq.begin(), seq.end()) != p.args.end();
  };
  for (const auto& p : points) {
    EXPECT_TRUE(has(p, {"--image", "none"})) << p.command_line();
    EXPECT_TRUE(has(p, {"--latency-probe"})) << p.command_line();
    EXPECT_TRUE(has(p, {"--trace", "vcd"})) << p.command_line();
    EXPECT_TRUE(has(p, {"--trace-max-events", std::to_string(kSweepTraceMaxEvents)}))
        << p.command_line();
    EXPECT_FALSE(has(p, {"-p", "image=none"})) << "a run flag is no parameter";
  }
  EXPECT_FALSE(has(points[0], {"--sample"})) << "sample = 0: the whole frame in detail";
  // A sampled run's settings only where it is sampled: `rtsim run` refuses them alone.
  EXPECT_FALSE(has(points[0], {"--sample-work-stride"})) << points[0].command_line();
  EXPECT_FALSE(has(points[0], {"--sample-warmup"})) << points[0].command_line();
  EXPECT_TRUE(has(points[1], {"--sample", "4"}));
  EXPECT_TRUE(has(points[1], {"--sample-work-stride", "4"})) << points[1].command_line();
  EXPECT_TRUE(has(points[1], {"--sample-warmup", "1"})) << points[1].command_line();
  EXPECT_EQ(f.swept_columns(), Strings{"sample"});
  EXPECT_TRUE(f.swept_params().empty());
  const SweepFile capped = parse(head() +
                                 "trace = \"perfetto\"\ntrace-max-events = 5000\n"
                                 "sample-error = \"1%\"\n");
  const auto p = expand_points(capped).at(0);
  EXPECT_TRUE(has(p, {"--trace", "perfetto"})) << p.command_line();
  EXPECT_TRUE(has(p, {"--trace-max-events", "5000"})) << p.command_line();
  EXPECT_TRUE(has(p, {"--sample-error", "1%"})) << p.command_line();
  EXPECT_EQ(std::count(p.args.begin(), p.args.end(), "--trace-max-events"), 1);
}

TEST(SweepFile, LinearRanges) {
  // Integer start/stop/step: integers, stop included; no step means 1.
  auto v = axis_texts("param = \"x\"\nrange = { start = 1, stop = 30, step = 1 }\n");
  ASSERT_EQ(v.size(), 30u);
  EXPECT_EQ(v.front(), "1");
  EXPECT_EQ(v.back(), "30");
  EXPECT_EQ(axis_texts("param = \"x\"\nrange = { start = 1, stop = 30 }\n").size(), 30u);
  EXPECT_EQ(axis_texts("param = \"x\"\nrange = { start = 2, stop = 11, step = 3 }\n"),
            (Strings{"2", "5", "8", "11"}));
  EXPECT_EQ(axis_texts("param = \"x\"\nrange = { start = 10, stop = 1, step = -4 }\n"),
            (Strings{"10", "6", "2"}));
  // Floats: 15 significant digits, so 0.1 steps do not print as 0.30000000000000004.
  EXPECT_EQ(axis_texts("param = \"x\"\nrange = { start = 0.1, stop = 0.5, step = 0.1 }\n"),
            (Strings{"0.1", "0.2", "0.3", "0.4", "0.5"}));
  // count: evenly spaced, both ends included; integers round.
  EXPECT_EQ(axis_texts("param = \"x\"\nrange = { start = 1, stop = 30, count = 4 }\n"),
            (Strings{"1", "11", "20", "30"}));
  EXPECT_EQ(axis_texts("param = \"x\"\nrange = { start = 0.0, stop = 1, count = 5 }\n"),
            (Strings{"0", "0.25", "0.5", "0.75", "1"}));
  // One value: start = stop. A count of 1 between two values named start alone, silently
  // (issue 30 item 9): refused.
  EXPECT_EQ(axis_texts("param = \"x\"\nrange = { start = 7, stop = 7, count = 1 }\n"),
            (Strings{"7"}));
  EXPECT_THROW(axis_texts("param = \"x\"\nrange = { start = 7, stop = 9, count = 1 }\n"),
               rtsim::InputError);
}

TEST(SweepFile, LogRanges) {
  EXPECT_EQ(axis_texts("param = \"x\"\nrange = { start = 1, stop = 64, count = 7, scale = "
                       "\"log\" }\n"),
            (Strings{"1", "2", "4", "8", "16", "32", "64"}));
  EXPECT_EQ(axis_texts("param = \"x\"\nrange = { start = 1.0, stop = 100, count = 3, scale = "
                       "\"log\" }\n"),
            (Strings{"1", "10", "100"}));
  // Integers round, and values made equal by rounding are kept once: 1, 1.32, 1.74, 2.30,
  // 3.03, 4 -> 1, 2, 3, 4.
  EXPECT_EQ(axis_texts("param = \"x\"\nrange = { start = 1, stop = 4, count = 6, scale = "
                       "\"log\" }\n"),
            (Strings{"1", "2", "3", "4"}));
}

TEST(SweepFile, RangesWithAUnitGiveQuantities) {
  const SweepFile f = parse(head() +
                            "[[axes]]\nparam = \"x\"\n"
                            "range = { start = 100, stop = 400, step = 100, unit = \"ns\" }\n");
  const auto& m = f.axes.at(0).members.at(0);
  EXPECT_EQ(texts(m), (Strings{"100 ns", "200 ns", "300 ns", "400 ns"}));
  EXPECT_EQ(m.values[0].json, "100 ns");
}

TEST(SweepFile, ProductOfMachinesScenesAxesAndZips) {
  const SweepFile f =
      parse("machine = [\"" + m2() + "\", \"" + m1() + "\"]\n" +
            "scenes = [\"builtin:default\", \"builtin:ullner-cubes\", \"my.nff\"]\n"
            "width = 16\nheight = 12\n"
            "[params]\nshade.max_depth = 0\n"
            "[[axes]]\nparam = \"render.spp\"\nvalues = [1, 2, 3, 4]\n"
            "[[axes]]\nzip = [ { param = \"a.b\", values = [1, 2] },\n"
            "        { param = \"c.d\", range = { start = 10, stop = 20, count = 2 } } ]\n");
  ASSERT_EQ(f.axes.size(), 4u);  // machine, scene, render.spp, the zip
  EXPECT_EQ(f.point_count(), 2u * 3u * 4u * 2u);
  EXPECT_EQ(f.swept_params(), (Strings{"render.spp", "a.b", "c.d"}));
  const auto points = expand_points(f);
  ASSERT_EQ(points.size(), 48u);

  // The last axis varies fastest; zipped members advance together.
  const auto at = [&](std::size_t i, const char* name) { return points[i].find(name)->value.text; };
  EXPECT_EQ(at(0, "a.b"), "1");
  EXPECT_EQ(at(0, "c.d"), "10");
  EXPECT_EQ(at(1, "a.b"), "2");
  EXPECT_EQ(at(1, "c.d"), "20");
  EXPECT_EQ(at(2, "render.spp"), "2");
  EXPECT_EQ(at(8, "scene"), "builtin:ullner-cubes");
  EXPECT_EQ(at(24, "machine"), m1());
  EXPECT_EQ(at(47, "scene"), "my.nff");
  EXPECT_EQ(points[7].key, "0007");
  EXPECT_EQ(points[7].index, 7u);

  // The command line: run options, -q, fixed parameters, then swept ones; relative scene files
  // resolved against the sweep file's folder.
  EXPECT_EQ(points[47].args,
            (Strings{"run", "--machine", m1(), "--scene", "/base/my.nff", "--width", "16",
                     "--height", "12", "-q", "-p", "shade.max_depth=0", "-p", "render.spp=4", "-p",
                     "a.b=2", "-p", "c.d=20"}));
  EXPECT_EQ(points[47].command_line(),
            "rtsim run --machine " + m1() +
                " --scene /base/my.nff --width 16 --height 12 "
                "-q -p shade.max_depth=0 -p render.spp=4 -p a.b=2 -p c.d=20");
}

TEST(SweepFile, NoAxesIsOnePointAndKeysGrowWithTheSweep) {
  const SweepFile one = parse(head());
  EXPECT_EQ(one.point_count(), 1u);
  EXPECT_EQ(expand_points(one).at(0).key, "0000");
  const SweepFile big =
      parse(head() + "[[axes]]\nparam = \"x\"\nrange = { start = 1, stop = 12000 }\n");
  const auto points = expand_points(big);
  EXPECT_EQ(points.front().key, "00000");
  EXPECT_EQ(points.back().key, "11999");
}

TEST(SweepFile, HashFollowsTheCommandLine) {
  const auto a = expand_points(parse(head() + "[params]\n\"shade.max_depth\" = 1\n"));
  const auto b = expand_points(parse(head() + "[params.shade]\nmax_depth = 1\n"));
  const auto c = expand_points(parse(head() + "[params]\n\"shade.max_depth\" = 2\n"));
  EXPECT_EQ(a[0].hash().size(), 16u);
  EXPECT_EQ(a[0].hash(), b[0].hash());  // a nested table is the same parameter
  EXPECT_NE(a[0].hash(), c[0].hash());
  EXPECT_EQ(fnv1a64_hex(""), "cbf29ce484222325");   // FNV-1a offset basis
  EXPECT_EQ(fnv1a64_hex("a"), "af63dc4c8601ec8c");  // published FNV-1a test vector
}

TEST(SweepCheck, AcceptsValidParametersForEveryMachine) {
  const SweepFile f = parse("machine = [\"" + m2() + "\", \"" + m1() + "\"]\n" +
                            "scene = \"builtin:ullner-cubes\"\n"
                            "[params]\nquantum = \"10 us\"\n"
                            "[[axes]]\nparam = \"shade.max_depth\"\nvalues = [0, 3]\n");
  EXPECT_NO_THROW(check_sweep(f, expand_points(f)));
}

TEST(SweepCheck, EveryBadInputNamesTheLineAndWhatWasExpected) {
  struct Case {
    const char* what;
    std::string text;
    std::string expected;  // "LINE: start of the message"
  };
  const std::string axis = "[[axes]]\n";
  const std::vector<Case> cases = {
      {"toml syntax", "machine = \"" + m2() + "\"\nscene = [1, ", "2: "},
      {"run flag of the wrong kind", head() + "image = \"jpg\"\n",
       "3: 'image' is \"all\", \"png\" or \"none\""},
      {"sample of one", head() + "sample = 1\n", "3: 'sample' = 1 would simulate every window"},
      {"sample out of range", head() + axis + "param = \"sample\"\nvalues = [4, -2]\n",
       "5: 'sample' must be 0 (the whole frame in detail) or K"},
      {"latency-probe not a bool", head() + "latency-probe = 1\n",
       "3: 'latency-probe' is true or false"},
      {"unknown trace", head() + "trace = \"vcd,json\"\n", "3: 'trace' is \"vcd\""},
      {"uncapped trace", head() + "trace = \"vcd\"\ntrace-max-events = 0\n",
       "4: 'trace-max-events' must be an integer from 1"},
      {"cap without a trace", head() + "trace-max-events = 10\n",
       "0: 'trace-max-events' caps traces"},
      {"sample-error not a percentage", head() + "sample-error = 0.01\n",
       "3: 'sample-error' is a percentage"},
      {"sample and sample-error", head() + "sample = 4\nsample-error = \"1%\"\n",
       "0: give 'sample' (K) or 'sample-error'"},
      {"a run flag in [params]", head() + "[params]\nsample = 4\n",
       "4: 'sample' is an option of `rtsim run`, not a parameter"},
      {"unknown top-level key", head() + "widht = 3\n",
       "3: unknown key 'widht' in the sweep file; did you mean 'width'?"},
      {"unknown key, no near name", head() + "zzz = 3\n",
       "3: unknown key 'zzz' in the sweep file; expected one of 'name', "},
      {"unknown parameter", head() + "[params]\n\"shade.max_dept\" = 2\n",
       "4: on machine '" + m1() +
           "': unknown parameter 'shade.max_dept'; did you mean "
           "'shade.max_depth'?"},
      {"value out of range",
       head() + axis + "param = \"peripheral.grid.divisions\"\nvalues = [1, -3]\n",
       "5: on machine '" + m1() +
           "': parameter 'peripheral.grid.divisions' expects an "
           "integer from 0 to"},
      {"value of the wrong kind", head() + "[params]\nquantum = 5\n",
       "4: on machine '" + m1() + "': parameter 'quantum': \"5\" has no unit"},
      {"parameter of another machine",
       "machine = [\"" + m1() + "\", \"" + m2() + "\"]\nscene = \"builtin:default\"\n" + axis +
           "param = \"peripheral.grid.divisions\"\nvalues = [1]\n",
       "4: on machine '" + m2() + "': parameter 'peripheral.grid.divisions' is not used by " +
           m2() + " (it would change nothing); did you mean 'render.grid.divisions'?"},
      {"unknown machine",
       "machine = [\"" + m2() + "\", \"" + misspelt(m1()) + "\"]\nscene = \"builtin:default\"\n",
       "1: unknown machine '" + misspelt(m1()) + "'; did you mean '" + m1() + "'?"},
      {"unknown builtin scene", "machine = \"" + m2() + "\"\nscene = \"builtin:ullner-cube\"\n",
       "2: scene 'builtin:ullner-cube': unknown builtin scene 'ullner-cube'; did you mean "
       "builtin:ullner-cubes"},
      {"missing scene file", "machine = \"" + m2() + "\"\nscene = \"nothere.nff\"\n",
       "2: scene 'nothere.nff': /base/nothere.nff: cannot open scene file"},
      {"no machine", "scene = \"builtin:default\"\n", "0: the sweep names no machine"},
      {"no scene", "machine = \"" + m2() + "\"\n", "0: the sweep names no scene"},
      {"machine and machines",
       "machine = \"" + m2() + "\"\nmachines = [\"" + m2() + "\"]\nscene = \"builtin:default\"\n",
       "2: give either 'machine' or 'machines', not both"},
      {"empty machine list", "machine = []\nscene = \"builtin:default\"\n",
       "1: 'machine' is an empty list"},
      {"machine not a string", "machine = 3\nscene = \"builtin:default\"\n",
       "1: 'machine' must be a name or a list of names; got an integer 3"},
      {"width 0", head() + "width = 0\n",
       "3: 'width' must be an integer from 1 to 16384 (pixels); got 0"},
      {"width as a list", head() + "width = [1, 2]\n",
       "3: 'width' takes one value; to vary it, add an [[axes]] entry"},
      {"run option in [params]", head() + "[params]\nwidth = 3\n",
       "4: 'width' is an option of `rtsim run`, not a parameter"},
      {"list in [params]", head() + "[params]\n\"render.spp\" = [1, 2]\n",
       "4: [params] sets one value per parameter; to vary 'render.spp', add an [[axes]] entry"},
      {"set twice",
       head() + "[params]\n\"render.spp\" = 1\n" + axis +
           "param = \"render.spp\"\nvalues = [1, 2]\n",
       "6: 'render.spp' is set or varied twice in this sweep"},
      {"two axes, one name",
       head() + axis + "param = \"render.spp\"\nvalues = [1]\n" + axis +
           "param = \"render.spp\"\nvalues = [2]\n",
       "7: 'render.spp' is set or varied twice"},
      {"[[axis]] for [[axes]]", head() + "[[axis]]\nparam = \"x\"\nvalues = [1]\n",
       "3: unknown key 'axis' in the sweep file; did you mean 'axes'?"},
      {"axis key typo", head() + axis + "param = \"render.spp\"\nvlaues = [1]\n",
       "5: unknown key 'vlaues' in axis 1; did you mean 'values'?"},
      {"axis without param", head() + axis + "values = [1]\n",
       "3: axis 1 needs 'param' (the parameter it varies) or 'zip'"},
      {"axis without values", head() + axis + "param = \"render.spp\"\n",
       "4: the axis of 'render.spp' needs 'values' (a list) or 'range'"},
      {"values and range",
       head() + axis + "param = \"render.spp\"\nvalues = [1]\nrange = { start = 1, stop = 2 }\n",
       "6: the axis of 'render.spp': give 'values' or 'range', not both"},
      {"empty values", head() + axis + "param = \"render.spp\"\nvalues = []\n",
       "5: the axis of 'render.spp': 'values' is empty"},
      {"value twice", head() + axis + "param = \"render.spp\"\nvalues = [1, 2, 1]\n",
       "5: the axis of 'render.spp' lists '1' twice"},
      {"table as a value", head() + axis + "param = \"render.spp\"\nvalues = [1, { a = 2 }]\n",
       "5: a value of 'render.spp' must be a number, a string or true/false; got a table"},
      {"range without stop", head() + axis + "param = \"render.spp\"\nrange = { start = 1 }\n",
       "5: the range of 'render.spp' needs 'stop'"},
      {"range with step and count",
       head() + axis +
           "param = \"render.spp\"\nrange = { start = 1, stop = 4, step = 1, count = 4 }\n",
       "5: the range of 'render.spp': give 'step' or 'count', not both"},
      {"step 0",
       head() + axis +
           "param = \"render.spp\"\nrange = { start = 1, stop = 4, step = "
           "0 }\n",
       "5: the range of 'render.spp': 'step' must not be 0"},
      {"step away from stop",
       head() + axis + "param = \"render.spp\"\nrange = { start = 1, stop = 5, step = -1 }\n",
       "5: the range of 'render.spp': step -1 goes away from stop 5 (from start 1)"},
      {"range key typo",
       head() + axis + "param = \"render.spp\"\nrange = { start = 1, stopp = 5 }\n",
       "5: unknown key 'stopp' in the range of 'render.spp'; did you mean 'stop'?"},
      {"bad scale",
       head() + axis +
           "param = \"render.spp\"\nrange = { start = 1, stop = 5, count = 2, scale = \"ln\" }\n",
       "5: the range of 'render.spp': scale must be \"linear\" or \"log\""},
      {"log without count",
       head() + axis + "param = \"render.spp\"\nrange = { start = 1, stop = 5, scale = \"log\" }\n",
       "5: the range of 'render.spp': a log range needs 'count'"},
      {"log from 0",
       head() + axis +
           "param = \"render.spp\"\nrange = { start = 0, stop = 5, count = 3, scale = \"log\" }\n",
       "5: the range of 'render.spp': a log range needs start and stop above 0"},
      {"count 0",
       head() + axis +
           "param = \"render.spp\"\nrange = { start = 1, stop = 5, count "
           "= 0 }\n",
       "5: the range of 'render.spp': 'count' must be an integer from 1 to 100000"},
      {"range too long",
       head() + axis + "param = \"render.spp\"\nrange = { start = 1, stop = 1e6 }\n",
       "5: the range of 'render.spp' has 1000000 values, more than 100000"},
      {"product too big",
       head() + axis + "param = \"a.b\"\nrange = { start = 1, stop = 1000 }\n" + axis +
           "param = \"c.d\"\nrange = { start = 1, stop = 1000 }\n",
       "6: the sweep has more than 100000 points"},
      {"zip lengths differ",
       head() + axis +
           "zip = [\n  { param = \"render.spp\", values = [1, 2] },\n"
           "  { param = \"shade.max_depth\", values = [1, 2, 3] },\n]\n",
       "6: zipped axis: 'render.spp' has 2 values but 'shade.max_depth' has 3"},
      {"zip with param", head() + axis + "param = \"x\"\nzip = []\n",
       "4: unknown key 'param' in axis 1 (a zipped axis has only 'zip')"},
      {"zip entry not a table", head() + axis + "zip = [1]\n",
       "4: axis 1: each entry of 'zip' must be a table"},
      {"config file missing", head() + "configs = [\"nothere.toml\"]\n",
       "3: config file 'nothere.toml' not found (looked for /base/nothere.toml"},
  };
  for (const auto& c : cases) {
    const std::string got = error_of(c.text);
    EXPECT_TRUE(got.starts_with(c.expected))
        << c.what << "\n  expected: " << c.expected << "\n  got:      " << got;
  }
}

TEST(SweepCheck, BadSweepExitsWithStatus2AndWritesNothing) {
  const fs::path dir = rtsim::test::scratch_dir("sweep-bad");
  fs::create_directories(dir);
  const fs::path file = dir / "bad.toml";
  std::ofstream(file) << head() << "[[axes]]\nparam = \"peripheral.grid.divisons\"\nvalues = [1]\n";
  const fs::path out = dir / "out";
  const auto r = rtsim::test::run_rtsim("sweep " + file.string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(file.string() + ":4: on machine '" + m1() +
                          "': unknown parameter "
                          "'peripheral.grid.divisons'; did you mean 'peripheral.grid.divisions'"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));

  const auto missing =
      rtsim::test::run_rtsim("sweep " + (dir / "none.toml").string() + " --out " + out.string());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("cannot open sweep file"), std::string::npos) << missing.output;
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(dir);
}

TEST(SweepHelp, ExplainsTheFormatAndPointsToTheDocs) {
  const auto r = rtsim::test::run_rtsim("sweep --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* s : {"[[axes]]", "range = {", "scale = \"log\"", "zip = [", "[params]",
                        "docs/sweeps.md", "--mpi", "--jobs", "--out", "results.csv"})
    EXPECT_NE(r.output.find(s), std::string::npos) << s;
}

TEST(ResultsTable, AClassOfManyInstancesOrOfAVaryingSizeIsColumnsOfItsAggregates) {
  // node* has 3 instances in one point and 2 in the other: node2 would be another node at each
  // size, so the table keeps the class's aggregates, never node0, node1, node2. pert*.shell
  // has 2 instances in both: its instances stay columns, and its band is added.
  const SweepFile f = parse(head() + "width = 8\n" +
                            "[[axes]]\nparam = \"peripheral.grid.divisions\"\nvalues = [0, 4]\n");
  const auto points = expand_points(f);
  std::vector<PointOutcome> outcomes(2);
  const auto stats = [](int nodes) {
    nlohmann::ordered_json s = {{"simulated_time_s", 1.0}};
    for (int k = 0; k < nodes; ++k)
      s["modules"]["node" + std::to_string(k)] = {{"utilization", 0.1 * k}, {"sent", k}};
    for (int k = 0; k < 2; ++k)
      s["modules"]["pert" + std::to_string(k) + ".shell"] = {{"utilization", 0.5}, {"rays", 2}};
    s["module_classes"] = rtsim::modules::class_aggregates(s["modules"]);
    return s.dump();
  };
  for (int i = 0; i < 2; ++i) {
    outcomes[i].ok = true;
    outcomes[i].stats_text = stats(3 - i);
  }
  const ResultsTable t = make_results_table(f, points, outcomes);
  const auto has = [&](const std::string& c) {
    return std::find(t.columns.begin(), t.columns.end(), c) != t.columns.end();
  };
  for (const char* c :
       {"module_classes.node*.instances", "module_classes.node*.utilization.min",
        "module_classes.node*.utilization.mean", "module_classes.node*.utilization.max",
        "module_classes.node*.utilization.max_instance", "module_classes.node*.sent.mean",
        "modules.pert0.shell.rays", "module_classes.pert*.shell.utilization.mean"})
    EXPECT_TRUE(has(c)) << c;
  for (const char* c : {"modules.node0.utilization", "modules.node2.sent",
                        "module_classes.node*.sent.max", "module_classes.pert*.shell.rays.mean"})
    EXPECT_FALSE(has(c)) << c;

  // Its instances are in each point's modules.csv.
  const std::string m = modules_csv(nlohmann::ordered_json::parse(stats(3)));
  EXPECT_EQ(m.substr(0, m.find('\n')), "module,class,utilization,sent,rays");
  EXPECT_NE(m.find("\nnode2,node*,0.2"), std::string::npos) << m;
}

TEST(ResultsTable, OneRowPerPointWithSweptValuesStatsAndFailures) {
  const SweepFile f = parse(head() + "width = 8\n" +
                            "[[axes]]\nparam = \"peripheral.grid.divisions\"\nvalues = [0, 4]\n");
  const auto points = expand_points(f);
  std::vector<PointOutcome> outcomes(2);
  outcomes[0].ok = true;
  outcomes[0].exit_code = 0;
  outcomes[0].wall_s = 1.5;
  outcomes[0].stats_text = R"({"tool": "rtsim", "machine": "a-machine", "width": 8,
      "height": 6, "simulated_time_s": 0.25, "rays": {"total": 48, "primary": 48},
      "modules": {"peripheral.pipeline": {"busy_s": 0.2, "utilization": 0.8}},
      "ray_latency_s": {"mean": 1e-5, "histogram": {"counts": [1, 2]}},
      "accel": {"description": "grid, 4 cells"}, "params": {"x": "1"}})";
  outcomes[1].exit_code = 2;
  outcomes[1].wall_s = 0.5;
  outcomes[1].error = "exit status 2: rtsim: error: bad, really";

  const ResultsTable t = make_results_table(f, points, outcomes);
  const Strings expected_columns = {"point",
                                    "machine",
                                    "scene",
                                    "width",
                                    "height",
                                    "peripheral.grid.divisions",
                                    "status",
                                    "exit_code",
                                    "error",
                                    "point_wall_time_s",
                                    "dir",
                                    "simulated_time_s",
                                    "rays.total",
                                    "rays.primary",
                                    "ray_latency_s.mean",
                                    "accel.description",
                                    "modules.peripheral.pipeline.busy_s",
                                    "modules.peripheral.pipeline.utilization",
                                    "command"};
  EXPECT_EQ(t.columns, expected_columns);
  ASSERT_EQ(t.rows.size(), 2u);
  const auto& ok = t.rows[0];
  EXPECT_EQ(ok[0], 0);
  EXPECT_EQ(ok[3], 8);
  EXPECT_EQ(ok[4], 6);  // as rendered (from stats.json)
  EXPECT_EQ(ok[5], 0);
  EXPECT_EQ(ok[6], "ok");
  EXPECT_EQ(ok[10], "points/0000");
  EXPECT_EQ(ok[17], 0.8);
  const auto& bad = t.rows[1];
  EXPECT_EQ(bad[3], 8);
  EXPECT_TRUE(bad[4].is_null());  // asked for no height, and the run said nothing
  EXPECT_EQ(bad[6], "failed");
  EXPECT_EQ(bad[7], 2);
  EXPECT_TRUE(bad[11].is_null());

  const std::string csv = to_csv(t);
  EXPECT_NE(csv.find("\n1," + m1() +
                     ",builtin:ullner-cubes,8,,4,failed,2,\"exit status 2: "
                     "rtsim: error: bad, really\",0.5,points/0001,,,,,,,,rtsim run "),
            std::string::npos)
      << csv;
  const std::string jsonl = to_jsonl(t);
  const auto first = nlohmann::ordered_json::parse(jsonl.substr(0, jsonl.find('\n')));
  EXPECT_EQ(first["peripheral.grid.divisions"], 0);
  EXPECT_EQ(first["rays.total"], 48);
  EXPECT_EQ(first.begin().key(), "point");
  EXPECT_TRUE(is_wall_clock_column("wall_time_s"));
  EXPECT_FALSE(is_wall_clock_column("simulated_time_s"));
}

TEST(SweepExamples, ConfigsSweepsParse) {
  // Both examples are checked whole: names, values and scenes, as `rtsim sweep` would.
  const std::string dir = std::string(RTSIM_SOURCE_DIR) + "/configs/sweeps/";
  const SweepFile fig = read_sweep_file(dir + "fig2-18-grid.toml");
  const auto points = expand_points(fig);
  ASSERT_EQ(points.size(), 30u);
  EXPECT_EQ(points.front().find("peripheral.grid.divisions")->value.text, "1");
  EXPECT_EQ(points.back().find("peripheral.grid.divisions")->value.text, "30");
  EXPECT_NO_THROW(check_sweep(fig, points));

  const SweepFile gaudet = read_sweep_file(dir + "gaudet-pert-speedup.toml");
  EXPECT_EQ(gaudet.point_count(), 3u * 3u * 7u);  // scenes x broadcast modes x PERT counts
  EXPECT_EQ(texts(gaudet.axes.back().members.at(0)),
            (Strings{"1", "2", "4", "8", "16", "32", "64"}));
  EXPECT_EQ(texts(gaudet.axes.at(1).members.at(0)),
            (Strings{"direct", "non-adaptive", "adaptive"}));
  EXPECT_EQ(texts(gaudet.axes.front().members.at(0)),
            (Strings{"builtin:npp-412", "builtin:npp-816", "builtin:npp-820"}));
  EXPECT_NO_THROW(check_sweep(gaudet, expand_points(gaudet)));

  // The image depends on the peripheral's grid (its twin's search) but on none of the timing
  // sweep's axes: fig2-18 renders each point's image, the timing sweep one.
  auto sharing = [](const SweepFile& f) {
    auto p = expand_points(f);
    rtsim::sweep::share_images(f, p);
    return std::count_if(p.begin(), p.end(), [](const auto& x) { return x.image_from; });
  };
  EXPECT_EQ(sharing(fig), 0);
  const SweepFile timing = read_sweep_file(dir + "gaudet-timing-100.toml");
  ASSERT_EQ(timing.point_count(), 100u);
  EXPECT_EQ(sharing(timing), 99);

  // Every example in the folder reads and checks as `rtsim sweep` would (names, values, scenes).
  std::size_t examples = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() != ".toml") continue;
    ++examples;
    const SweepFile f = read_sweep_file(e.path().string());
    EXPECT_NO_THROW(check_sweep(f, expand_points(f))) << e.path();
  }
  EXPECT_GE(examples, 6u);
}
