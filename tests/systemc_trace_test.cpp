// Trace writers: the Perfetto/Chrome JSON trace (tracks, metadata, times, arguments, dropped
// events, escaping, determinism, streaming) and the VCD signal trace (header, scopes, $var
// lines, value changes at the simulated times, windows, the cap). Scenarios that call sc_start run
// in a forked child (one SystemC simulation per process, tests/systemc_test_support.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <systemc>
#include <vector>

#include "modules/trace/perfetto_trace.hpp"
#include "modules/trace/vcd_trace.hpp"
#include "systemc_test_support.hpp"
#include "test_support.hpp"

int sc_main(int, char*[]) { return 0; }

namespace rtsim::modules {
namespace {

using nlohmann::json;
using rtsim::test::read_file;
using rtsim::test::run_in_child;
using rtsim::test::scratch_dir;

std::filesystem::path fresh_dir(const std::string& name) {
  auto dir = scratch_dir(name);
  std::filesystem::create_directories(dir);
  return dir;
}

json parse_trace(const std::filesystem::path& p) {
  const std::string text = read_file(p);
  EXPECT_FALSE(text.empty()) << p;
  return json::parse(text);  // throws (fails the test) on malformed JSON
}

/// Events of one phase.
std::vector<json> events_of(const json& trace, const std::string& phase) {
  std::vector<json> out;
  for (const auto& e : trace.at("traceEvents")) {
    if (e.at("ph") == phase) out.push_back(e);
  }
  return out;
}

/// The metadata event `what` for (pid, tid), or null.
json metadata(const json& trace, const std::string& what, int pid, int tid) {
  for (const auto& e : trace.at("traceEvents")) {
    if (e.at("ph") == "M" && e.at("name") == what && e.at("pid") == pid && e.at("tid") == tid) {
      return e;
    }
  }
  return nullptr;
}

// --- time formatting ---------------------------------------------------------------------------

TEST(PerfettoTrace, TimesAreMicrosecondsWithPicosecondDigits) {
  EXPECT_EQ(perfetto_us_from_seconds(0.0), "0.000000");
  EXPECT_EQ(perfetto_us_from_seconds(-0.0), "0.000000");
  EXPECT_EQ(perfetto_us_from_seconds(1.5e-6), "1.500000");
  EXPECT_EQ(perfetto_us_from_seconds(1e-12), "0.000001");  // one picosecond
  EXPECT_EQ(perfetto_us_from_seconds(2.5e-9), "0.002500");
  EXPECT_EQ(perfetto_us_from_seconds(87.4), "87400000.000000");
  EXPECT_THROW(perfetto_us_from_seconds(-1e-9), std::invalid_argument);
  EXPECT_THROW(perfetto_us_from_seconds(std::nan("")), std::invalid_argument);
  EXPECT_THROW(perfetto_us_from_seconds(std::numeric_limits<double>::infinity()),
               std::invalid_argument);
  // Integer picoseconds are exact at any magnitude (here ~5 hours).
  EXPECT_EQ(perfetto_us_from_ps(0), "0.000000");
  EXPECT_EQ(perfetto_us_from_ps(1), "0.000001");
  EXPECT_EQ(perfetto_us_from_ps(1'234'567), "1.234567");
  EXPECT_EQ(perfetto_us_from_ps(18'000'000'000'000'001ull), "18000000000.000001");
}

TEST(PerfettoTrace, JsonStringsAreEscapedAndValidUtf8) {
  EXPECT_EQ(perfetto_json_string("plain"), "\"plain\"");
  EXPECT_EQ(perfetto_json_string("a\"b\\c\nd\te\x01"), "\"a\\\"b\\\\c\\nd\\te\\u0001\"");
  EXPECT_EQ(perfetto_json_string("\xC2\xB5s"), "\"\xC2\xB5s\"");      // "µs" kept
  EXPECT_EQ(perfetto_json_string("x\xFFy"), "\"x\\ufffdy\"");         // invalid byte
  EXPECT_EQ(perfetto_json_string("\xE2\x82"), "\"\\ufffd\\ufffd\"");  // truncated sequence
  EXPECT_EQ(perfetto_json_string("\xED\xA0\x80"), "\"\\ufffd\\ufffd\\ufffd\"");  // surrogate
  // Whatever the bytes, nlohmann parses the result back.
  std::string all;
  for (int c = 0; c < 256; ++c) all += static_cast<char>(c);
  EXPECT_TRUE(json::accept(perfetto_json_string(all)));
}

// --- the JSON trace
// --------------------------------------------------------------------------------

TEST(PerfettoTrace, ModuleHierarchyBecomesProcessesAndThreads) {
  const auto dir = fresh_dir("perfetto-tracks");
  const auto path = dir / "trace.json";
  {
    PerfettoTrace trace(path, 100);
    const int pipeline = trace.track("peripheral.pipeline");
    const int memory = trace.track("peripheral.memory.bank0");
    const int host = trace.track("host");
    EXPECT_EQ(pipeline, 0);
    EXPECT_EQ(memory, 1);
    EXPECT_EQ(host, 2);
    EXPECT_EQ(trace.track("peripheral.pipeline"), pipeline);  // idempotent
    EXPECT_EQ(trace.track("host"), host);
    EXPECT_EQ(trace.track_count(), 3u);
    EXPECT_THROW(trace.track(""), std::invalid_argument);
    EXPECT_THROW(trace.track(".x"), std::invalid_argument);
    // Before close the trace is only the partial file.
    EXPECT_TRUE(std::filesystem::exists(dir / "trace.json.partial"));
    EXPECT_FALSE(std::filesystem::exists(path));
  }  // the destructor closes
  EXPECT_FALSE(std::filesystem::exists(dir / "trace.json.partial"));
  const json t = parse_trace(path);
  EXPECT_EQ(t.at("displayTimeUnit"), "ns");
  // Two processes, three threads; process of the peripheral tracks shared.
  std::map<std::string, int> pid_of_process;
  std::map<std::string, std::pair<int, int>> thread;
  for (const auto& e : events_of(t, "M")) {
    if (e.at("name") == "process_name") pid_of_process[e["args"]["name"]] = e["pid"];
    if (e.at("name") == "thread_name") thread[e["args"]["name"]] = {e["pid"], e["tid"]};
  }
  ASSERT_EQ(pid_of_process.size(), 2u);
  ASSERT_EQ(thread.size(), 3u);
  const int peripheral = pid_of_process.at("peripheral");
  EXPECT_EQ(thread.at("peripheral.pipeline").first, peripheral);
  EXPECT_EQ(thread.at("peripheral.memory.bank0").first, peripheral);
  EXPECT_EQ(thread.at("host").first, pid_of_process.at("host"));
  // No tid equals a pid (a viewer would take it for the process's main thread); all distinct.
  std::set<int> ids;
  for (const auto& [name, pid] : pid_of_process) ids.insert(pid);
  for (const auto& [name, pt] : thread) ids.insert(pt.second);
  EXPECT_EQ(ids.size(), 5u);
  // Sort indices keep the creation order.
  for (const auto& [name, pt] : thread) {
    const json s = metadata(t, "thread_sort_index", pt.first, pt.second);
    ASSERT_FALSE(s.is_null()) << name;
    EXPECT_EQ(s["args"]["sort_index"], pt.second);
  }
  EXPECT_FALSE(metadata(t, "process_sort_index", peripheral, 0).is_null());
  EXPECT_EQ(t["otherData"]["rtsim_events_written"], 0);
  EXPECT_EQ(t["otherData"]["rtsim_events_dropped"], 0);
}

TEST(PerfettoTrace, NumberedModulesSortInNumberOrderWhateverTheirCreationOrder) {
  // gaudet-pert's PERTs: created pert0, pert11, pert10, ..., they read pert0, pert1, ..., pert11,
  // each stem where it first appeared (the buses after the PERTs).
  const auto dir = fresh_dir("perfetto-order");
  const auto path = dir / "trace.json";
  {
    PerfettoTrace trace(path, 100);
    for (const char* name : {"pert0.shade", "pert11.shade", "pert2.shade", "pert10.shell",
                             "shell_bus", "pert1.prim", "prim_bus"})
      trace.track(name);
  }
  const json t = parse_trace(path);
  std::map<int, std::string> process_by_sort_index;
  std::map<int, int> sort_index_of_pid;
  for (const auto& e : events_of(t, "M"))
    if (e.at("name") == "process_sort_index") sort_index_of_pid[e["pid"]] = e["args"]["sort_index"];
  for (const auto& e : events_of(t, "M"))
    if (e.at("name") == "process_name")
      process_by_sort_index[sort_index_of_pid.at(e["pid"])] = e["args"]["name"];
  std::vector<std::string> order;
  for (const auto& [index, name] : process_by_sort_index) order.push_back(name);
  EXPECT_EQ(order, (std::vector<std::string>{"pert0", "pert1", "pert2", "pert10", "pert11",
                                             "shell_bus", "prim_bus"}));
}

TEST(PerfettoTrace, SlicesInstantsAndCountersCarryTheirTimes) {
  const auto dir = fresh_dir("perfetto-events");
  const auto path = dir / "trace.json";
  PerfettoTrace trace(path, 100);
  const int pipe = trace.track("peripheral.pipeline");
  const int queue = trace.track("peripheral.queue");
  trace.slice(pipe, "ray 17", 1.5e-6, 1000 / 3.0 * 1e-6, {{"ray", 17}, {"polygons", 1000}});
  trace.slice(pipe, "ray 18", 1e-12, 2.5e-9);  // picosecond start
  trace.slice(pipe, "early", 0.5e-6, 1e-6);    // out of time order: allowed
  trace.instant(pipe, "hit", 2e-6);
  trace.counter(queue, "depth", 3e-6, 4);
  trace.counter(queue, "depth", 4e-6, 0.5);
  // sc_time overloads are exact in picoseconds.
  trace.slice(pipe, "sc", sc_core::sc_time(1'234'567, sc_core::SC_PS),
              sc_core::sc_time(400, sc_core::SC_NS), {{"n", 2}});
  trace.instant(pipe, "sc-hit", sc_core::sc_time(7, sc_core::SC_PS));
  trace.counter(queue, "depth", sc_core::sc_time(5, sc_core::SC_US), 1);
  EXPECT_EQ(trace.events_written(), 9u);
  trace.close();
  trace.close();  // idempotent
  EXPECT_FALSE(trace.is_open());

  const std::string text = read_file(path);
  // Times as written (microseconds, six decimals).
  EXPECT_NE(text.find("\"ts\":1.500000,"), std::string::npos);
  EXPECT_NE(text.find("\"dur\":333.333333,"), std::string::npos);
  EXPECT_NE(text.find("\"ts\":0.000001,"), std::string::npos);
  EXPECT_NE(text.find("\"dur\":0.002500"), std::string::npos);
  EXPECT_NE(text.find("\"ts\":1.234567,"), std::string::npos);
  EXPECT_NE(text.find("\"dur\":0.400000,"), std::string::npos);
  EXPECT_NE(text.find("\"ts\":0.000007,"), std::string::npos);

  const json t = json::parse(text);
  const auto slices = events_of(t, "X");
  ASSERT_EQ(slices.size(), 4u);
  EXPECT_EQ(slices[0]["name"], "ray 17");
  EXPECT_DOUBLE_EQ(slices[0]["ts"].get<double>(), 1.5);
  EXPECT_NEAR(slices[0]["dur"].get<double>(), 1000 / 3.0, 1e-6);
  EXPECT_EQ(slices[0]["args"]["ray"], 17);
  EXPECT_EQ(slices[0]["args"]["polygons"], 1000);
  EXPECT_FALSE(slices[1].contains("args"));
  EXPECT_DOUBLE_EQ(slices[2]["ts"].get<double>(), 0.5);
  EXPECT_EQ(slices[3]["args"]["n"], 2);
  const auto instants = events_of(t, "i");
  ASSERT_EQ(instants.size(), 2u);
  EXPECT_EQ(instants[0]["name"], "hit");
  EXPECT_EQ(instants[0]["s"], "t");
  EXPECT_DOUBLE_EQ(instants[0]["ts"].get<double>(), 2.0);
  const auto counters = events_of(t, "C");
  ASSERT_EQ(counters.size(), 3u);
  EXPECT_EQ(counters[0]["name"], "peripheral.queue.depth");
  EXPECT_EQ(counters[0]["args"]["value"], 4);
  EXPECT_DOUBLE_EQ(counters[1]["args"]["value"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(counters[2]["ts"].get<double>(), 5.0);
  // Every event sits on its track's pid/tid.
  const json thread = metadata(t, "thread_name", slices[0]["pid"], slices[0]["tid"]);
  ASSERT_FALSE(thread.is_null());
  EXPECT_EQ(thread["args"]["name"], "peripheral.pipeline");
  EXPECT_EQ(metadata(t, "thread_name", counters[0]["pid"], counters[0]["tid"])["args"]["name"],
            "peripheral.queue");
}

TEST(PerfettoTrace, EventsBeyondTheLimitAreDroppedAndCounted) {
  const auto dir = fresh_dir("perfetto-drop");
  const auto path = dir / "trace.json";
  PerfettoTrace trace(path, 3);
  const int a = trace.track("a.x");
  for (int i = 0; i < 5; ++i) trace.slice(a, "s", i * 1e-6, 1e-6);
  trace.instant(a, "i", 0.0);
  const int b = trace.track("b");  // metadata is never dropped
  trace.counter(b, "c", 0.0, 1.0);
  EXPECT_EQ(trace.events_written(), 3u);
  EXPECT_EQ(trace.events_dropped(), 4u);
  trace.close();
  const json t = parse_trace(path);
  EXPECT_EQ(events_of(t, "X").size(), 3u);
  EXPECT_EQ(events_of(t, "i").size(), 0u);
  EXPECT_EQ(events_of(t, "C").size(), 0u);
  EXPECT_EQ(events_of(t, "M").size(), 8u);  // 2 processes x 2 + 2 threads x 2
  EXPECT_EQ(t["otherData"]["rtsim_events_written"], 3);
  EXPECT_EQ(t["otherData"]["rtsim_events_dropped"], 4);
  EXPECT_EQ(t["otherData"]["rtsim_max_events"], 3);
}

TEST(PerfettoTrace, NoLimitByDefaultAndOtherDataCarriesTheRunsKeys) {
  const auto dir = fresh_dir("perfetto-all");
  const auto path = dir / "trace.json";
  PerfettoTrace trace(path, 0);  // 0: every event
  const int a = trace.track("a");
  for (int i = 0; i < 10'000; ++i) trace.slice(a, "s", i * 1e-6, 1e-6);
  trace.other_data("rtsim_window_s", "[0,1]");
  trace.close();
  EXPECT_EQ(trace.events_written(), 10'000u);
  EXPECT_EQ(trace.events_dropped(), 0u);
  const json t = parse_trace(path);
  EXPECT_EQ(events_of(t, "X").size(), 10'000u);
  EXPECT_EQ(t["otherData"]["rtsim_max_events"], 0);
  EXPECT_EQ(t["otherData"]["rtsim_window_s"], json::array({0, 1}));
}

TEST(PerfettoTrace, ItSaysOnceWhileWritingThatItHasPassedASize) {
  // rtsim run warns while the run goes on that a trace will be too large to open (on_size);
  // and a cap's first dropped event bounds the window the file holds whole.
  const auto dir = fresh_dir("perfetto-size");
  PerfettoTrace trace(dir / "trace.json", 9'000);
  std::vector<std::uint64_t> told;
  trace.on_size(100'000, [&](std::uint64_t bytes) { told.push_back(bytes); });
  const int a = trace.track("a");
  for (int i = 0; i < 10'000; ++i) trace.slice(a, "s", i * 1e-6, 1e-6);
  ASSERT_EQ(told.size(), 1u);
  EXPECT_GT(told[0], 100'000u);
  EXPECT_LT(told[0], 100'000u + 4096u * 200u);  // checked every 4096 events
  EXPECT_DOUBLE_EQ(trace.first_dropped_s(), 9'000e-6);
  trace.close();
  EXPECT_EQ(told.size(), 1u);
}

TEST(PerfettoTrace, NamesAreEscaped) {
  const auto dir = fresh_dir("perfetto-escape");
  const auto path = dir / "trace.json";
  const std::string odd = "say \"hi\"\\\n\t\x01 \xC2\xB5s \xFF";
  {
    PerfettoTrace trace(path, 10);
    const int tr = trace.track("top.\"quoted\" module");
    trace.slice(tr, odd, 0.0, 1e-6, {{"arg \"x\"", 1}});
  }
  const json t = parse_trace(path);
  const auto slices = events_of(t, "X");
  ASSERT_EQ(slices.size(), 1u);
  EXPECT_EQ(slices[0]["name"], "say \"hi\"\\\n\t\x01 \xC2\xB5s \xEF\xBF\xBD");
  EXPECT_EQ(slices[0]["args"]["arg \"x\""], 1);
  EXPECT_EQ(metadata(t, "thread_name", slices[0]["pid"], slices[0]["tid"])["args"]["name"],
            "top.\"quoted\" module");
}

TEST(PerfettoTrace, SameCallsGiveTheSameBytes) {
  const auto dir = fresh_dir("perfetto-determinism");
  auto write = [](const std::filesystem::path& p) {
    PerfettoTrace trace(p, 50);
    for (int i = 0; i < 40; ++i) {
      const int tr = trace.track(i % 3 == 0 ? "host" : "peripheral.unit" + std::to_string(i % 4));
      trace.slice(tr, "job " + std::to_string(i), 1e-7 * (40 - i), 3.3e-8 * i, {{"i", i}});
      trace.counter(tr, "q", 1e-7 * i, i % 5);
    }
  };
  write(dir / "a.json");
  write(dir / "b.json");
  const std::string a = read_file(dir / "a.json");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a, read_file(dir / "b.json"));
  EXPECT_TRUE(json::accept(a));
}

TEST(PerfettoTrace, EventsAreStreamedToDisk) {
  // 20,000 events of ~100 bytes: the partial file holds nearly all of them before close, so the
  // writer keeps only its stream buffer in memory (tolerance: one buffer, 64 KiB, unwritten).
  const auto dir = fresh_dir("perfetto-stream");
  PerfettoTrace trace(dir / "trace.json", 1'000'000);
  const int tr = trace.track("peripheral.pipeline");
  for (int i = 0; i < 20'000; ++i) trace.slice(tr, "ray", i * 1e-6, 1e-6, {{"ray", i}});
  const auto on_disk = std::filesystem::file_size(dir / "trace.json.partial");
  std::cout << "partial file before close: " << on_disk << " bytes\n";
  EXPECT_GT(on_disk, 20'000u * 80u - 65'536u);
  trace.close();
  EXPECT_EQ(parse_trace(dir / "trace.json")["traceEvents"].size(), 20'000u + 4u);  // + metadata
  std::filesystem::remove_all(dir);                                                // 2 MB
}

TEST(PerfettoTrace, MisuseIsReported) {
  const auto dir = fresh_dir("perfetto-misuse");
  PerfettoTrace trace(dir / "trace.json", 10);
  const int tr = trace.track("m");
  EXPECT_THROW(trace.slice(tr + 1, "x", 0.0, 1.0), std::out_of_range);
  EXPECT_THROW(trace.slice(-1, "x", 0.0, 1.0), std::out_of_range);
  EXPECT_THROW(trace.slice(tr, "x", 0.0, -1e-9), std::invalid_argument);
  EXPECT_THROW(trace.slice(tr, "x", std::nan(""), 1.0), std::invalid_argument);
  EXPECT_THROW(trace.slice(tr, "x", 0.0, 1.0, {{"a", std::nan("")}}), std::invalid_argument);
  EXPECT_THROW(trace.counter(tr, "x", 0.0, std::numeric_limits<double>::infinity()),
               std::invalid_argument);
  EXPECT_EQ(trace.events_written(), 0u);  // rejected calls write nothing
  trace.close();
  EXPECT_NO_THROW((void)parse_trace(dir / "trace.json"));
  EXPECT_THROW(PerfettoTrace(dir / "no-such-dir" / "t.json", 1), std::runtime_error);
}

TEST(PerfettoTrace, AbandonLeavesNoFile) {
  const auto dir = fresh_dir("perfetto-abandon");
  {
    PerfettoTrace trace(dir / "trace.json", 10);
    trace.slice(trace.track("m"), "x", 0.0, 1e-6);
    trace.abandon();
    trace.close();  // no-op after abandon
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

// --- traces from a running simulation --------------------------------------------------------

/// A unit that takes 2 jobs from a queue at 10 ns, 15 ns each, and traces them.
struct Unit : sc_core::sc_module {
  PerfettoTrace* trace = nullptr;
  int track = -1;
  SC_HAS_PROCESS(Unit);
  explicit Unit(sc_core::sc_module_name name) : sc_core::sc_module(name) { SC_THREAD(run); }
  void run() {
    using sc_core::SC_NS;
    using sc_core::sc_time;
    // t = 10 ns: 2 jobs arrive; each takes 15 ns; idle from 40 ns.
    wait(sc_time(10, SC_NS));
    for (int job = 0; job < 2; ++job) {
      const sc_time start = sc_core::sc_time_stamp();
      if (trace) trace->counter(track, "depth", start, 2 - job);
      wait(sc_time(15, SC_NS));
      if (trace) trace->slice(track, "job", start, sc_time(15, SC_NS), {{"job", job}});
    }
    if (trace) trace->counter(track, "depth", sc_core::sc_time_stamp(), 0);
  }
};

// --- VCD --------------------------------------------------------------------------------------

/// The value changes after $enddefinitions, by time stamp (ps), and the time stamps in order.
struct VcdDump {
  std::map<long long, std::vector<std::string>> changes;
  std::vector<long long> stamps;
};

VcdDump parse_vcd(const std::string& vcd) {
  VcdDump d;
  long long now = -1;
  std::istringstream lines(vcd.substr(vcd.find("$enddefinitions")));
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && line[0] == '#') {
      now = std::stoll(line.substr(1));
      d.stamps.push_back(now);
      d.changes[now];
    } else if (now >= 0 && !line.empty() && line[0] != '$') {
      d.changes[now].push_back(line);
    }
  }
  return d;
}

/// A unit busy over [10, 25) and [25, 40) ns (back to back: one rise, one fall) whose queue holds
/// 2, then 1, then 0 entries.
void add_unit_signals(VcdTrace& vcd) {
  vcd.signal("top.unit.busy", {{10'000, 1}, {40'000, 0}});
  vcd.signal("top.unit.queue.depth", {{10'000, 2}, {25'000, 1}, {40'000, 0}},
             VcdTrace::Kind::kCount);
}

TEST(VcdTrace, HasHeaderScopesAndValueChangesAtSimulatedTimes) {
  const auto dir = fresh_dir("vcd");
  const auto path = dir / "signals.vcd";
  {
    VcdTrace vcd(path);
    add_unit_signals(vcd);
    EXPECT_FALSE(std::filesystem::exists(path)) << "written at close()";
    vcd.close(0, 50'000);
    vcd.close(0, 60'000);  // idempotent
    EXPECT_EQ(vcd.changes_written(), 5u);
    EXPECT_EQ(vcd.changes_dropped(), 0u);
  }
  const std::string vcd = read_file(path);
  ASSERT_FALSE(vcd.empty());
  EXPECT_TRUE(std::regex_search(vcd, std::regex(R"(\$timescale 1 ps \$end)")));
  // The dotted names became scopes top / unit / queue.
  EXPECT_NE(vcd.find("$scope module top $end\n$scope module unit $end\n$var wire 1 ! busy $end\n"
                     "$scope module queue $end\n$var integer 32 \" depth $end\n$upscope $end\n"
                     "$upscope $end\n$upscope $end\n$enddefinitions $end\n"),
            std::string::npos)
      << vcd;
  EXPECT_NE(vcd.find("#0\n$dumpvars\n0!\nb0 \"\n$end\n"), std::string::npos) << vcd;
  const VcdDump d = parse_vcd(vcd);
  EXPECT_EQ(d.stamps, (std::vector<long long>{0, 10'000, 25'000, 40'000, 50'000}));
  EXPECT_EQ(d.changes.at(10'000), (std::vector<std::string>{"1!", "b10 \""}));
  EXPECT_EQ(d.changes.at(25'000), (std::vector<std::string>{"b1 \""}));
  EXPECT_EQ(d.changes.at(40'000), (std::vector<std::string>{"0!", "b0 \""}));
  EXPECT_TRUE(d.changes.at(50'000).empty()) << "the end of the dump, values held to there";
}

TEST(VcdTrace, WindowStartsWithTheValuesThenAndCapDropsAndCounts) {
  const auto dir = fresh_dir("vcd-window");
  {
    VcdTrace vcd(dir / "w.vcd");
    add_unit_signals(vcd);
    vcd.close(20'000, 30'000);
    EXPECT_EQ(vcd.changes_written(), 1u);  // depth 1 at 25 ns
  }
  std::string text = read_file(dir / "w.vcd");
  EXPECT_NE(text.find("#20000\n$dumpvars\n1!\nb10 \"\n$end\n"), std::string::npos) << text;
  VcdDump d = parse_vcd(text);
  EXPECT_EQ(d.stamps, (std::vector<long long>{20'000, 25'000, 30'000}));
  {
    VcdTrace vcd(dir / "cap.vcd");
    add_unit_signals(vcd);
    vcd.close(0, 50'000, 3);
    EXPECT_EQ(vcd.changes_written(), 3u);
    EXPECT_EQ(vcd.changes_dropped(), 2u);
  }
  d = parse_vcd(read_file(dir / "cap.vcd"));
  EXPECT_EQ(d.stamps, (std::vector<long long>{0, 10'000, 25'000}))
      << "a dump cut short ends at its last change";
}

TEST(VcdTrace, LevelsAbove1AreIntegersAndIdentifiersArePrintable) {
  const auto dir = fresh_dir("vcd-int");
  {
    VcdTrace vcd(dir / "i.vcd");
    vcd.signal("a.busy", {{5, 2}, {7, 0}});  // overlapping intervals
    vcd.close(0, 10);
  }
  EXPECT_NE(read_file(dir / "i.vcd").find("$var integer 32 ! busy $end"), std::string::npos);
  EXPECT_EQ(vcd_identifier(0), "!");
  EXPECT_EQ(vcd_identifier(93), "~");
  EXPECT_EQ(vcd_identifier(94), "!\"");
  std::set<std::string> ids;
  for (std::size_t i = 0; i < 20'000; ++i) {
    const std::string id = vcd_identifier(i);
    for (char c : id) EXPECT_TRUE(c >= '!' && c <= '~');
    ids.insert(id);
  }
  EXPECT_EQ(ids.size(), 20'000u);
}

TEST(VcdTrace, MisuseIsReportedAndAbandonLeavesNoFile) {
  const auto dir = fresh_dir("vcd-misuse");
  VcdTrace vcd(dir / "m.vcd");
  EXPECT_THROW(vcd.signal("a..busy", {}), std::invalid_argument);
  EXPECT_THROW(vcd.signal("", {}), std::invalid_argument);
  EXPECT_THROW(vcd.signal("a.busy", {{5, 1}, {4, 0}}), std::invalid_argument);
  vcd.signal("a.busy", {});
  EXPECT_THROW(vcd.signal("a.busy", {}), std::invalid_argument);
  vcd.abandon();
  vcd.close(0, 1);  // no-op after abandon
  EXPECT_TRUE(std::filesystem::is_empty(dir));
  {
    VcdTrace unclosed(dir / "u.vcd");
    unclosed.signal("a.busy", {{1, 1}});
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir)) << "a trace never closed is no file";
}

TEST(SystemCTrace, PerfettoSlicesFromARunningSimulation) {
  const auto dir = fresh_dir("perfetto-sim");
  const auto path = dir / "trace.json";
  ASSERT_EQ(run_in_child([&] {
              PerfettoTrace trace(path, 100);
              Unit unit("peripheral");
              unit.trace = &trace;
              unit.track = trace.track(unit.name());
              sc_core::sc_start();
              trace.close();
              return 0;
            }),
            0);
  const json t = parse_trace(path);
  const auto slices = events_of(t, "X");
  ASSERT_EQ(slices.size(), 2u);
  EXPECT_DOUBLE_EQ(slices[0]["ts"].get<double>(), 0.010);
  EXPECT_DOUBLE_EQ(slices[0]["dur"].get<double>(), 0.015);
  EXPECT_DOUBLE_EQ(slices[1]["ts"].get<double>(), 0.025);
  EXPECT_EQ(slices[1]["args"]["job"], 1);
  const auto counters = events_of(t, "C");
  ASSERT_EQ(counters.size(), 3u);
  EXPECT_EQ(counters[0]["name"], "peripheral.depth");
  EXPECT_DOUBLE_EQ(counters[2]["ts"].get<double>(), 0.040);
  EXPECT_EQ(counters[2]["args"]["value"], 0);
}

TEST(SystemCTrace, RunInChildReportsFailures) {
  EXPECT_EQ(run_in_child([] { return 7; }), 7);
  EXPECT_EQ(run_in_child([]() -> int { throw std::runtime_error("boom"); }), 2);
}

}  // namespace
}  // namespace rtsim::modules
