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

}  // namespace

TEST(GaudetSync, WaitingOnlyToInteractGivesTheAnswersOfWaitingAfterEveryComputation) {
  struct Case {
    std::string tag, args;
  };
  const Case cases[] = {
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
  for (const Case& c : cases) {
    SCOPED_TRACE(c.tag);
    const std::string base = "run --machine gaudet-pert " + c.args;
    const fs::path every =
        run_ok("sync-computations-" + c.tag, base + " -p pert.sync=computations");
    const fs::path few = run_ok("sync-interactions-" + c.tag, base + " -p pert.sync=interactions");
    const ordered_json a = read_json(every / "stats.json");
    const ordered_json b = read_json(few / "stats.json");
    ASSERT_TRUE(a.contains("simulation") && b.contains("simulation"));
    const auto waits_a = a["simulation"]["process_activations"].get<double>();
    const auto waits_b = b["simulation"]["process_activations"].get<double>();
    std::printf("%s: frame %.9g s and %.9g s; thread activations %.0f and %.0f (%.2fx)\n",
                c.tag.c_str(), a["simulated_time_s"].get<double>(),
                b["simulated_time_s"].get<double>(), waits_a, waits_b, waits_b / waits_a);
    std::vector<std::string> diffs;
    differences(machine_answers(a), machine_answers(b), "", diffs);
    std::string listed;
    for (const auto& d : diffs) listed += "\n  " + d;
    EXPECT_TRUE(diffs.empty()) << "stats.json differs (computations / interactions):" << listed;
    EXPECT_EQ(read_file(every / "image.png"), read_file(few / "image.png"));
    // What it is for: the threads wait less.
    EXPECT_LT(waits_b, 0.9 * waits_a);
  }
}
