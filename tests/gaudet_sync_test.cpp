// gaudet-pert's processors wait for simulated time only where they interact (pert.sync =
// interactions, the default) and the machine's answers are those of threads that wait after
// every computation (pert.sync = computations): every statistic, the frame time and the image,
// on the runs below, which between them meet both rules that make this hold:
//  * a strobe still matches a request withdrawn at its very time (bus_interface.hpp): balls-s2
//    at 8 PERTs has a PrimProcessor withdraw a request at the time of its strobe;
//  * a message goes into the next queue as its sender begins writing it (pert_processor.hpp,
//    WritingAhead): teapot-s2 at 8 PERTs has a ShadeProcessor look at its queue at the very
//    time an answer arrives.
// Without either rule some of these runs differ (a packet captured or not, an answer taken at
// once or after other work); so does a run whose processor skips a settle() before it touches
// its port or queues.
// Likewise the Broadcast Processors, which wake only at the strobes they plan
// (broadcast.wakes = needed), give the answers of buses that wake at every change.
// And the programs of the processors and the buses on the machine's event queue (process =
// queue) give the answers of programs that SystemC runs in a method each.
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using nlohmann::ordered_json;
using rtsim::test::read_file;
using rtsim::test::read_json;
using rtsim::test::run_ok;

namespace {

/// stats.json without what differs by design: wall times, the command line and parameters
/// (pert.sync itself), and the simulation's own counts (how often the kernel ran the threads).
ordered_json machine_answers(ordered_json s) {
  for (const char* k : {"wall_time_s", "rays_per_second", "command", "params", "simulation",
                        "functional_wall_time_s", "overhead_ratio"})
    s.erase(k);
  return s;
}

/// Where `a` and `b` differ: "path: a-value / b-value", at most `limit` of them.
void differences(const ordered_json& a, const ordered_json& b, const std::string& path,
                 std::vector<std::string>& out, std::size_t limit = 8) {
  if (out.size() >= limit || a == b) return;
  if (a.is_object() && b.is_object()) {
    for (const auto& [k, v] : a.items()) {
      if (!b.contains(k))
        out.push_back(path + "/" + k + ": only in the first");
      else
        differences(v, b[k], path + "/" + k, out, limit);
    }
    for (const auto& [k, v] : b.items())
      if (!a.contains(k) && out.size() < limit)
        out.push_back(path + "/" + k + ": only in the second");
    return;
  }
  if (a.is_array() && b.is_array() && a.size() == b.size()) {
    for (std::size_t i = 0; i < a.size(); ++i)
      differences(a[i], b[i], path + "[" + std::to_string(i) + "]", out, limit);
    return;
  }
  out.push_back(path + ": " + a.dump() + " / " + b.dump());
}

struct Case {
  std::string tag, args;
};

/// Runs every case with `reference` and with `fast` appended: the same stats.json (less what
/// differs by design) and the same image, and `fast` costs the kernel at most `at_most` times
/// as much of `cost` (stats.json simulation.process_activations: how often it ran a process;
/// delta_cycles) as `reference`.
void same_answers(const std::string& name, const std::vector<Case>& cases,
                  const std::string& reference, const std::string& fast, double at_most,
                  const char* cost = "process_activations") {
  for (const Case& c : cases) {
    SCOPED_TRACE(c.tag);
    const std::string base = "run --machine gaudet-pert " + c.args;
    const fs::path every = run_ok(name + "-reference-" + c.tag, base + " " + reference);
    const fs::path few = run_ok(name + "-fast-" + c.tag, base + " " + fast);
    const ordered_json a = read_json(every / "stats.json");
    const ordered_json b = read_json(few / "stats.json");
    ASSERT_TRUE(a.contains("simulation") && b.contains("simulation"));
    const auto waits_a = a["simulation"][cost].get<double>();
    const auto waits_b = b["simulation"][cost].get<double>();
    std::printf("%s %s: frame %.9g s and %.9g s; %s %.0f and %.0f (%.2fx)\n", name.c_str(),
                c.tag.c_str(), a["simulated_time_s"].get<double>(),
                b["simulated_time_s"].get<double>(), cost, waits_a, waits_b, waits_b / waits_a);
    std::vector<std::string> diffs;
    differences(machine_answers(a), machine_answers(b), "", diffs);
    std::string listed;
    for (const auto& d : diffs) listed += "\n  " + d;
    EXPECT_TRUE(diffs.empty()) << "stats.json differs (" << reference << " / " << fast
                               << "):" << listed;
    EXPECT_EQ(read_file(every / "image.png"), read_file(few / "image.png"));
    // What it is for: the kernel works less.
    EXPECT_LT(waits_b, at_most * waits_a);
  }
}

const std::vector<Case>& cases() {
  static const std::vector<Case> all = {
      {"balls-8", "--scene " + rtsim::test::shared_path("scenes/balls-s2.nff") +
                      " --width 96 --height 96 -p pert_count=8"},
      {"teapot-8", "--scene " + rtsim::test::shared_path("scenes/teapot-s2.nff") +
                       " --width 96 --height 96 -p pert_count=8"},
      {"balls-64", "--scene " + rtsim::test::shared_path("scenes/balls-s2.nff") +
                       " --width 96 --height 96 -p pert_count=64"},
      {"npp-direct", "--scene builtin:npp-412 --width 64 --height 64 -p broadcast.mode=direct"},
      {"npp-probe",
       "--scene builtin:npp-412 --width 48 --height 48 -p pert_count=4 "
       "-p broadcast.mode=non-adaptive --latency-probe"},
  };
  return all;
}

}  // namespace

TEST(GaudetSync, WaitingOnlyToInteractGivesTheAnswersOfWaitingAfterEveryComputation) {
  same_answers("sync", cases(), "-p pert.sync=computations", "-p pert.sync=interactions", 0.9);
}

// The Broadcast Processors plan their next strobe as they strobe, and a request for a sooner
// slot moves their alarm (broadcast.wakes = needed, the default): the answers of buses that wake
// at every request, every freed buffer and every packet's end (every_change), on the adaptive
// runs above (the modes that send every packet, or none, wake as the reference does) and on
// four that reach the loop's other plans: one PERT (strobes that miss for want of a buffer, and
// the sleep through them), depth-first ID lists, a quantum (registers valid from a processor's
// time ahead of the bus's: the loop sleeps until the first of them) and the latency probe.
TEST(GaudetSync, BusesThatPlanAheadGiveTheAnswersOfBusesThatWakeAtEveryChange) {
  std::vector<Case> all(cases().begin(), cases().begin() + 3);
  all.push_back({"npp-probe-adaptive",
                 "--scene builtin:npp-412 --width 48 --height 48 -p pert_count=4 --latency-probe"});
  all.push_back({"npp-1", "--scene builtin:npp-412 --width 64 --height 64 -p pert_count=1"});
  all.push_back({"balls-depth", "--scene " + rtsim::test::shared_path("scenes/balls-s2.nff") +
                                    " --width 64 --height 64 -p pert_count=4 "
                                    "-p broadcast.order=depth"});
  all.push_back({"npp-quantum",
                 "--scene builtin:npp-412 --width 64 --height 64 -p pert_count=8 "
                 "--quantum 10us"});
  same_answers("wakes", all, "-p broadcast.wakes=every_change", "-p broadcast.wakes=needed", 1.0);
}

// The programs of the PERT processors and the Broadcast Processors on the machine's event queue
// (process = queue, the default), which runs them ahead of SystemC while nothing else is due,
// give the answers of programs that SystemC runs as a method each (method), on the runs above
// (direct memory: no buses), one PERT, a quantum, and waits after every computation.
TEST(GaudetSync, ProgramsOnTheQueueGiveTheAnswersOfProgramsInMethods) {
  std::vector<Case> all = cases();
  all.push_back({"npp-1", "--scene builtin:npp-412 --width 64 --height 64 -p pert_count=1"});
  all.push_back({"npp-quantum",
                 "--scene builtin:npp-412 --width 64 --height 64 -p pert_count=8 "
                 "--quantum 10us"});
  all.push_back({"teapot-computations",
                 "--scene " + rtsim::test::shared_path("scenes/teapot-s2.nff") +
                     " --width 64 --height 64 -p pert_count=8 -p pert.sync=computations"});
  same_answers("process", all, "-p process=method", "-p process=queue", 0.8, "delta_cycles");
}
