// Every parameter of every machine at its bounds (issue 30 item 5, item 8): the bounds a
// parameter declares are the real ones (docs/bad-input.md), so a run with any value inside them
// either runs (exit 0) or is refused as bad input (exit 2): never a crash, an internal error
// (exit 1), a hang, or more than 2 GiB of memory for an 8 x 8 frame. Numbers and units are run
// at their lower and upper bounds (an open upper bound at the largest value its kind holds);
// strings at every allowed value, booleans flipped. Machines come from `rtsim list machines
// --format json`, so a new machine is covered with no edit here.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/limited_run.hpp"
#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using rtsim::test::LimitedRun;
using rtsim::test::run_limited;

/// Peak memory a run at 8 x 8 may take.
constexpr long kMaxRssKib = 2L << 20;
/// The address space a run gets: past it an allocation fails in the run (exit 1: a defect the
/// test reports) instead of pushing the machine into swap.
constexpr std::uint64_t kAddressSpace = std::uint64_t{8} << 30;
/// A run at a bound may take long (a frame of a million samples); past this it is stopped and
/// reported, and counts as a failure: a value inside the bounds must not hang the program.
constexpr double kTimeoutS = 120.0;

using rtsim::test::MachineInfo;

/// The scene a machine's bounds are tried on: its small test run's (wang-bezier's sample scene
/// has no patches to keep its pipeline busy; its test run's has); the run's parameters are
/// left out, as the bounds set them.
std::string scene_for(const MachineInfo& m) {
  std::istringstream words(m.small_run());
  for (std::string w; words >> w;)
    if (w == "--scene" && words >> w) return w;
  return m.sample_scene;
}
/// The largest value of a kind with no declared upper bound: what the parser can hold.
std::string open_upper_bound(const std::string& kind) {
  if (kind == "int") return "9223372036854775807";
  if (kind == "double") return "1e308";
  if (kind == "time") return "9000000 s";  // 2^63 ps is 9.2e6 s
  if (kind == "frequency") return "1e15 Hz";
  if (kind == "bitrate") return "1e18 bit/s";
  if (kind == "datasize") return "1e15 B";
  return "";
}

struct Setting {
  std::string name, value;
};

/// The values each parameter is tried at.
std::vector<Setting> bound_settings(const nlohmann::json& params) {
  std::vector<Setting> out;
  for (const auto& p : params) {
    const std::string name = p.at("name"), kind = p.at("kind"), value = p.at("value");
    const auto add = [&](const std::string& v) {
      if (!v.empty() && v != value) out.push_back({name, v});
    };
    if (kind == "bool") {
      add(value == "true" ? "false" : "true");
    } else if (kind == "string") {
      for (const auto& a : p.at("allowed")) add(a.get<std::string>());
    } else {
      add(p.at("min").get<std::string>());
      const std::string max = p.at("max");
      add(max.empty() ? open_upper_bound(kind) : max);
    }
  }
  return out;
}

class ParamBounds : public testing::TestWithParam<MachineInfo> {};

TEST_P(ParamBounds, EveryParameterAtItsBoundsRunsOrIsRefusedWithinTwoGiB) {
  const std::string machine = GetParam().name;
  const std::string scene = scene_for(GetParam());
  const fs::path dir = rtsim::test::scratch_dir("bounds-" + machine);
  fs::create_directories(dir);
  const LimitedRun list =
      run_limited({"list", "params", "--machine", machine, "--format", "json"}, dir, 60);
  ASSERT_EQ(list.exit_code, 0) << list.output;
  const std::vector<Setting> settings = bound_settings(nlohmann::json::parse(list.output));
  ASSERT_FALSE(settings.empty());

  struct Result {
    Setting setting;
    LimitedRun run;
    bool output_left = false;  ///< the --out folder exists after the run
  };
  std::vector<Result> results(settings.size());
  // Two at a time (the machine has two cores; ctest runs other tests beside).
  std::atomic<std::size_t> next{0};
  const auto worker = [&] {
    for (std::size_t i = next++; i < settings.size(); i = next++) {
      const Setting& s = settings[i];
      const fs::path out = dir / ("out" + std::to_string(i));
      results[i] = {
          s,
          run_limited({"run", "--machine", machine, "--scene", scene, "--width", "8", "--height",
                       "8", "-q", "--out", out.string(), "-p", s.name + "=" + s.value},
                      dir, kTimeoutS, kAddressSpace),
          fs::exists(out)};
      fs::remove_all(out);
    }
  };
  std::thread a(worker), b(worker);
  a.join();
  b.join();

  std::size_t ran = 0, refused = 0;
  for (const auto& [s, r, output_left] : results) {
    const std::string what = machine + " -p " + s.name + "=" + s.value;
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 2) << what << ": " << r.status() << "\n"
                                                      << r.output;
    EXPECT_LT(r.max_rss_kib, kMaxRssKib) << what << ": peak " << r.max_rss_kib / 1024 << " MiB";
    // Refused: nothing written, not even the folder.
    if (r.exit_code == 2) {
      EXPECT_FALSE(output_left) << what;
    }
    (r.exit_code == 0 ? ran : refused)++;
  }
  // The slowest and the largest, for the record (docs/bad-input.md).
  std::vector<const Result*> order;
  for (const auto& r : results) order.push_back(&r);
  std::sort(order.begin(), order.end(),
            [](const Result* x, const Result* y) { return x->run.wall_s > y->run.wall_s; });
  std::printf("%s: %zu settings, %zu ran, %zu refused; slowest:", machine.c_str(), settings.size(),
              ran, refused);
  for (std::size_t i = 0; i < std::min<std::size_t>(3, order.size()); ++i)
    std::printf(" %s=%s %.1f s;", order[i]->setting.name.c_str(), order[i]->setting.value.c_str(),
                order[i]->run.wall_s);
  std::sort(order.begin(), order.end(), [](const Result* x, const Result* y) {
    return x->run.max_rss_kib > y->run.max_rss_kib;
  });
  std::printf(" largest: %s=%s %ld MiB\n", order[0]->setting.name.c_str(),
              order[0]->setting.value.c_str(), order[0]->run.max_rss_kib / 1024);
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Machines, ParamBounds, testing::ValuesIn(rtsim::test::kit_machines()),
                         [](const testing::TestParamInfo<MachineInfo>& i) {
                           return rtsim::test::gtest_param_name(i.param.name);
                         });

}  // namespace
