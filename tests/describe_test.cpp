// `rtsim describe MACHINE`: the module tree it prints is the machine's own — every statistics
// group stats.json reports and every module parameter appears, under the module that owns it —
// and the block diagram is real DOT (and SVG, drawn by Graphviz, which the README installs).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using rtsim::test::read_file;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;

struct Case {
  const char* machine;
  const char* scene;
};

class Describe : public testing::TestWithParam<Case> {};

TEST_P(Describe, TreeHoldsEveryModuleParameterAndStatisticsGroup) {
  const Case c = GetParam();
  const fs::path dir = scratch_dir(std::string("describe-") + c.machine);
  const auto d = run_rtsim(std::string("describe ") + c.machine + " --out " + dir.string());
  ASSERT_EQ(d.exit_code, 0) << d.output;
  // The statistics groups of a run of the same scene.
  const fs::path run_dir = dir / "run";
  const auto r = run_rtsim(std::string("run --machine ") + c.machine + " --scene " + c.scene +
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
  // The diagram: a digraph with every connection the text lists.
  const std::string dot = read_file(dir / (std::string(c.machine) + ".dot"));
  EXPECT_EQ(dot.rfind("digraph", 0), 0u);
  auto count = [](const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
      ++n;
    return n;
  };
  const std::string listed = d.output.substr(d.output.find("Connections:"));
  EXPECT_EQ(count(dot, " -> "), count(listed, " -> "));
  // The VAX is one module; the others are connected.
  if (std::string(c.machine) != "vax-750") {
    EXPECT_GT(count(dot, " -> "), 0u);
  }
  if (std::system("command -v dot >/dev/null 2>&1") == 0) {
    const std::string svg = read_file(dir / (std::string(c.machine) + ".svg"));
    EXPECT_NE(svg.find("<svg"), std::string::npos);
  } else {
    ADD_FAILURE() << "Graphviz's dot is not installed (scripts/quickstart.sh installs graphviz)";
  }
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Machines, Describe,
                         testing::Values(Case{"gaudet-pert", "builtin:npp-412"},
                                         Case{"ullner-peripheral", "builtin:ullner-cubes"},
                                         Case{"ullner-pipeline", "builtin:ullner-cubes"},
                                         Case{"ullner-array", "builtin:ullner-cubes"},
                                         Case{"wang-bezier", "builtin:default"},
                                         Case{"pxpl5-raytrace", "builtin:default"},
                                         Case{"vax-750", "builtin:npp-412"}),
                         [](const testing::TestParamInfo<Case>& i) {
                           return rtsim::test::gtest_param_name(i.param.machine);
                         });

TEST(Describe, EveryMachineIsCovered) {
  const auto r = run_rtsim("list machines");
  ASSERT_EQ(r.exit_code, 0);
  std::size_t machines = 0;
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("  ", 0) != 0) continue;  // machines are the indented lines
    std::istringstream words(line);
    std::string name;
    words >> name;
    if (name == "(none)") continue;  // the functional renderer
    bool covered = false;
    for (const char* m : {"gaudet-pert", "ullner-peripheral", "ullner-pipeline", "ullner-array",
                          "vax-750", "wang-bezier", "pxpl5-raytrace"})
      covered |= name == m;
    EXPECT_TRUE(covered) << name << " has no case in Machines/Describe";
    ++machines;
  }
  EXPECT_EQ(machines, 7u);
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

TEST(Describe, BadInputIsExitTwo) {
  const auto m = run_rtsim("describe gaudet-perts");
  EXPECT_EQ(m.exit_code, 2) << m.output;
  EXPECT_NE(m.output.find("gaudet-pert"), std::string::npos) << m.output;
  const auto s = run_rtsim("describe ullner-peripheral --scene builtin:npp-412");
  EXPECT_EQ(s.exit_code, 2) << s.output;
}

}  // namespace
