// `rtsim run --trace-window`, `--trace-modules`, `--trace-max-events`: a narrowed trace holds
// only what was asked for and the same values as the whole trace there; a cap that drops events
// is printed, recorded in stats.json and shown in the report; bad values are bad input.
#include "app/trace_options.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using rtsim::test::read_file;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;

namespace {

const std::string kRun =
    "run --machine ullner-peripheral --scene builtin:ullner-cubes --width 16 --height 16 "
    "-p peripheral.grid.divisions=4 ";

/// Thread (track) names by (pid, tid).
std::map<std::pair<int, int>, std::string> track_names(const json& trace) {
  std::map<std::pair<int, int>, std::string> out;
  for (const auto& e : trace["traceEvents"])
    if (e["ph"] == "M" && e["name"] == "thread_name")
      out[{e["pid"].get<int>(), e["tid"].get<int>()}] = e["args"]["name"].get<std::string>();
  return out;
}

/// The value of counter `name` in effect at `t_us` (0 before its first sample).
double counter_at(const json& trace, const std::string& name, double t_us) {
  double best_t = -1, value = 0;
  for (const auto& e : trace["traceEvents"]) {
    if (e["ph"] != "C" || e["name"] != name) continue;
    const double t = e["ts"].get<double>();
    if (t <= t_us && t >= best_t) {
      best_t = t;
      value = e["args"]["value"].get<double>();
    }
  }
  return value;
}

}  // namespace

TEST(TraceOptions, WindowAndModulesNarrowTheTracesAndKeepTheirValues) {
  const fs::path whole = scratch_dir("trace-whole");
  auto r = run_rtsim(kRun + "--trace perfetto -q --out " + whole.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json stats = json::parse(read_file(whole / "stats.json"));
  const double b = stats["trace"]["stats_interval_s"][0].get<double>();
  const double e = stats["trace"]["stats_interval_s"][1].get<double>();
  // The middle third of the frame, in whole picoseconds.
  const auto t0 = static_cast<long long>(std::llround((b + (e - b) / 3) * 1e12));
  const auto t1 = static_cast<long long>(std::llround((b + 2 * (e - b) / 3) * 1e12));

  const fs::path part = scratch_dir("trace-part");
  r = run_rtsim(kRun + "--trace perfetto,vcd --trace-window '" + std::to_string(t0) + " ps," +
                std::to_string(t1) + " ps' --trace-modules 'peripheral.*' -q --out " +
                part.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, "");
  const json pstats = json::parse(read_file(part / "stats.json"));
  EXPECT_DOUBLE_EQ(pstats["trace"]["window_s"][0].get<double>(), static_cast<double>(t0) * 1e-12);
  EXPECT_DOUBLE_EQ(pstats["trace"]["window_s"][1].get<double>(), static_cast<double>(t1) * 1e-12);
  EXPECT_EQ(pstats["trace"]["modules"], json::array({"peripheral.*"}));
  // Narrowing the traces changes nothing else.
  EXPECT_EQ(pstats["simulated_time_s"], stats["simulated_time_s"]);
  EXPECT_EQ(pstats["modules"], stats["modules"]);

  const json wt = json::parse(read_file(whole / "trace.json"));
  const json pt = json::parse(read_file(part / "trace.json"));
  const auto names = track_names(pt);
  const double t0_us = static_cast<double>(t0) * 1e-6, t1_us = static_cast<double>(t1) * 1e-6;
  std::size_t slices = 0, counters = 0;
  for (const auto& ev : pt["traceEvents"]) {
    if (ev["ph"] == "M") continue;
    const double ts = ev["ts"].get<double>();
    if (ev["ph"] == "X") {
      ++slices;
      EXPECT_LE(ts, t1_us + 1e-6);
      EXPECT_GE(ts + ev["dur"].get<double>(), t0_us - 1e-6);
      const std::string track = names.at({ev["pid"].get<int>(), ev["tid"].get<int>()});
      EXPECT_EQ(track.rfind("peripheral.", 0), 0u) << track;
    } else if (ev["ph"] == "C") {
      ++counters;
      EXPECT_GE(ts, t0_us - 1e-6);
      EXPECT_LE(ts, t1_us + 1e-6);
      const std::string name = ev["name"].get<std::string>();
      EXPECT_EQ(name.rfind("peripheral.", 0), 0u) << name;
      // The same value as the whole trace has at that time.
      EXPECT_EQ(ev["args"]["value"].get<double>(), counter_at(wt, name, ts)) << name << " " << ts;
    }
  }
  EXPECT_GT(slices, 0u);
  EXPECT_GT(counters, 0u);

  // The VCD: peripheral's signals only, from T0 to T1.
  const std::string vcd = read_file(part / "trace.vcd");
  EXPECT_EQ(vcd.find("$scope module host"), std::string::npos);
  EXPECT_NE(vcd.find("$scope module ray_queue"), std::string::npos);
  std::vector<long long> stamps;
  std::istringstream lines(vcd);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty() && line[0] == '#') stamps.push_back(std::stoll(line.substr(1)));
  ASSERT_GE(stamps.size(), 2u);
  EXPECT_EQ(stamps.front(), t0);
  EXPECT_EQ(stamps.back(), t1);
  fs::remove_all(whole);
  fs::remove_all(part);
}

TEST(TraceOptions, ACapThatDropsEventsIsPrintedRecordedAndReported) {
  const fs::path dir = scratch_dir("trace-cap");
  const auto r = run_rtsim(kRun + "--trace perfetto,vcd --trace-max-events 100 --report -q --out " +
                           dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::regex_search(
      r.output, std::regex("warning: trace.json: [0-9]+ events dropped at --trace-max-events 100")))
      << r.output;
  EXPECT_TRUE(std::regex_search(
      r.output,
      std::regex("warning: trace.vcd: [0-9]+ value changes dropped at --trace-max-events 100")))
      << r.output;
  const json stats = json::parse(read_file(dir / "stats.json"));
  EXPECT_EQ(stats["trace"]["max_events"], 100);
  EXPECT_EQ(stats["trace"]["perfetto"]["events_written"], 100);
  EXPECT_GT(stats["trace"]["perfetto"]["events_dropped"].get<int>(), 0);
  EXPECT_EQ(stats["trace"]["vcd"]["changes_written"], 100);
  EXPECT_GT(stats["trace"]["vcd"]["changes_dropped"].get<int>(), 0);
  const json trace = json::parse(read_file(dir / "trace.json"));
  EXPECT_EQ(trace["otherData"]["rtsim_events_dropped"],
            stats["trace"]["perfetto"]["events_dropped"]);
  const std::string html = read_file(dir / "report.html");
  EXPECT_NE(html.find("dropped at --trace-max-events 100"), std::string::npos);
  fs::remove_all(dir);
}

TEST(TraceOptions, ACappedTraceSaysWhatItHoldsWhole) {
  // The same run, whole and capped: window_s of the capped one ends at the earliest event it
  // dropped, and it holds every slice, instant and flow event of the whole one before that.
  const fs::path whole_dir = scratch_dir("trace-whole"), capped_dir = scratch_dir("trace-capped");
  ASSERT_EQ(run_rtsim(kRun + "--trace perfetto -q --out " + whole_dir.string()).exit_code, 0);
  const auto r =
      run_rtsim(kRun + "--trace perfetto --trace-max-events 400 -q --out " + capped_dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json whole = json::parse(read_file(whole_dir / "stats.json"))["trace"];
  const json capped = json::parse(read_file(capped_dir / "stats.json"))["trace"];
  const double t0 = capped["window_s"][0].get<double>(), t1 = capped["window_s"][1].get<double>();
  std::printf("whole: %.9g to %.9g s; capped at 400 events: whole from %.9g to %.9g s\n",
              whole["window_s"][0].get<double>(), whole["window_s"][1].get<double>(), t0, t1);
  EXPECT_LT(t1, whole["window_s"][1].get<double>());
  EXPECT_GT(t1, t0);
  EXPECT_EQ(capped["requested_window_s"], whole["window_s"]);
  EXPECT_FALSE(whole.contains("requested_window_s"));
  EXPECT_GT(capped["perfetto"]["counters_dropped"].get<int>(), 0);
  EXPECT_TRUE(r.output.find("it holds every event from") != std::string::npos) << r.output;
  const auto events_before = [&](const fs::path& file) {
    std::multiset<std::string> out;
    const json trace = json::parse(read_file(file));
    for (const auto& e : trace["traceEvents"])
      if (e["ph"] != "M" && e["ph"] != "C" && e["ts"].get<double>() < t1 * 1e6)
        out.insert(e.dump());
    return out;
  };
  const auto expected = events_before(whole_dir / "trace.json");
  EXPECT_GT(expected.size(), 50u);
  EXPECT_EQ(events_before(capped_dir / "trace.json"), expected);
  fs::remove_all(whole_dir);
  fs::remove_all(capped_dir);
}

TEST(TraceOptions, AFileTooLargeToOpenIsSaidWithWhatKeepsLess) {
  // stats.json gives each trace file's size.
  const fs::path dir = scratch_dir("trace-bytes");
  const auto r = run_rtsim(kRun + "--trace perfetto,vcd -q --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  json stats = json::parse(read_file(dir / "stats.json"));
  EXPECT_EQ(stats["trace"]["perfetto"]["bytes"].get<std::uintmax_t>(),
            fs::file_size(dir / "trace.json"));
  EXPECT_EQ(stats["trace"]["vcd"]["bytes"].get<std::uintmax_t>(), fs::file_size(dir / "trace.vcd"));
  EXPECT_TRUE(rtsim::app::trace_warnings(stats).empty());
  // The README's 512 x 512 grid example wrote 544 MB of trace.json.
  stats["trace"]["perfetto"]["bytes"] = 544'000'000;
  const auto warnings = rtsim::app::trace_warnings(stats);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("trace.json is 544 MB, more than the 200 MB Perfetto's UI opens"),
            std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[0].find("--trace-window T0,T1"), std::string::npos);
  EXPECT_NE(warnings[0].find("--trace-modules PATTERN"), std::string::npos);
  fs::remove_all(dir);
}

TEST(TraceOptions, PatternsThatMatchNoModuleAreReported) {
  const fs::path dir = scratch_dir("trace-nomatch");
  const auto r =
      run_rtsim(kRun + "--trace vcd --trace-modules 'pert*,host' -q --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("--trace-modules pert* matched no module"), std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("--trace-modules host"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

TEST(TraceOptions, BadValuesAreBadInputAndWriteNothing) {
  const std::vector<std::string> bad = {
      "--trace vcd --trace-window 1ms",               // one time
      "--trace vcd --trace-window '1 ms,2 ms,3 ms'",  // three
      "--trace vcd --trace-window 'soon,2 ms'",       // not a time
      "--trace vcd --trace-window '2 ms,1 ms'",       // reversed
      "--trace vcd --trace-window '1 ms,1 ms'",       // empty
      "--trace vcd --trace-window '-1 ms,1 ms'",      // negative
      "--trace vcd --trace-window '0.5 ps,1 ms'",     // finer than the resolution
      "--trace vcd --trace-modules 'peripheral.[ab'",
      "--trace vcd --trace-modules ''",
      "--trace vcd --trace-max-events -1",
      "--trace vcd --trace-max-events lots",
      "--trace-window '1 ms,2 ms'",  // nothing to narrow
      "--trace-max-events 10",
  };
  for (const auto& args : bad) {
    const fs::path dir = scratch_dir("trace-bad");
    const auto r = run_rtsim(kRun + args + " -q --out " + dir.string());
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("trace"), std::string::npos) << args << ": names the flag\n"
                                                         << r.output;
    EXPECT_FALSE(fs::exists(dir)) << args;
  }
  // Plain seconds and spaces around the comma are fine.
  const fs::path dir = scratch_dir("trace-seconds");
  const auto r =
      run_rtsim(kRun + "--trace vcd --trace-window '0.01, 0.02' -q --out " + dir.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  fs::remove_all(dir);
}
