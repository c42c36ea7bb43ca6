// Traces agree with stats.json (issue 10, item 6): every machine runs with both traces, and for
// every module and queue of stats.json the time-weighted mean of its traced signal over the
// frame (stats.json trace.stats_interval_s) equals stats.json's utilisation or mean occupancy
// within 1e-6 relative, in trace.json's counters and in trace.vcd alike; the maximum depth
// equals max_occupancy; and nothing was dropped. The worst relative error of each machine and
// file is printed and recorded as a test property.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using rtsim::test::read_file;
using rtsim::test::run_kit;
using rtsim::test::scratch_dir;

namespace {

constexpr double kRelativeTolerance = 1e-6;

/// One signal: (time in seconds, value from then on), in time order; 0 before the first.
using Steps = std::vector<std::pair<long double, long double>>;

/// Time-weighted mean and maximum of a step signal over [b, e].
std::pair<long double, long double> mean_and_max(const Steps& steps, long double b, long double e) {
  long double level = 0, area = 0, last = b, max = 0;
  for (const auto& [t, v] : steps) {
    if (t > e) break;
    if (t > b) {
      area += level * (t - last);
      last = t;
      max = std::max(max, level);
    }
    level = v;
  }
  max = std::max(max, level);
  area += level * (e - last);
  return {area / (e - b), max};
}

/// trace.json: counters by name ("host.busy"); ts are microseconds.
std::map<std::string, Steps> perfetto_signals(const json& trace) {
  std::map<std::string, Steps> out;
  for (const auto& e : trace.at("traceEvents")) {
    if (e.at("ph") != "C") continue;
    out[e.at("name").get<std::string>()].emplace_back(
        static_cast<long double>(e.at("ts").get<double>()) * 1e-6L,
        static_cast<long double>(e.at("args").at("value").get<double>()));
  }
  for (auto& [name, steps] : out)
    std::stable_sort(steps.begin(), steps.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
  return out;
}

/// trace.vcd: signals by dotted name (scopes joined with '.'); times are picoseconds.
std::map<std::string, Steps> vcd_signals(const std::string& vcd) {
  std::map<std::string, std::string> name_of;  // identifier -> dotted name
  std::map<std::string, Steps> out;
  std::vector<std::string> scopes;
  std::istringstream in(vcd);
  std::string line;
  bool definitions = true;
  long double now = 0;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string w;
    words >> w;
    if (definitions) {
      if (w == "$timescale") {
        std::string n, unit;
        words >> n >> unit;
        EXPECT_EQ(n + " " + unit, "1 ps") << "the test reads picoseconds";
      } else if (w == "$scope") {
        std::string kind, name;
        words >> kind >> name;
        scopes.push_back(name);
      } else if (w == "$upscope") {
        scopes.pop_back();
      } else if (w == "$var") {
        std::string type, width, id, name;
        words >> type >> width >> id >> name;
        std::string dotted;
        for (const auto& s : scopes) dotted += s + ".";
        name_of[id] = dotted + name;
      } else if (w == "$enddefinitions") {
        definitions = false;
      }
      continue;
    }
    if (w.empty() || w[0] == '$') continue;
    if (w[0] == '#') {
      now = static_cast<long double>(std::stoull(w.substr(1))) * 1e-12L;
    } else if (w[0] == 'b') {
      std::string id;
      words >> id;
      out[name_of.at(id)].emplace_back(
          now, static_cast<long double>(std::stoull(w.substr(1), nullptr, 2)));
    } else {
      out[name_of.at(w.substr(1))].emplace_back(now, w[0] == '1' ? 1.0L : 0.0L);
    }
  }
  return out;
}

/// |a - b| relative to the larger; exact zeros must match exactly.
double relative(long double got, double want) {
  const long double scale = std::max(std::fabs(got), std::fabs(static_cast<long double>(want)));
  return scale == 0 ? 0.0 : static_cast<double>(std::fabs(got - want) / scale);
}

/// Each machine's test runs (its registration), on small frames: seconds each.
constexpr const char* kSize = " --width 24 --height 24";

class TraceAgreement : public testing::TestWithParam<rtsim::test::MachineInfo> {};

}  // namespace

TEST_P(TraceAgreement, TracedSignalsHaveStatsJsonsMeans) {
  const std::string& machine = GetParam().name;
  const std::vector<std::string>& runs = GetParam().test_runs;
  {
    std::map<std::string, std::pair<double, std::string>> worst;  // file -> (error, signal)
    for (std::size_t k = 0; k < runs.size(); ++k) {
      const fs::path dir = scratch_dir("agree-" + machine + "-" + std::to_string(k));
      const auto r = run_kit("run --machine " + machine + " " + runs[k] + kSize +
                             " --trace vcd,perfetto -q --out " + dir.string());
      ASSERT_EQ(r.exit_code, 0) << runs[k] << "\n" << r.output;
      EXPECT_EQ(r.output, "") << "no warning: nothing dropped";
      const json stats = json::parse(read_file(dir / "stats.json"));
      const json& t = stats.at("trace");
      EXPECT_EQ(t.at("perfetto").at("events_dropped"), 0);
      EXPECT_EQ(t.at("vcd").at("changes_dropped"), 0);
      const long double b = t.at("stats_interval_s")[0].get<double>();
      const long double e = t.at("stats_interval_s")[1].get<double>();
      ASSERT_GT(e, b);
      EXPECT_NEAR(static_cast<double>(e - b), stats.at("simulated_time_s").get<double>(),
                  1e-12 * static_cast<double>(e));
      const json perfetto = json::parse(read_file(dir / "trace.json"));
      const std::map<std::string, std::map<std::string, Steps>> traces = {
          {"trace.json", perfetto_signals(perfetto)},
          {"trace.vcd", vcd_signals(read_file(dir / "trace.vcd"))}};
      std::size_t compared = 0, traced = 0;
      for (const auto& [name, m] : stats.at("modules").items()) {
        const bool queue = m.contains("queue");
        if (!queue && !m.contains("utilization")) continue;  // counters only (a BIC's)
        ++traced;
        const std::string signal = name + (queue ? ".depth" : ".busy");
        const double want =
            queue ? m["queue"]["mean_occupancy"].get<double>() : m["utilization"].get<double>();
        for (const auto& [file, signals] : traces) {
          const auto it = signals.find(signal);
          if (it == signals.end()) {
            ADD_FAILURE() << machine << " run " << k << ": " << file << " has no " << signal;
            continue;
          }
          const auto [mean, max] = mean_and_max(it->second, b, e);
          const double rel = relative(mean, want);
          EXPECT_LE(rel, kRelativeTolerance)
              << machine << " run " << k << " " << file << " " << signal << ": traced mean "
              << static_cast<double>(mean) << ", stats.json " << want;
          if (queue) {
            EXPECT_EQ(static_cast<double>(max), m["queue"]["max_occupancy"].get<double>())
                << machine << " " << file << " " << signal;
          }
          if (rel >= worst[file].first) worst[file] = {rel, signal};
          ++compared;
        }
      }
      EXPECT_GE(compared, 2 * traced);
      EXPECT_GE(traced, 1u);
      fs::remove_all(dir);
    }
    for (const auto& [file, w] : worst) {
      std::cout << "[ agreement ] " << machine << " " << file << ": max relative error " << w.first
                << " (" << w.second << ")\n";
      testing::Test::RecordProperty(machine + " " + file + " max relative error",
                                    std::to_string(w.first));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Machines, TraceAgreement, testing::ValuesIn(rtsim::test::kit_machines()),
                         rtsim::test::machine_param_name);
