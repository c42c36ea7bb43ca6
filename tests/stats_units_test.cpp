// Units (modules/stat_unit.hpp): every number of every machine's stats.json has a unit declared
// where it is written, and carried in the file's `units`; the console, diff and the reports show
// it from that unit: a rate never as a time, a count never with a unit, a time always with one.
// Each machine is run with everything that adds keys: the latency probe, both traces, --overhead,
// and a sampled run; the functional render too.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "app/number_text.hpp"
#include "modules/stat_unit.hpp"
#include "tests/test_support.hpp"

using rtsim::modules::StatUnit;
using rtsim::modules::UnitSchema;

namespace {

/// Checks every number of `stats` against its declared unit; returns how many it checked.
std::size_t check_units(const nlohmann::ordered_json& stats, const std::string& label) {
  const UnitSchema units = UnitSchema::from_stats(stats);
  EXPECT_FALSE(units.empty()) << label << ": stats.json has no `units`";
  std::size_t checked = 0;
  std::set<std::string> reported;
  rtsim::test::each_number(stats, [&](const std::string& path, double x) {
    ++checked;
    const auto unit = units.unit_of(path);
    if (!unit) {
      if (reported.insert(path).second) ADD_FAILURE() << label << ": no unit for " << path;
      return;
    }
    // The declaration agrees with what the key's own name says (not its module's:
    // node3.link_s is the south link); a summary's by the name of what it summarises.
    const std::string_view name = rtsim::modules::unit_name(*unit);
    std::string key = path.substr(path.rfind('.') + 1);
    static const std::set<std::string> kSummaries = {"min", "mean", "max", "sum",
                                                     "p10", "p50",  "p90", "p99"};
    if (kSummaries.contains(key) && key.size() < path.size()) {
      const std::string head = path.substr(0, path.rfind('.'));
      key = head.substr(head.rfind('.') + 1) + "." + key;
    }
    if (rtsim::app::names_seconds(key)) {
      EXPECT_EQ(*unit, StatUnit::seconds) << label << ": " << path << " is declared " << name;
    }
    if (key.ends_with("_per_s") || key.ends_with("per_second")) {
      EXPECT_EQ(*unit, StatUnit::rate) << label << ": " << path << " is declared " << name;
    }
    if (rtsim::app::names_fraction(key)) {
      EXPECT_EQ(*unit, StatUnit::fraction) << label << ": " << path << " is declared " << name;
    }
    const std::string text = rtsim::app::format_figure(units, path, x);
    EXPECT_FALSE(std::regex_search(text, std::regex("[0-9]e[-+]?[0-9]")))
        << label << ": " << path << " = " << text;
    switch (*unit) {
      case StatUnit::count:
      case StatUnit::ratio:
        EXPECT_TRUE(std::regex_match(text, std::regex("-?[0-9]+(\\.[0-9]+)?")))
            << label << ": " << path << " = " << text;
        break;
      case StatUnit::rate:
        EXPECT_TRUE(std::regex_match(text, std::regex("-?[0-9]+(\\.[0-9]+)?/s")))
            << label << ": " << path << " = " << text;
        break;
      case StatUnit::seconds:
        EXPECT_TRUE(std::regex_match(text, std::regex("-?[0-9.]+ (ns|µs|ms|s|min|h)")))
            << label << ": " << path << " = " << text;
        break;
      case StatUnit::fraction:
        EXPECT_TRUE(text.ends_with("%")) << label << ": " << path << " = " << text;
        break;
      default:
        EXPECT_TRUE(text.ends_with(std::string(" ") + std::string(name)) ||
                    std::regex_search(text, std::regex(" [kMG]B$")))
            << label << ": " << path << " = " << text;
    }
  });
  return checked;
}

class StatsUnits : public testing::TestWithParam<rtsim::test::MachineInfo> {};

TEST_P(StatsUnits, EveryNumberOfEveryRunHasADeclaredUnit) {
  const auto& m = GetParam();
  const std::string args = m.small_run() + " --width 16 --height 16";
  const auto full = rtsim::test::run_machine(
      m.name, "units-full",
      args + " --latency-probe --trace perfetto --trace vcd --overhead --report");
  ASSERT_FALSE(full.empty());
  const std::size_t a = check_units(full, m.name + " (probe, traces, overhead)");
  if (!m.samples) {  // it refuses --sample (sampled_simulation_test.cpp checks that)
    std::printf("%-18s %zu numbers, each in its declared unit\n", m.name.c_str(), a);
    return;
  }
  const auto sampled = rtsim::test::run_machine(m.name, "units-sampled",
                                                m.small_run() +
                                                    " --width 32 --height 32 "
                                                    "--sample 4 --image none");
  ASSERT_FALSE(sampled.empty());
  ASSERT_TRUE(sampled.contains("sample"));
  const std::size_t b = check_units(sampled, m.name + " (sampled)");
  std::printf("%-18s %zu + %zu numbers, each in its declared unit\n", m.name.c_str(), a, b);
}

INSTANTIATE_TEST_SUITE_P(Machines, StatsUnits, testing::ValuesIn(rtsim::test::kit_machines()),
                         rtsim::test::machine_param_name);

TEST(StatsUnits, TheFunctionalRenderDeclaresItsUnitsToo) {
  const auto dir = rtsim::test::scratch_dir("units-render");
  const auto r = rtsim::test::run_rtsim(
      "render --scene builtin:default --width 16 --height 16 -q --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_GT(check_units(rtsim::test::read_json(dir / "stats.json"), "render"), 20u);
}

TEST(StatsUnits, AUnitIsShownAsPeopleReadIt) {
  using rtsim::app::format_in_unit;
  EXPECT_EQ(format_in_unit(StatUnit::rate, 915751.2), "915751/s");
  EXPECT_EQ(format_in_unit(StatUnit::rate, 254.4 * 3600), "915840/s");
  EXPECT_EQ(format_in_unit(StatUnit::count, 37.77 * 3600), "135972");
  EXPECT_EQ(format_in_unit(StatUnit::seconds, 0.0215), "21.50 ms");
  EXPECT_EQ(format_in_unit(StatUnit::fraction, 0.07613), "7.6%");
  EXPECT_EQ(format_in_unit(StatUnit::bytes, 33.2e6), "33.20 MB");
  EXPECT_EQ(format_in_unit(StatUnit::bits, 1024), "1024 bits");
  // A schema's patterns: the first declared wins; a module instance is found under its class,
  // and a class aggregate in its key's unit.
  UnitSchema u{{"array.node_busy_fraction", StatUnit::fraction}, {"array.*", StatUnit::count}};
  u.add("modules.node*.link_e.bits", StatUnit::bits);
  EXPECT_EQ(u.unit_of("array.node_busy_fraction"), StatUnit::fraction);
  EXPECT_EQ(u.unit_of("array.messages_sent_by_type.vision"), StatUnit::count);
  EXPECT_EQ(u.unit_of("modules.node12.link_e.bits"), StatUnit::bits);
  EXPECT_EQ(u.unit_of("module_classes.node*.link_e.bits.max"), StatUnit::bits);
  EXPECT_FALSE(u.unit_of("modules.node12.link_e.messages").has_value());
  // Written and read back as stats.json carries it.
  nlohmann::ordered_json stats;
  stats["units"] = u.to_json();
  EXPECT_EQ(UnitSchema::from_stats(stats).unit_of("modules.node3.link_e.bits"), StatUnit::bits);
}

}  // namespace
