// Module-owned statistics (modules/statistics.hpp) and the directory that writes stats.json's
// `modules` from them (modules/stat_directory.hpp): each kind's value and key, the order of a
// module's keys, groups of one name merged, child groups, the traces' signals, and groups
// leaving the directory when they are destroyed. Plain arithmetic on sc_time, no simulation.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <systemc>
#include <vector>

#include "modules/stat_classes.hpp"
#include "modules/stat_directory.hpp"
#include "modules/statistics.hpp"
#include "modules/timed_fifo.hpp"

extern "C" int sc_main(int, char*[]) { return 0; }

using namespace rtsim::modules;
using sc_core::sc_time;

namespace {
sc_time ps(std::uint64_t v) { return sc_time::from_value(v); }
const StatWindow kFrame{ps(100), ps(1100)};

nlohmann::ordered_json modules_json() { return StatDirectory::instance().to_json(kFrame); }

struct Unit : StatGroup {
  using StatGroup::StatGroup;
  Busy busy{*this};
  Counter jobs{*this, "jobs", "jobs"};
  Peak peak{*this, "in_flight_peak", "in flight"};
  Duration waited{*this, "waited_s", "waited"};
  Scalar ratio{*this, "ratio", "a ratio", rtsim::modules::StatUnit::ratio};
  CounterArray by_kind{*this, "sent_", {"a", "b"}, "by kind"};
  Computed stages{*this, "stages", rtsim::modules::StatUnit::count, "depth", [] { return 11; }};
  Counter bits{*this, "bits", "bits carried", rtsim::modules::StatUnit::bits};
  Distribution latency{*this, "latency_s", "per job"};
};
}  // namespace

TEST(Statistics, EachKindWritesItsValueUnderItsName) {
  Unit u("unit");
  u.busy.record(ps(100), ps(400));
  ++u.jobs;
  u.jobs += 2;
  u.peak.note(5);
  u.peak.note(3);
  u.waited += ps(250);
  u.ratio = 0.25;
  u.by_kind.add(1, 7);
  u.latency.add(ps(10));
  const auto j = modules_json();
  ASSERT_TRUE(j.contains("unit")) << j.dump();
  const auto& m = j["unit"];
  EXPECT_DOUBLE_EQ(m["busy_s"].get<double>(), 400e-12);
  EXPECT_DOUBLE_EQ(m["utilization"].get<double>(), 0.4);
  EXPECT_EQ(m["jobs"].get<std::uint64_t>(), 3u);
  EXPECT_EQ(m["in_flight_peak"].get<std::uint64_t>(), 5u);
  EXPECT_DOUBLE_EQ(m["waited_s"].get<double>(), 250e-12);
  EXPECT_DOUBLE_EQ(m["ratio"].get<double>(), 0.25);
  EXPECT_EQ(m["sent_a"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(m["sent_b"].get<std::uint64_t>(), 7u);
  EXPECT_EQ(m["stages"].get<int>(), 11);
  EXPECT_EQ(m["latency_s"]["count"].get<int>(), 1);
  EXPECT_EQ(m["utilization_windows"]["values"].size(), 100u);
  EXPECT_DOUBLE_EQ(m["utilization_windows"]["begin_s"].get<double>(), 100e-12);
  // The order stats.json has always had: busy_s, utilization, the values by name, the windows.
  std::vector<std::string> keys;
  for (const auto& [k, v] : m.items()) keys.push_back(k);
  const std::vector<std::string> expected = {
      "busy_s", "utilization", "bits",   "in_flight_peak", "jobs",     "latency_s",
      "ratio",  "sent_a",      "sent_b", "stages",         "waited_s", "utilization_windows"};
  EXPECT_EQ(keys, expected);
}

TEST(Statistics, EachKindDeclaresTheUnitOfWhatItWrites) {
  using rtsim::modules::StatUnit;
  Unit u("node12.link_e");
  u.busy.record(ps(100), ps(400));
  u.latency.add(ps(10));
  rtsim::modules::UnitSchema units;
  StatDirectory::instance().to_json(kFrame, &units);
  // Under the module's class: every node's link_e declares its keys once.
  const std::vector<std::pair<std::string, StatUnit>> expected = {
      {"busy_s", StatUnit::seconds},
      {"utilization", StatUnit::fraction},
      {"utilization_windows.values", StatUnit::fraction},
      {"utilization_windows.window_s", StatUnit::seconds},
      {"jobs", StatUnit::count},
      {"bits", StatUnit::bits},
      {"in_flight_peak", StatUnit::count},
      {"waited_s", StatUnit::seconds},
      {"ratio", StatUnit::ratio},
      {"sent_b", StatUnit::count},
      {"stages", StatUnit::count},
      {"latency_s.p99", StatUnit::seconds},
      {"latency_s.count", StatUnit::count},
      {"latency_s.histogram.counts", StatUnit::count}};
  for (const auto& [key, unit] : expected) {
    EXPECT_EQ(units.unit_of("modules.node3.link_e." + key), unit) << key;
    EXPECT_EQ(units.unit_of("module_classes.node*.link_e." + key + ".max"), unit) << key;
  }
  EXPECT_FALSE(units.unit_of("modules.node3.link_e.unknown").has_value());
}

TEST(Statistics, ManyStatisticsReportAsEachWouldAlone) {
  // 400 units hold 4,000 statistics: the directory reports them (their windows included) on two
  // threads (StatDirectory::reports), and each unit's report is what it reports alone, in its
  // order.
  std::vector<std::unique_ptr<Unit>> units;
  for (int k = 0; k < 400; ++k) {
    units.push_back(std::make_unique<Unit>("many" + std::to_string(k)));
    Unit& u = *units.back();
    for (int i = 0; i <= k % 7; ++i)
      u.busy.record(ps(100 + 37 * static_cast<std::uint64_t>(i * k % 29)), ps(11 + i));
    u.jobs += static_cast<std::uint64_t>(k);
  }
  const auto reports = StatDirectory::instance().reports(kFrame);
  for (const auto& u : units) {
    StatReport alone;
    for (const Statistic* s : u->statistics()) s->report(alone, kFrame);
    const StatReport& r = reports.at(u->stat_path());
    EXPECT_EQ(r.busy, alone.busy) << u->stat_path();
    EXPECT_EQ(r.windows, alone.windows) << u->stat_path();
    EXPECT_EQ(r.values, alone.values) << u->stat_path();
    EXPECT_EQ(r.units, alone.units) << u->stat_path();
  }
}

TEST(Statistics, AFailingReportIsTheFirstNamesWhateverThreadMetIt) {
  // Enough statistics for two threads; two names each hold two queues (Level statistics), which
  // cannot report under one name. The error names the first of them in name order, whether the
  // thread that met it was the first or the second, as one thread would: the two names side by
  // side, and far apart (the threads take the names a few at a time).
  std::vector<std::unique_ptr<Unit>> units;
  for (int k = 0; k < 300; ++k) units.push_back(std::make_unique<Unit>("fill" + std::to_string(k)));
  for (const char* first : {"clash_a", "clash_b"}) {
    SCOPED_TRACE(first);
    const std::string second = first == std::string("clash_a") ? "clash_b" : "zz_clash";
    StatGroup a(first), a2(first), b(second), b2(second);
    Level qa(a, 4), qa2(a2, 4), qb(b, 4), qb2(b2, 4);
    try {
      modules_json();
      ADD_FAILURE() << "two queues under one name reported";
    } catch (const std::logic_error& e) {
      EXPECT_EQ(std::string(e.what()),
                std::string(first) + ": two Level statistics report under one name (queue)");
    }
  }
}

TEST(Statistics, AGroupLeavesTheDirectoryWithItsObject) {
  {
    Unit u("short_lived");
    EXPECT_TRUE(modules_json().contains("short_lived"));
  }
  EXPECT_FALSE(modules_json().contains("short_lived"));
}

TEST(Statistics, GroupsOfOneNameAreOneModuleAndChildrenAreNamedUnderTheirParent) {
  StatGroup processor("pert0.shell");
  Counter rays(processor, "rays", "rays");
  StatGroup extra("pert0.shell");  // a subclass's counters, a second object: the same module
  Counter tests(extra, "box_tests", "tests");
  StatGroup bic(processor, "bic");
  Counter requests(bic, "requests", "requests");
  ++rays;
  ++requests;
  const auto j = modules_json();
  EXPECT_EQ(j["pert0.shell"]["rays"].get<int>(), 1);
  EXPECT_EQ(j["pert0.shell"]["box_tests"].get<int>(), 0);
  EXPECT_EQ(j["pert0.shell.bic"]["requests"].get<int>(), 1);
  // A group of counters only has no busy time to report.
  EXPECT_FALSE(j["pert0.shell.bic"].contains("busy_s"));
}

TEST(Statistics, TwoBusyTimesUnderOneNameAreAModellingError) {
  Unit a("twice"), b("twice");
  EXPECT_THROW(modules_json(), std::logic_error);
}

TEST(Statistics, AQueueReportsItsDepthWaitsAndMessages) {
  TimedFifo<int> q("host.queue", 2);
  TimedFifo<int> unbounded("node0.in_e", TimedFifo<int>::kUnbounded);
  // Without a simulation: puts into room only (a full FIFO would wait()).
  q.put(1, ps(100));
  q.put(2, ps(300));
  sc_time taken;
  q.get(ps(600), taken);
  const auto j = modules_json();
  const auto& m = j["host.queue"];
  EXPECT_FALSE(m.contains("busy_s"));
  EXPECT_EQ(m["messages"].get<int>(), 2);
  EXPECT_EQ(m["waits"].get<int>(), 0);
  EXPECT_EQ(m["queue"]["capacity"].get<int>(), 2);
  EXPECT_EQ(m["queue"]["max_occupancy"].get<int>(), 2);
  // 1 entry over [100, 300), 2 over [300, 600), 1 over [600, 1100): 2000 / 1000.
  EXPECT_DOUBLE_EQ(m["queue"]["mean_occupancy"].get<double>(),
                   1.0 * 200 / 1000 + 2.0 * 300 / 1000 + 1.0 * 500 / 1000);
  EXPECT_TRUE(j["node0.in_e"]["queue"]["capacity"].is_null());
}

TEST(Statistics, SignalsComeByNameBusyThenDepthThenTheOthers) {
  BusyTimeline::KeepIntervals keep;  // busy signals need the intervals
  StatGroup ring("ring");
  LevelSignal holder(ring, "holder", "who transmits");
  Level depth(ring, 4);
  Busy busy(ring);
  busy.record(ps(0), ps(10));
  depth.put(ps(5));
  holder.change(5, 1);
  std::vector<std::string> kinds;
  for (const NamedSignal& s :
       StatDirectory::instance().signals([](const std::string& n) { return n == "ring"; })) {
    EXPECT_EQ(s.name, "ring");  // only the names kept
    kinds.push_back(s.kind);
  }
  EXPECT_EQ(kinds, (std::vector<std::string>{"busy", "depth", "holder"}));
}

TEST(StatClasses, AnInstancesClassIsItsNameWithoutTrailingDigits) {
  EXPECT_EQ(instance_class("node12.link_e"), "node*.link_e");
  EXPECT_EQ(instance_class("pert3.shell.bic"), "pert*.shell.bic");
  EXPECT_EQ(instance_class("pert0.queue.shade_to_shell"), "pert*.queue.shade_to_shell");
  EXPECT_EQ(instance_class("host"), "host");
  EXPECT_EQ(instance_class("pipeline.split_u"), "pipeline.split_u");
  EXPECT_EQ(instance_class("x.0"), "x.0");  // a part of digits only names no instance
  EXPECT_EQ(instance_class(""), "");
}

TEST(StatClasses, AClassGivesMinMeanMaxSumAndItsBusiestInstance) {
  const auto modules = nlohmann::ordered_json::parse(R"({
      "host": {"busy_s": 1.0, "utilization": 0.5},
      "node0": {"busy_s": 0.2, "utilization": 0.1, "sent_vision": 3,
                "utilization_windows": {"begin_s": 0, "window_s": 1, "values": [0.1]}},
      "node1": {"busy_s": 0.8, "utilization": 0.4, "sent_vision": 5},
      "node2": {"busy_s": 0.8, "utilization": 0.4},
      "node0.in_e": {"queue": {"capacity": null, "mean_occupancy": 0.5, "max_occupancy": 2}},
      "node1.in_e": {"queue": {"capacity": null, "mean_occupancy": 1.5, "max_occupancy": 4}}})");
  const auto c = class_aggregates(modules);
  EXPECT_FALSE(c.contains("host"));  // one instance: no class
  const auto& node = c["node*"];
  EXPECT_EQ(node["instances"].get<int>(), 3);
  EXPECT_DOUBLE_EQ(node["utilization"]["min"].get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(node["utilization"]["mean"].get<double>(), 0.3);
  EXPECT_DOUBLE_EQ(node["utilization"]["max"].get<double>(), 0.4);
  EXPECT_DOUBLE_EQ(node["utilization"]["sum"].get<double>(), 0.9);
  EXPECT_EQ(node["utilization"]["max_instance"], "node1");  // ties: the first by name
  EXPECT_EQ(node["sent_vision"]["instances_reporting"].get<int>(), 2);
  EXPECT_DOUBLE_EQ(node["sent_vision"]["mean"].get<double>(), 4.0);
  EXPECT_FALSE(node.contains("utilization_windows.begin_s"));
  const auto& in = c["node*.in_e"];
  EXPECT_DOUBLE_EQ(in["queue.mean_occupancy"]["mean"].get<double>(), 1.0);
  EXPECT_EQ(in["queue.max_occupancy"]["max_instance"], "node1.in_e");
  EXPECT_FALSE(in.contains("queue.capacity"));  // null: not a number
}
