// `--trace perfetto` follows each ray: its messages on the links are slices with their arguments
// (the ray, its bits) and a flow links the ray's slices from processor to link to processor, so
// that Perfetto draws its journey as arrows (modules::SliceSink::hop, modules::Link::Carried);
// a token ring's packets are slices with the message, its source, destination and bytes, and a
// flow runs from its transmission to the module it is delivered to (pxpl5-raytrace).
// ullner-array's messages carry theirs per message (tests/ullner_array_test.cpp).
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "tests/test_support.hpp"

using json = nlohmann::json;

namespace {

struct FlowCase {
  std::string machine;
  std::string args;
  /// Whether the machine's rays cross links between modules (wang-bezier's host is the only
  /// module its rays' work is recorded on).
  bool crosses_modules;
};

void PrintTo(const FlowCase& c, std::ostream* os) { *os << c.machine; }

class TraceFlows : public testing::TestWithParam<FlowCase> {};

TEST_P(TraceFlows, ARaysSlicesAreLinkedAndItsMessagesCarryItsId) {
  const FlowCase& c = GetParam();
  const auto dir = rtsim::test::scratch_dir("flows-" + c.machine);
  const auto r =
      rtsim::test::run_rtsim("run --machine " + c.machine + " " + c.args +
                             " --width 16 --height 16 --trace perfetto -q --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json trace = json::parse(rtsim::test::read_file(dir / "trace.json"));
  std::map<std::string, std::set<std::pair<int, int>>> tracks_of;  // flow -> its tracks
  std::size_t starts = 0, steps = 0, carried = 0;
  for (const auto& e : trace["traceEvents"]) {
    const std::string ph = e["ph"];
    if (ph == "s" || ph == "t") {
      (ph == "s" ? starts : steps)++;
      tracks_of[e["name"].get<std::string>() + ":" + std::to_string(e["id"].get<std::uint64_t>())]
          .insert({e["pid"].get<int>(), e["tid"].get<int>()});
    }
    // A message on a link or the ring: the ray (or message) it carries and its size.
    if (ph == "X" && e.contains("args") &&
        (e["args"].contains("ray") || e["args"].contains("message")) &&
        (e["args"].contains("bits") || e["args"].contains("bytes")))
      ++carried;
  }
  std::size_t crossing = 0;
  for (const auto& [flow, tracks] : tracks_of) crossing += tracks.size() > 1;
  std::printf(
      "%-18s %zu flows (%zu start, %zu step events), %zu across modules, %zu messages "
      "with their ray and bits\n",
      c.machine.c_str(), tracks_of.size(), starts, steps, crossing, carried);
  EXPECT_GT(starts, 0u);
  EXPECT_GT(steps, 0u);
  // Each flow starts once.
  EXPECT_EQ(starts, tracks_of.size());
  if (c.crosses_modules) {
    EXPECT_GT(carried, 0u);
    EXPECT_GT(crossing, tracks_of.size() / 2) << "most rays' flows should cross modules";
  }
  std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(
    Machines, TraceFlows,
    testing::Values(FlowCase{"ullner-peripheral", "--scene builtin:ullner-cubes", true},
                    FlowCase{"ullner-pipeline", "--scene builtin:ullner-cubes", true},
                    FlowCase{"gaudet-pert", "--scene builtin:npp-412 -p pert_count=2", true},
                    FlowCase{"wang-bezier", "--scene builtin:teapot", false},
                    FlowCase{"pxpl5-raytrace", "--scene builtin:spd-teapot", true}),
    [](const testing::TestParamInfo<FlowCase>& i) {
      std::string n = i.param.machine;
      for (char& ch : n)
        if (ch == '-') ch = '_';
      return n;
    });

}  // namespace
