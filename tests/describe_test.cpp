// `rtsim describe MACHINE`: the module tree it prints is the machine's own — every statistics
// group stats.json reports and every module parameter appears, under the module that owns it —
// and the block diagram is real DOT (and SVG, drawn by Graphviz, which the README installs).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "platform/machine_registry.hpp"
#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using rtsim::test::MachineInfo;
using rtsim::test::read_file;
using rtsim::test::run_kit;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;

class Describe : public testing::TestWithParam<MachineInfo> {};

TEST_P(Describe, TreeHoldsEveryModuleParameterAndStatisticsGroup) {
  const MachineInfo& m = GetParam();
  const fs::path dir = scratch_dir("describe-" + m.name);
  const auto d = run_kit("describe " + m.name + " --out " + dir.string());
  ASSERT_EQ(d.exit_code, 0) << d.output;
  // The statistics groups of a run of the same scene.
  const fs::path run_dir = dir / "run";
  const auto r = run_kit("run --machine " + m.name + " --scene " + m.sample_scene +
                         " --width 4 --height 4 -q --out " + run_dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto stats = nlohmann::json::parse(read_file(run_dir / "stats.json"));
  std::size_t groups = 0;
  for (const auto& [name, group] : stats.at("modules").items()) {
    EXPECT_NE(d.output.find("]  " + name + "\n"), std::string::npos) << name << "\n" << d.output;
    ++groups;
  }
  EXPECT_GT(groups, 0u);
  // Every parameter is listed once: a module's as "param NAME", the machine's in its list.
  std::size_t params = 0;
  for (const auto& [name, value] : stats.at("params").items()) {
    const bool as_module = d.output.find("param " + name + " = ") != std::string::npos;
    const bool as_machine = d.output.find(" " + name + " ") != std::string::npos ||
                            d.output.find(" " + name + "\n") != std::string::npos;
    EXPECT_TRUE(as_module || as_machine) << name;
    ++params;
  }
  EXPECT_GT(params, 5u);
  // The unit of every number of its stats.json, as the run's `units` declares it.
  ASSERT_TRUE(d.output.find("Units of stats.json's numbers") != std::string::npos);
  const std::string units_text = d.output.substr(d.output.find("Units of stats.json's numbers"));
  std::size_t units = 0;
  for (const auto& [pattern, unit] : stats.at("units").items()) {
    std::string key = "\n  ";  // appends: GCC 12 warns falsely on literal + string (-Wrestrict)
    key += pattern;
    key += ' ';
    const std::size_t at = units_text.find(key);
    ASSERT_NE(at, std::string::npos) << pattern;
    const std::size_t end = units_text.find('\n', at + 1);
    const std::string line = units_text.substr(at + 1, end - at - 1);
    std::string spaced = " ";
    spaced += unit.get<std::string>();
    EXPECT_TRUE(line.ends_with(spaced)) << line;
    ++units;
  }
  EXPECT_GT(units, 20u);
  // The diagram: a digraph with every connection the text lists.
  const std::string dot = read_file(dir / (m.name + ".dot"));
  EXPECT_EQ(dot.rfind("digraph", 0), 0u);
  auto count = [](const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
      ++n;
    return n;
  };
  const std::string after = d.output.substr(d.output.find("Connections:"));
  const std::string listed = after.substr(0, after.find("\nRing "));
  if (dot.find("(token ring)") != std::string::npos) {
    // A ring (pxpl5-raytrace's) is drawn as the ring it is: its nodes in the token's order, each
    // to the next and the last back to the first, as a racetrack (a column of the picture holds
    // node k and node n-1-k); its channel's deliveries to each node are the ring itself.
    const std::string ring = after.substr(after.find("\nRing "));
    const std::size_t stops = count(ring.substr(0, ring.find('\n', 1)), " -> ");
    EXPECT_GT(stops, 2u);
    EXPECT_EQ(count(dot, "color=royalblue"), stops);
    EXPECT_EQ(count(dot, "{ rank=same;"), stops / 2);
    EXPECT_LT(count(dot, " -> ") - stops, count(listed, " -> "));
  } else if (dot.find(" more ") != std::string::npos &&
             dot.find("each holding:") == std::string::npos) {
    // A class of more instances than a picture holds (ullner-scanline-tree's processors, one a
    // polygon) is drawn as its first few and a box counting the rest: the text lists them all.
    EXPECT_LT(count(dot, " -> "), count(listed, " -> "));
    EXPECT_GT(count(dot, " -> "), 0u);
  } else if (dot.find("each holding:") == std::string::npos) {
    EXPECT_EQ(count(dot, " -> "), count(listed, " -> "));
  } else {
    // A mesh (ullner-array's nodes) is drawn as its grid: a column of the picture a rank, its
    // links east and south once each, its modules' insides named in a note; the text lists
    // every connection.
    EXPECT_GT(count(dot, "{ rank=same;"), 1u);
    EXPECT_GT(count(dot, "[dir=none"), 0u);
    EXPECT_LT(count(dot, " -> "), count(listed, " -> "));
  }
  // A machine of one module (the VAX) has no connections; any other is connected.
  if (groups > 1) {
    EXPECT_GT(count(dot, " -> "), 0u);
  }
  if (std::system("command -v dot >/dev/null 2>&1") == 0) {
    const std::string svg = read_file(dir / (m.name + ".svg"));
    EXPECT_NE(svg.find("<svg"), std::string::npos);
  } else {
    ADD_FAILURE() << "Graphviz's dot is not installed (scripts/quickstart.sh installs graphviz)";
  }
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Machines, Describe, testing::ValuesIn(rtsim::test::kit_machines()),
                         rtsim::test::machine_param_name);

// The generic tests cover whatever rtsim-kit registers: every machine of rtsim, and the kit's
// minimal machine, which registers itself in tests/kit_machine/ with no list naming it.
TEST(Describe, TheKitProgramHasEveryMachineAndTheMinimalOne) {
  std::vector<std::string> rtsim, kit;
  for (const auto& m : rtsim::test::registered_machines()) rtsim.push_back(m.name);
  for (const auto& m : rtsim::test::kit_machines())
    if (m.name != "kit-minimal") kit.push_back(m.name);
  EXPECT_GE(rtsim.size(), 7u);
  EXPECT_EQ(kit, rtsim);
  EXPECT_EQ(rtsim::test::kit_machines().size(), rtsim.size() + 1);
}

TEST(Describe, ConnectionsFollowTheWiring) {
  const auto d = run_rtsim("describe gaudet-pert -p pert_count=2");
  ASSERT_EQ(d.exit_code, 0) << d.output;
  // The ring, initiator to target, and each bus to every PERT's BIC.
  for (const char* edge :
       {"pert1.shade -> pert1.shell.input  (TLM)", "pert1.shell -> pert1.prim.input  (TLM)",
        "pert1.prim -> pert1.shade.input  (TLM)", "shell_bus -> pert0.shell.bic  (broadcast)",
        "shell_bus -> pert1.shell.bic  (broadcast)", "control -> prim_bus.memory  (TLM)"})
    EXPECT_NE(d.output.find(edge), std::string::npos) << edge << "\n" << d.output;
  EXPECT_EQ(d.output.find("pert0.shell.input -> pert0.shade"), std::string::npos)
      << "a target's backward path is no connection of its own";
}

TEST(Describe, LeavesOutTheModulesThatOnlyOrderTheOthersRemoval) {
  // ullner-array makes a few empty modules before its own (modules/removal_order.hpp).
  const auto d = run_rtsim("describe ullner-array -p array.rows=2 -p array.cols=2");
  ASSERT_EQ(d.exit_code, 0) << d.output;
  EXPECT_NE(d.output.find("node3"), std::string::npos) << d.output;
  EXPECT_EQ(d.output.find("removal_order"), std::string::npos) << d.output;
}

TEST(Describe, BadInputIsExitTwo) {
  // A machine's name with an "s" too many: the message suggests the name.
  const std::string name = rtsim::platform::default_machine().name();
  const auto m = run_rtsim("describe " + name + "s");
  EXPECT_EQ(m.exit_code, 2) << m.output;
  EXPECT_NE(m.output.find(name), std::string::npos) << m.output;
  const auto s = run_rtsim("describe " + name + " --scene builtin:no-such-scene");
  EXPECT_EQ(s.exit_code, 2) << s.output;
}

}  // namespace
