// Tests of `rtsim validate`: the framework's pure parts (tolerances, rows, table/JSON/CSV,
// figure selection, curve shape), Ullner's analytic Fig. 2-18 curve, the figure sets' plans,
// the subprocess runner and the command end to end against a fake rtsim
// (tests/data/fake_rtsim.py, which answers with the seeds' formulas), and, once `rtsim run`
// exists, the real quick validation.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "common/csv_field.hpp"
#include "platform/runs/run_queue.hpp"
#include "platform/validation/curve_shape.hpp"
#include "platform/validation/figure_registry.hpp"
#include "platform/validation/sensitivity.hpp"
#include "platform/validation/ullner_figures.hpp"
#include "platform/validation/validation.hpp"
#include "platform/validation/vax_figures.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using namespace rtsim::validation;
using rtsim::csv_field;
using rtsim::runs::run_all;
using rtsim::test::read_file;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;

namespace {

const std::string kFake = std::string(RTSIM_TEST_DATA_DIR) + "/fake_rtsim.py";

bool have_python() { return fs::exists("/usr/bin/python3"); }

// Sets an environment variable for one scope (the runner's children inherit it).
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() { ::unsetenv(name_); }

 private:
  const char* name_;
};

Row make_row(double seed, std::optional<double> simulated, Tolerance tol) {
  Row r;
  r.id = "X1";
  r.title = "a figure";
  r.seed_ref = "seed 000 L1";
  r.unit = "us";
  r.seed_value = seed;
  r.simulated = simulated;
  r.tolerance = std::move(tol);
  return r;
}

RunOutcome ok_run(const std::string& key, nlohmann::json stats) {
  RunOutcome o;
  o.request.key = key;
  o.exit_code = 0;
  o.stats = std::move(stats);
  return o;
}

}  // namespace

// ---- Tolerances -------------------------------------------------------------------------------

TEST(ValidateTolerance, RelativeAcceptsInsideAndRejectsOutside) {
  const auto t = Tolerance::relative(0.02, "why");
  EXPECT_TRUE(t.accepts(100.0, 100.0));
  EXPECT_TRUE(t.accepts(100.0, 102.0));
  EXPECT_TRUE(t.accepts(100.0, 98.0));
  EXPECT_FALSE(t.accepts(100.0, 102.1));
  EXPECT_FALSE(t.accepts(100.0, 97.9));
  EXPECT_TRUE(t.accepts(-5.0, -5.1));  // relative to |seed|
  EXPECT_FALSE(t.accepts(100.0, std::nan("")));
  EXPECT_FALSE(t.accepts(100.0, std::numeric_limits<double>::infinity()));
  EXPECT_EQ(t.describe(), "±2%");
  EXPECT_EQ(Tolerance::relative(1e-6, "").describe(), "±0.0001%");
}

TEST(ValidateTolerance, AbsoluteAboveAndRange) {
  const auto a = Tolerance::absolute(3, "why");
  EXPECT_TRUE(a.accepts(11, 14));
  EXPECT_TRUE(a.accepts(11, 8));
  EXPECT_FALSE(a.accepts(11, 15));
  EXPECT_EQ(a.describe(), "±3");
  const auto exact = Tolerance::absolute(0, "why");
  EXPECT_TRUE(exact.accepts(17, 17));
  EXPECT_FALSE(exact.accepts(17, 17.000001));
  EXPECT_EQ(exact.describe(), "exact");

  const auto above = Tolerance::above(1, "why");
  EXPECT_TRUE(above.accepts(0, 1.0001));
  EXPECT_FALSE(above.accepts(0, 1.0));
  EXPECT_TRUE(above.accepts(0, std::numeric_limits<double>::infinity()));
  EXPECT_FALSE(above.accepts(0, std::nan("")));
  EXPECT_EQ(above.describe(), "> 1");

  const auto range = Tolerance::range(2, 29, "why");
  EXPECT_TRUE(range.accepts(0, 2));
  EXPECT_TRUE(range.accepts(0, 29));
  EXPECT_FALSE(range.accepts(0, 1));
  EXPECT_FALSE(range.accepts(0, 30));
  EXPECT_EQ(range.describe(), "[2, 29]");
  EXPECT_EQ(Tolerance::range(0, 0, "").describe(), "= 0");
}

TEST(ValidateRow, PassNeedsAValueAndNoError) {
  auto r = make_row(333.33, 339.0, Tolerance::relative(0.03, "fill"));
  EXPECT_TRUE(r.pass());
  ASSERT_TRUE(r.relative_error().has_value());
  EXPECT_NEAR(*r.relative_error(), (339.0 - 333.33) / 333.33, 1e-12);
  r.error = "run failed";
  EXPECT_FALSE(r.pass());
  auto none = make_row(333.33, std::nullopt, Tolerance::relative(0.03, ""));
  EXPECT_FALSE(none.pass());
  EXPECT_FALSE(none.relative_error().has_value());
  auto qualitative = make_row(1, 1.5, Tolerance::above(1, ""));
  qualitative.seed_display = "steeper left";
  EXPECT_TRUE(qualitative.pass());
  EXPECT_FALSE(qualitative.relative_error().has_value());
  EXPECT_FALSE(make_row(0, 0.0, Tolerance::range(0, 0, "")).relative_error().has_value());
}

// ---- Output -----------------------------------------------------------------------------------

TEST(ValidateOutput, NumbersAreShortAndReadable) {
  EXPECT_EQ(format_number(17), "17");
  EXPECT_EQ(format_number(262144), "262144");
  EXPECT_EQ(format_number(1000.0 / 3.0), "333.3");
  EXPECT_EQ(format_number(5.6), "5.6");
  EXPECT_EQ(format_number(14.306), "14.31");
  EXPECT_EQ(format_number(0.3333333), "0.3333");
  EXPECT_EQ(format_number(0), "0");
  EXPECT_EQ(format_number(-2.5), "-2.5");
  EXPECT_EQ(format_number(1.5e-7), "1.5e-07");
  EXPECT_EQ(format_number(1004123.5), "1004000");  // not 1.004e+06
  EXPECT_EQ(format_number(std::numeric_limits<double>::infinity()), "inf");
}

TEST(ValidateOutput, TableShowsEveryRowVerdictAndNotes) {
  std::vector<Row> rows;
  rows.push_back(make_row(333.33, 339.0, Tolerance::relative(0.03, "")));
  rows.back().note = "a mean per ray";
  rows.push_back(make_row(5.6, 7.0, Tolerance::relative(0.02, "")));
  rows.back().id = "X2";
  rows.back().title =
      "Pipelined, the compositors saturated: frame interval over the busiest compositor's time "
      "a frame, with every caster and the master by-passed";
  rows.push_back(make_row(11, std::nullopt, Tolerance::absolute(3, "")));
  rows.back().id = "X3";
  rows.back().error = "run peripheral-grid-ns11 failed: exit status 3";
  const std::string t = format_table(rows);
  std::cout << t;
  EXPECT_NE(t.find("seed"), std::string::npos);
  EXPECT_NE(t.find("simulated"), std::string::npos);
  EXPECT_NE(t.find("tolerance"), std::string::npos);
  EXPECT_NE(t.find("333.3 us"), std::string::npos);
  EXPECT_NE(t.find("339 us"), std::string::npos);
  EXPECT_NE(t.find("+1.70%"), std::string::npos);
  EXPECT_NE(t.find("+25.00%"), std::string::npos);
  EXPECT_NE(t.find("pass"), std::string::npos);
  EXPECT_NE(t.find("FAIL"), std::string::npos);
  EXPECT_NE(t.find("X1: a mean per ray"), std::string::npos);
  EXPECT_NE(t.find("X3: error: run peripheral-grid-ns11 failed"), std::string::npos);
  EXPECT_NE(t.find("3 measured, 0 derived, 0 qualitative; 1 of 3 measured pass"),
            std::string::npos);
  // A terminal's 120 columns: the figure and its source wrap under their column.
  EXPECT_NE(t.find("\n" + std::string(t.find("figure (source)") -
                                          t.rfind('\n', t.find("figure (source)")) - 1,
                                      ' ')),
            std::string::npos)
      << "X2's title continues on a line of its own";
  std::istringstream lines(t);
  for (std::string l; std::getline(lines, l);) {
    std::size_t columns = 0;
    for (unsigned char c : l) columns += (c & 0xC0) != 0x80 ? 1 : 0;
    EXPECT_LE(columns, 120u) << l;
  }
}

// Measured, qualitative and derived rows are printed in their own tables and counted apart;
// a derived row that disagrees still shows (and still fails the exit status), and a class error
// is never expected.
TEST(ValidateOutput, ClassesArePrintedApartAndCountedApart) {
  std::vector<Row> rows;
  rows.push_back(make_row(333.33, 339.0, Tolerance::relative(0.03, "")));
  rows.push_back(make_row(1.092, 1.092, Tolerance::relative(0.01, "")));
  rows.back().id = "W1c";
  rows.back().figure_class = FigureClass::kDerived;
  rows.push_back(make_row(0.8, 0.9, Tolerance::relative(0.01, "")));
  rows.back().id = "W1g";
  rows.back().figure_class = FigureClass::kDerived;
  rows.push_back(make_row(1, 2.0, Tolerance::above(1, "")));
  rows.back().id = "V9b";
  rows.back().figure_class = FigureClass::kQualitative;
  const std::string t = format_table(rows);
  std::cout << t;
  const auto qualitative = t.find("Qualitative (");
  const auto derived = t.find("Derived (");
  ASSERT_NE(qualitative, std::string::npos);
  ASSERT_NE(derived, std::string::npos);
  EXPECT_LT(t.find("X1"), qualitative);
  EXPECT_GT(t.find("V9b"), qualitative);
  EXPECT_LT(t.find("V9b"), derived);
  EXPECT_GT(t.find("W1c"), derived);
  EXPECT_NE(t.find("1 measured, 2 derived, 1 qualitative; 1 of 1 measured pass, 1 of 1 "
                   "qualitative hold, 1 of 2 derived agree"),
            std::string::npos);
  EXPECT_FALSE(rows[2].as_expected());
  EXPECT_EQ(rows_to_json(rows)[1]["class"], "derived");
  EXPECT_EQ(rows_to_json(rows)[3]["class"], "qualitative");
  rows[0].class_error = "classed measured but its value does not come from its runs";
  EXPECT_TRUE(rows[0].pass());
  EXPECT_FALSE(rows[0].as_expected());
  rows[0].open = "a known open figure";
  EXPECT_FALSE(rows[0].as_expected());
  EXPECT_NE(format_table(rows).find("FAIL (class)"), std::string::npos);
}

TEST(ValidateOutput, JsonAndCsvHoldTheSameRows) {
  std::vector<Row> rows;
  rows.push_back(make_row(333.33, 339.0, Tolerance::relative(0.03, "pipeline fill, 1.7%")));
  rows.back().title = "time per ray, brute force";  // a comma: quoted in the CSV
  rows.back().commands = {"rtsim run --machine ullner-peripheral"};
  rows.push_back(make_row(11, std::nullopt, Tolerance::range(2, 29, "interior")));
  rows.back().id = "X2";
  rows.back().error = "no \"value\"";
  const auto j = rows_to_json(rows);
  ASSERT_EQ(j.size(), 2u);
  EXPECT_EQ(j[0]["id"], "X1");
  EXPECT_EQ(j[0]["seed_value"], 333.33);
  EXPECT_EQ(j[0]["simulated_value"], 339.0);
  EXPECT_NEAR(j[0]["relative_error"].get<double>(), (339.0 - 333.33) / 333.33, 1e-12);
  EXPECT_EQ(j[0]["tolerance"]["kind"], "relative");
  EXPECT_EQ(j[0]["tolerance"]["value"], 0.03);
  EXPECT_EQ(j[0]["tolerance"]["why"], "pipeline fill, 1.7%");
  EXPECT_EQ(j[0]["pass"], true);
  EXPECT_EQ(j[0]["commands"][0], "rtsim run --machine ullner-peripheral");
  EXPECT_TRUE(j[1]["simulated_value"].is_null());
  EXPECT_TRUE(j[1]["relative_error"].is_null());
  EXPECT_EQ(j[1]["tolerance"]["lo"], 2);
  EXPECT_EQ(j[1]["tolerance"]["hi"], 29);
  EXPECT_EQ(j[1]["pass"], false);

  const std::string csv = rows_to_csv(rows);
  std::istringstream in(csv);
  std::string header, r1, r2, extra;
  std::getline(in, header);
  std::getline(in, r1);
  std::getline(in, r2);
  EXPECT_FALSE(std::getline(in, extra));
  EXPECT_EQ(header,
            "id,title,seed_ref,unit,seed_value,seed_display,simulated_value,relative_error,"
            "tolerance,pass,note,error,class,assumptions");
  EXPECT_EQ(r1.rfind("X1,\"time per ray, brute force\",seed 000 L1,us,333.33,,339,", 0), 0u) << r1;
  EXPECT_NE(r1.find(",pass,"), std::string::npos);
  EXPECT_NE(r2.find(",fail,"), std::string::npos);
  EXPECT_NE(r2.find("\"no \"\"value\"\"\""), std::string::npos) << r2;
  EXPECT_EQ(r1.substr(r1.size() - 10), ",measured,") << r1;
  EXPECT_EQ(j[0]["class"], "measured");
  EXPECT_EQ(csv_field("plain"), "plain");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
}

// ---- Plans ------------------------------------------------------------------------------------

TEST(ValidatePlan, SelectingAGroupKeepsItsMembersAndTheirRunsOnly) {
  Plan p;
  for (const char* id : {"V2a", "V2b", "V20", "V4"}) {
    Figure f;
    f.id = id;
    f.runs = {std::string("run-") + id};
    p.add_run(RunRequest{.key = f.runs[0], .args = {"run", id}});
    p.figures.push_back(f);
  }
  p.artifacts.push_back(Artifact{.file_name = "a.csv", .runs = {"run-V4"}, .contents = {}});
  const Plan s = select_figures(p, {"V2"});
  ASSERT_EQ(s.figures.size(), 2u);
  EXPECT_EQ(s.figures[0].id, "V2a");
  EXPECT_EQ(s.figures[1].id, "V2b");
  ASSERT_EQ(s.runs.size(), 2u);
  EXPECT_TRUE(s.artifacts.empty());
  const Plan exact = select_figures(p, {"V20", "V4"});
  EXPECT_EQ(exact.figures.size(), 2u);
  EXPECT_EQ(exact.artifacts.size(), 1u);
  EXPECT_EQ(select_figures(p, {}).figures.size(), 4u);
  EXPECT_THROW(select_figures(p, {"V3"}), std::invalid_argument);
  // Sharing: the same key with other arguments is a programming error.
  EXPECT_THROW(p.add_run(RunRequest{.key = "run-V4", .args = {"other"}}), std::logic_error);
  EXPECT_EQ(p.add_run(RunRequest{.key = "run-V4", .args = {"run", "V4"}}), "run-V4");
  EXPECT_EQ(p.runs.size(), 4u);
}

TEST(ValidatePlan, EveryFigureIsCompleteAndItsRunsExist) {
  for (bool quick : {true, false}) {
    const Plan plan = make_validation_plan(PlanOptions{.quick = quick});
    std::set<std::string> ids, keys;
    for (const auto& r : plan.runs) {
      EXPECT_TRUE(keys.insert(r.key).second) << "duplicate run " << r.key;
      ASSERT_FALSE(r.args.empty());
      EXPECT_TRUE(r.args[0] == "run" || r.args[0] == "render") << r.key;
    }
    for (const auto& f : plan.figures) {
      EXPECT_TRUE(ids.insert(f.id).second) << "duplicate figure " << f.id;
      EXPECT_FALSE(f.title.empty()) << f.id;
      EXPECT_FALSE(f.seed_ref.empty()) << f.id;
      EXPECT_FALSE(f.seed_text.empty()) << f.id;
      EXPECT_FALSE(f.workload.empty()) << f.id;
      EXPECT_GT(f.tolerance.why.size(), 20u) << f.id << ": say why the tolerance";
      EXPECT_TRUE(static_cast<bool>(f.measure)) << f.id;
      for (const auto& k : f.runs) EXPECT_TRUE(keys.count(k)) << f.id << " needs " << k;
    }
    for (const char* id : {"V1", "V2a", "V2b", "V2c", "V2d", "V4", "V5", "V8a", "V8b", "V8c", "V8d",
                           "V9a", "V9b", "VAX1", "VAX2"})
      EXPECT_TRUE(ids.count(id)) << id;
    // The brute-force run is the frame of V5: 512x512 in full mode, smaller in quick mode.
    const RunRequest* brute = plan.find_run("peripheral-brute-adders1");
    ASSERT_NE(brute, nullptr);
    const std::string side = quick ? std::to_string(kUllnerQuickSide) : "512";
    const auto w = std::find(brute->args.begin(), brute->args.end(), "--width");
    ASSERT_NE(w, brute->args.end());
    EXPECT_EQ(*(w + 1), side);
    const auto divisions = fig2_18_divisions(quick);
    EXPECT_EQ(divisions.size(), quick ? 12u : 30u);
    for (int n : divisions)
      EXPECT_TRUE(
          keys.count("peripheral-grid-ns" + std::string(n < 10 ? "0" : "") + std::to_string(n)))
          << n;
  }
}

TEST(ValidatePlan, FiguresWithoutRunsAreTheAnalyticModel) {
  const Plan plan = select_figures(make_validation_plan({}), {"V8a", "V8b", "V9a"});
  EXPECT_TRUE(plan.runs.empty());
  const auto rows = evaluate(plan, {});
  for (const auto& r : rows) {
    std::cout << r.id << ": seed "
              << (r.seed_display.empty() ? format_number(r.seed_value) : r.seed_display)
              << ", model " << format_number(r.simulated.value_or(NAN)) << " ("
              << r.tolerance.describe() << ")\n";
    EXPECT_TRUE(r.pass()) << r.id << " " << r.error;
  }
}

// The moves of W1h's assumptions: factors for numbers (as the run's own value times the
// factor, in whole picoseconds for times), stated values where the figure gives them.
TEST(ValidateSensitivity, PlanMovesEachAssumptionInTheRunsThatReadIt) {
  const Plan plan = select_figures(make_validation_plan(PlanOptions{.quick = true}), {"W1h"});
  const SensitivityPlan sp = make_sensitivity_plan(plan, SensitivityOptions{});
  std::map<std::string, std::string> value_of;  // "param label" -> the value given
  for (const auto& p : sp.perturbations) {
    EXPECT_EQ(p.figures, std::vector<std::string>{"W1h"});
    ASSERT_EQ(p.runs.size(), 1u) << p.param << " " << p.label << ": " << p.skipped;
    value_of[p.param + " " + p.label] = p.values.begin()->second;
  }
  EXPECT_EQ(value_of["pipeline.link.bit_time x0.5"], "3 ns");
  EXPECT_EQ(value_of["pipeline.link.bit_time x2"], "12 ns");
  EXPECT_EQ(value_of["pipeline.buffer_depth = 2"], "2");
  EXPECT_EQ(value_of["pipeline.buffer_depth = 4"], "4");
  EXPECT_EQ(value_of["host.rays_in_flight x2"], "8192");
  EXPECT_EQ(sp.runs.size(), 6u);
  // The moved run is the figure's run with one more -p, which wins over the preset.
  const auto& run = sp.runs.front();
  ASSERT_GE(run.args.size(), 2u);
  EXPECT_EQ(run.args[run.args.size() - 2], "-p");
  EXPECT_EQ(run.args.back(), "pipeline.link.bit_time=3000 ps");
  EXPECT_EQ(machine_of(run), "wang-bezier");
  EXPECT_TRUE(is_assumption_source("assumption: a 32-bit word a DSP cycle"));
  EXPECT_FALSE(is_assumption_source("seed 002 L437"));
  // An assumption nobody's run reads, or a seed-sourced parameter, is a programming error.
  const Figure& w1h = plan.figures.front();
  EXPECT_NE(assumption_problem(plan, w1h, {.param = "node.clock"}).find("no run of W1h"),
            std::string::npos);
  EXPECT_NE(
      assumption_problem(plan, w1h, {.param = "pipeline.split_u.cycles"}).find("not an assumption"),
      std::string::npos);
  EXPECT_NE(assumption_problem(plan, w1h, {.param = "pipeline.buffer_depth", .values = {"-1"}})
                .find("stated value -1"),
            std::string::npos);
}

// holds_over: the moves over which the base verdict stays, and where it changes.
TEST(ValidateSensitivity, HoldsOverNamesTheRangeAndWhereTheVerdictChanges) {
  Row base = make_row(2.0, 2.1, Tolerance::range(2, 10, ""));
  const SensitivityEntry half{
      .figure = "X1", .param = "p", .label = "x0.5", .factor = 0.5, .pass = false, .flips = true};
  const SensitivityEntry twice{
      .figure = "X1", .param = "p", .label = "x2", .factor = 2, .pass = true, .flips = false};
  const SensitivityEntry stated{
      .figure = "X1", .param = "p", .label = "= 0.9", .pass = false, .flips = true};
  EXPECT_EQ(holds_over(base, {&half, &twice}),
            "the base verdict (pass) holds over x1..x2; it changes at x0.5");
  EXPECT_EQ(holds_over(base, {&twice, &stated}),
            "the base verdict (pass) holds over x1..x2 and at no stated value; it changes at "
            "= 0.9");
  const std::vector<SensitivityEntry> entries = {half, twice};
  const std::string t = format_sensitivity({base}, entries);
  std::cout << t;
  EXPECT_NE(t.find("x0.5: "), std::string::npos);
  EXPECT_NE(t.find("<- verdict changes"), std::string::npos);
  EXPECT_NE(t.find("Verdicts that depend on an assumption (1)"), std::string::npos);
}

// docs/assumptions.md holds what `rtsim list assumptions --format markdown` prints.
TEST(ValidateDocs, AssumptionsPageIsCurrent) {
  const auto r = run_rtsim("list assumptions --format markdown");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const fs::path page = fs::path(RTSIM_TEST_DATA_DIR) / ".." / ".." / "docs" / "assumptions.md";
  const std::string text = read_file(page);
  EXPECT_NE(text.find(r.output), std::string::npos)
      << "docs/assumptions.md is stale: regenerate it with `build/rtsim list assumptions "
         "--format markdown` (its header says how)";
  EXPECT_NE(r.output.find("| `node.cpu_memory_share` | `0.6` |"), std::string::npos);
  EXPECT_EQ(r.output.find("| `quantum`"), std::string::npos) << "a simulator setting";
}

// ---- Evaluation -------------------------------------------------------------------------------

// check_classes: a measured or qualitative row must need its runs; a measured row's verdict
// must not follow a parameter its formula reads directly; a row without runs is derived.
TEST(ValidateClasses, EachClassIsCheckedForWhatItClaims) {
  RunResults results;
  results["run"] = ok_run("run", {{"simulated_time_s", 2.0e-3},
                                  {"rays", 400},
                                  {"params", {{"pipeline.interval", "5 us"}, {"n", "400"}}}});
  Plan plan;
  plan.add_run({.key = "run", .args = {"run"}});
  const auto param_us = [](const RunResults& r, const char* name) {
    const auto& p = stats_of(r, "run")["params"][name];
    return std::stod(p.get<std::string>());
  };
  Figure f;
  f.seed_value = 5.0;
  f.tolerance = Tolerance::relative(0.05, "");
  f.runs = {"run"};
  // A: measured from the run (frame over rays): passes every check.
  f.id = "A";
  f.measure = [](const RunResults& r) {
    return Measured{
        stats_number(r, "run", "simulated_time_s") / stats_number(r, "run", "rays") * 1e6, ""};
  };
  plan.figures.push_back(f);
  // B: "measured", but it is the parameter itself.
  f.id = "B";
  f.measure = [param_us](const RunResults& r) {
    return Measured{param_us(r, "pipeline.interval"), ""};
  };
  plan.figures.push_back(f);
  // C: the same, classed derived: nothing to object to.
  f.id = "C";
  f.figure_class = FigureClass::kDerived;
  plan.figures.push_back(f);
  // D: measured, the run's frame over a ray count its formula takes from the parameters: the
  // verdict follows `n` with nothing run again.
  f.id = "D";
  f.figure_class = FigureClass::kMeasured;
  f.measure = [param_us](const RunResults& r) {
    return Measured{stats_number(r, "run", "simulated_time_s") / param_us(r, "n") * 1e6, ""};
  };
  plan.figures.push_back(f);
  // E: the same, qualitative: only the need for a run is checked, which it has.
  f.id = "E";
  f.figure_class = FigureClass::kQualitative;
  plan.figures.push_back(f);
  // F and G: no run. Derived is right; measured is not.
  f.runs = {};
  f.measure = [](const RunResults&) { return Measured{5.0, ""}; };
  f.id = "F";
  f.figure_class = FigureClass::kDerived;
  plan.figures.push_back(f);
  f.id = "G";
  f.figure_class = FigureClass::kMeasured;
  plan.figures.push_back(f);

  const auto rows = evaluate(plan, results);
  ASSERT_EQ(rows.size(), 7u);
  for (const auto& r : rows) {
    std::cout << r.id << ": " << (r.class_error.empty() ? "ok" : r.class_error) << "\n";
    EXPECT_TRUE(r.pass()) << r.id;
  }
  EXPECT_EQ(rows[0].class_error, "");
  EXPECT_TRUE(rows[0].formula_params.empty());
  EXPECT_NE(rows[1].class_error.find("does not come from its runs"), std::string::npos);
  EXPECT_FALSE(rows[1].as_expected());
  EXPECT_EQ(rows[2].class_error, "");
  EXPECT_NE(rows[3].class_error.find("verdict follows n"), std::string::npos);
  EXPECT_EQ(rows[3].formula_params, std::vector<std::string>{"n"});
  EXPECT_EQ(rows[4].class_error, "");
  EXPECT_EQ(rows[5].class_error, "");
  EXPECT_NE(rows[6].class_error.find("runs nothing"), std::string::npos);
}

// Every registered figure is classed, and every assumption a row names is a parameter of one
// of its runs' machines whose source is an assumption.
TEST(ValidateClasses, EveryRowIsClassedAndNamesRealAssumptions) {
  const Plan plan = make_validation_plan(PlanOptions{.quick = true});
  std::map<std::string, int> per_class;
  for (const auto& f : plan.figures) {
    ++per_class[class_name(f.figure_class)];
    if (f.runs.empty()) {
      EXPECT_EQ(f.figure_class, FigureClass::kDerived) << f.id;
    }
    if (f.figure_class == FigureClass::kDerived) {
      EXPECT_TRUE(f.assumptions.empty()) << f.id;
    }
    for (const auto& a : f.assumptions) {
      const auto problem = assumption_problem(plan, f, a);
      EXPECT_EQ(problem, "") << f.id << ": " << a.param;
    }
  }
  for (const auto& [c, n] : per_class) std::cout << c << ": " << n << "\n";
  EXPECT_GT(per_class["measured"], 0);
  EXPECT_GT(per_class["derived"], 0);
  EXPECT_GT(per_class["qualitative"], 0);
}

TEST(ValidateEvaluate, FailedRunsAndMissingKeysBecomeRowErrors) {
  RunResults results;
  results["good"] = ok_run("good", {{"peripheral", {{"time_per_ray_s", 339e-6}}}});
  RunOutcome bad;
  bad.request.key = "bad";
  bad.exit_code = 2;
  bad.failure = "exit status 2: unknown parameter";
  results["bad"] = bad;
  EXPECT_DOUBLE_EQ(stats_number(results, "good", "peripheral.time_per_ray_s"), 339e-6);
  try {
    stats_number(results, "good", "peripheral.tests_per_ray");
    FAIL() << "no throw";
  } catch (const MeasureError& e) {
    EXPECT_NE(std::string(e.what()).find("has no peripheral.tests_per_ray"), std::string::npos);
  }
  EXPECT_THROW(stats_of(results, "bad"), MeasureError);
  EXPECT_THROW(stats_of(results, "absent"), MeasureError);

  Plan plan;
  plan.add_run({.key = "good", .args = {"run"}});
  plan.add_run({.key = "bad", .args = {"run", "-p", "x=1"}});
  Figure f;
  f.id = "A";
  f.seed_value = 333.33;
  f.tolerance = Tolerance::relative(0.03, "");
  f.runs = {"good"};
  f.measure = [](const RunResults& r) {
    return Measured{stats_number(r, "good", "peripheral.time_per_ray_s") * 1e6, "note"};
  };
  plan.figures.push_back(f);
  f.id = "B";
  f.runs = {"bad"};
  f.measure = [](const RunResults& r) {
    return Measured{stats_number(r, "bad", "peripheral.time_per_ray_s"), ""};
  };
  plan.figures.push_back(f);
  f.id = "C";
  f.seed_from_run = true;
  f.runs = {"good"};
  f.measure = [](const RunResults&) { return Measured{2.0, "", 2.0}; };
  plan.figures.push_back(f);

  const auto rows = evaluate(plan, results);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_TRUE(rows[0].pass());
  EXPECT_EQ(rows[0].note, "note");
  EXPECT_EQ(rows[0].commands, std::vector<std::string>{"rtsim run"});
  EXPECT_FALSE(rows[1].pass());
  EXPECT_NE(rows[1].error.find("run bad failed: exit status 2"), std::string::npos);
  EXPECT_EQ(rows[1].commands, std::vector<std::string>{"rtsim run -p x=1"});
  EXPECT_DOUBLE_EQ(rows[2].seed_value, 2.0);  // the reference replaces the seed value
  EXPECT_TRUE(rows[2].pass());
}

// ---- Curve shape and Ullner's analytic model (Fig. 2-18) ---------------------------------------

TEST(ValidateCurve, ShapeOfASampledCurve) {
  // y = 100/x + x: minimum at 10 (y = 20); y(5) = 25, y(20) = 25: the rises are equal.
  std::vector<CurvePoint> c;
  for (int x = 1; x <= 30; ++x) c.push_back({double(x), 100.0 / x + x});
  const auto s = curve_shape(c);
  EXPECT_EQ(s.argmin, 10);
  EXPECT_DOUBLE_EQ(s.minimum, 20);
  EXPECT_DOUBLE_EQ(s.left_rise, 5);
  EXPECT_DOUBLE_EQ(s.right_rise, 5);
  EXPECT_DOUBLE_EQ(s.steepness, 1);
  EXPECT_FALSE(s.left_clamped);
  EXPECT_FALSE(s.right_clamped);
  // Interpolation between samples, clamped at the ends.
  EXPECT_DOUBLE_EQ(interpolate({{1, 10}, {3, 30}}, 2), 20);
  EXPECT_DOUBLE_EQ(interpolate({{1, 10}, {3, 30}}, 0), 10);
  EXPECT_DOUBLE_EQ(interpolate({{1, 10}, {3, 30}}, 9), 30);
  // 2 x argmin past the last sample: the last one is used and flagged.
  const auto clamped = curve_shape({{1, 5}, {2, 3}, {3, 4}});
  EXPECT_EQ(clamped.argmin, 2);
  EXPECT_TRUE(clamped.right_clamped);
  EXPECT_DOUBLE_EQ(clamped.right_rise, 1);
  // A flat right side with a rising left is infinitely steeper on the left.
  EXPECT_TRUE(std::isinf(curve_shape({{1, 9}, {2, 1}, {4, 1}}).steepness));
  EXPECT_THROW(curve_shape({}), std::invalid_argument);
  EXPECT_THROW(curve_shape({{2, 1}, {1, 1}}), std::invalid_argument);
}

TEST(ValidateCurve, UllnerModelHasTheThesisMinimumAndIsSteeperOnTheLeft) {
  // Seed 000 L654: minimum 14.3 us per ray at n_s = 11; L656: steeper left of the minimum.
  std::vector<int> all;
  for (int n = 1; n <= 30; ++n) all.push_back(n);
  const auto curve = fig2_18_model_curve(all);
  const auto s = curve_shape(curve);
  std::cout << "Fig. 2-18 model: argmin " << s.argmin << " (thesis 11), minimum " << s.minimum
            << " us (thesis 14.3, tolerance 0.5%: three printed digits), steepness " << s.steepness
            << " (> 1: steeper left)\n";
  EXPECT_EQ(s.argmin, 11);
  EXPECT_NEAR(s.minimum, 14.3, 14.3 * 0.005);
  EXPECT_GT(s.steepness, 1.0);
  // Spot values of note 000 §2.5's recomputed table (n_s = 1, 4, 20, 30), to its 4 digits.
  EXPECT_NEAR(curve[0].y, 339.9, 0.05);
  EXPECT_NEAR(curve[3].y, 28.0, 0.05);
  EXPECT_NEAR(curve[19].y, 16.92, 0.005);
  EXPECT_NEAR(curve[29].y, 21.47, 0.005);
  // The quick subset keeps the minimum and both sides.
  const auto quick = curve_shape(fig2_18_model_curve(fig2_18_divisions(true)));
  EXPECT_EQ(quick.argmin, 11);
  EXPECT_GT(quick.steepness, 1.0);
  EXPECT_FALSE(quick.left_clamped);
  EXPECT_FALSE(quick.right_clamped);
}

TEST(ValidateVax, GaudetsFig14EstimateIs238Hours) {
  // seed 001 L322: R_t = 1,824,915.46; L326: T_t = R_t (T_s + T_i O) ~ 238 h.
  EXPECT_NEAR(gaudet_fig1_4_rays(), 1824915.46, 0.01);
  const double hours =
      gaudet_fig1_4_rays() * (kVaxRayTime + kVaxIntersectionTime * kGaudetFig14Objects) / 3600;
  std::cout << "Gaudet Fig 1-4 on the VAX: " << hours << " h (seed: about 238 h)\n";
  EXPECT_NEAR(hours, 238.05, 0.01);
}

// ---- The runner and the command, against the fake rtsim ---------------------------------------

TEST(ValidateRunner, RunsInParallelAndReportsFailures) {
  if (!have_python()) GTEST_SKIP() << "/usr/bin/python3 missing: the fake rtsim needs it";
  const auto dir = scratch_dir("validate-runner");
  std::vector<RunRequest> reqs;
  for (int i = 0; i < 5; ++i) {
    reqs.push_back({.key = "vax-" + std::to_string(i),
                    .args = {"run", "--machine", kVaxMachine, "--scene", "builtin:default",
                             "--width", std::to_string(4 + i), "--height", "4"},
                    .cost_hint = double(i)});
  }
  reqs.push_back({.key = "bad-fails", .args = {"run", "--machine", kVaxMachine}});
  ScopedEnv fail("FAKE_RTSIM_FAIL", "-fails");
  int calls = 0, last_done = 0;
  const auto results = run_all(reqs, {.executable = kFake,
                                      .work_dir = dir,
                                      .jobs = 3,
                                      .on_finished = [&](const RunOutcome&, int done, int total) {
                                        ++calls;
                                        EXPECT_EQ(total, 6);
                                        EXPECT_EQ(done, last_done + 1);
                                        last_done = done;
                                      }});
  EXPECT_EQ(calls, 6);
  ASSERT_EQ(results.size(), 6u);
  for (int i = 0; i < 5; ++i) {
    const auto& o = results.at("vax-" + std::to_string(i));
    EXPECT_EQ(o.exit_code, 0) << o.failure;
    EXPECT_TRUE(o.failure.empty());
    ASSERT_TRUE(o.stats.has_value());
    EXPECT_EQ((*o.stats)["width"], 4 + i);
    EXPECT_EQ(o.out_dir, dir / ("vax-" + std::to_string(i)));
  }
  const auto& bad = results.at("bad-fails");
  EXPECT_EQ(bad.exit_code, 3);
  EXPECT_NE(bad.failure.find("exit status 3"), std::string::npos) << bad.failure;
  EXPECT_NE(bad.failure.find("failing on purpose"), std::string::npos) << bad.failure;
  EXPECT_FALSE(bad.stats.has_value());

  const auto missing = run_all({{.key = "x", .args = {"run"}}},
                               {.executable = dir / "no-such-binary", .work_dir = dir, .jobs = 1});
  EXPECT_FALSE(missing.at("x").failure.empty());
  fs::remove_all(dir);
}

TEST(ValidateCommand, QuickValidationAgainstAFakeThatFollowsTheSeedsPasses) {
  if (!have_python()) GTEST_SKIP() << "/usr/bin/python3 missing: the fake rtsim needs it";
  const auto dir = scratch_dir("validate-fake");
  // The fake answers the peripheral and the VAX (gaudet-pert's figures run on the real binary
  // in RealQuickValidationPasses).
  const auto r = run_rtsim(
      "validate --quick --jobs 2 --only V1,V2,V4,V5,V8,V9,V10,V11,G1,VAX1,VAX2,VAX3,VAX4,VAX5 "
      "--rtsim " +
      kFake + " --out " + dir.string());
  std::cout << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("measured pass"), std::string::npos);
  const auto doc = nlohmann::json::parse(read_file(dir / "validation.json"));
  EXPECT_EQ(doc["mode"], "quick");
  EXPECT_EQ(doc["class_errors"].size(), 0u);
  EXPECT_EQ(doc["pass"], true);
  EXPECT_EQ(doc["failed"], 0);
  EXPECT_EQ(doc["rows"].size(), doc["figures"].get<std::size_t>());
  EXPECT_GE(doc["rows"].size(), 20u);
  for (const auto& row : doc["rows"]) EXPECT_TRUE(row["pass"].get<bool>()) << row["id"];
  // CSV: a header and one line per figure.
  std::istringstream csv(read_file(dir / "validation.csv"));
  std::string line;
  std::size_t lines = 0;
  while (std::getline(csv, line)) ++lines;
  EXPECT_EQ(lines, doc["rows"].size() + 1);
  // fig2-18.csv: a header and one line per n_s of the quick sweep, both curves filled.
  std::istringstream fig(read_file(dir / "fig2-18.csv"));
  std::getline(fig, line);
  EXPECT_EQ(line.rfind("n_s,model_t_r_us,simulated_t_r_us,", 0), 0u);
  std::size_t points = 0;
  while (std::getline(fig, line)) {
    ++points;
    EXPECT_EQ(line.find(",,"), std::string::npos) << line;
  }
  EXPECT_EQ(points, fig2_18_divisions(true).size());
  // Run folders are temporary: none is left without --keep.
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_FALSE(e.is_directory()) << e.path() << " left behind";
  fs::remove_all(dir);
}

TEST(ValidateCommand, AFailedRunOrAFigureOutOfToleranceFailsTheValidation) {
  if (!have_python()) GTEST_SKIP() << "/usr/bin/python3 missing: the fake rtsim needs it";
  {
    const auto dir = scratch_dir("validate-fail-run");
    ScopedEnv fail("FAKE_RTSIM_FAIL", "-ns11");
    const auto r =
        run_rtsim("validate --quick --only V8c,V1 --rtsim " + kFake + " --out " + dir.string());
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("V8c: error: 1 of 12 sweep runs unusable"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("0 of 1 measured pass"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("1 of 1 derived agree"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("kept: 1 run(s) failed"), std::string::npos) << r.output;
    const auto doc = nlohmann::json::parse(read_file(dir / "validation.json"));
    EXPECT_EQ(doc["failed"], 1);
    fs::remove_all(dir);
  }
  {
    const auto dir = scratch_dir("validate-fail-skew");
    ScopedEnv skew("FAKE_RTSIM_SKEW", "1.1");  // 10% slower rays: V4 (3%) must fail
    const auto r =
        run_rtsim("validate --quick --only V4 --rtsim " + kFake + " --out " + dir.string());
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("FAIL"), std::string::npos) << r.output;
    fs::remove_all(dir);
  }
}

TEST(ValidateCommand, BadUsageExitsWithTwo) {
  EXPECT_EQ(run_rtsim("validate --only NOPE --quick").exit_code, 2);
  EXPECT_EQ(run_rtsim("validate --jobs 0").exit_code, 2);
  EXPECT_EQ(run_rtsim("validate --frobnicate").exit_code, 2);
  const auto factors = run_rtsim("validate --quick --sensitivity --factors 0.5,-2 --only X4b");
  EXPECT_EQ(factors.exit_code, 2);
  EXPECT_NE(factors.output.find("'-2' is not a positive number"), std::string::npos)
      << factors.output;
  const auto list = run_rtsim("validate --list --only V2");
  EXPECT_EQ(list.exit_code, 0);
  EXPECT_NE(list.output.find("V2a"), std::string::npos);
  EXPECT_NE(list.output.find("V2d"), std::string::npos);
  EXPECT_EQ(list.output.find("V4 "), std::string::npos);
}

// ---- The real thing, once `rtsim run` exists ---------------------------------------------------

// Figures the real machines do not meet yet, with the reason; docs/validation.md ("Open
// figures") says more. The test fails if any other figure fails, and says so when one of these
// starts to pass (then remove it here and in the docs).
// Figures known to fail, with the reason (none now: Fig. 2-18 runs on builtin:ullner-sheets-1000,
// the scene its text describes; on random squares its minimum is ~22 us, see docs/validation.md).
const std::map<std::string, std::string> kOpenFigures = {
    {"P4a",
     "Fig. 6-11's order effect is not reproduced: a ShellProcessor spends ~40 us a box test, so "
     "the bus has cycled several times whenever it asks again (docs/validation.md)"},
    {"P4b", "as P4a"},
    {"HL2b",
     "a plane processor holds its intersection until the next message, a cleanup processor its "
     "segment until the next segment: a hop costs the spacing of segments, not one message time "
     "(docs/validation.md)"},
    {"HL3", "as HL2b"},
    {"V17c",
     "L891 assumes every processor is kept busy fetching; simulated, their CPUs' other work and "
     "waiting take most of the frame (docs/validation.md)"},
    {"V17d", "as V17c"},
    {"V19",
     "with the CPU's own bus traffic on the shared memory the array is about 2x the peripheral, "
     "at the edge of \"a few times\" (docs/validation.md)"},
    {"PF3b",
     "L130's formula has stages that never wait for one another; the model's nodes hold few "
     "regions, so a shader busy with pins holds up the in-order composition (docs/validation.md)"},
    {"PF7a",
     "the composition network every node shares sets the pace at 6 + 24 nodes at L120's rate "
     "(docs/validation.md)"}};

// A sensitivity run on one machine (pxpl5-raytrace): X4b's master share rests on the master's
// assumed cost a region, and the run says so.
TEST(ValidateCommand, SensitivityShowsWhichAssumptionAVerdictRestsOn) {
  const auto dir = scratch_dir("validate-sensitivity");
  const auto r =
      run_rtsim("validate --quick --sensitivity --only X4b --jobs 2 --out " + dir.string());
  std::cout << r.output;
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.output.find("Verdicts that depend on an assumption (1)"), std::string::npos);
  const auto doc = nlohmann::json::parse(read_file(dir / "validation-sensitivity.json"));
  EXPECT_EQ(doc["mode"], "quick");
  bool assign_half = false;
  for (const auto& e : doc["entries"]) {
    EXPECT_EQ(e["figure"], "X4b");
    if (e["param"] == "master.assign_time" && e["label"] == "x0.5") {
      assign_half = true;
      EXPECT_EQ(e["flips"], true) << "a master half as slow no longer saturates";
      EXPECT_LT(e["relative_change"].get<double>(), 0.0);
    }
  }
  EXPECT_TRUE(assign_half);
  ASSERT_EQ(doc["verdict_depends"].size(), 1u);
  EXPECT_EQ(doc["verdict_depends"][0]["param"], "master.assign_time");
  // The picture is drawn where matplotlib is installed (docs/validation.md).
  if (r.output.find("no validation-sensitivity.png") == std::string::npos) {
    EXPECT_TRUE(fs::exists(dir / "validation-sensitivity.png"));
  }
  fs::remove_all(dir);
}

TEST(ValidateCommand, RealQuickValidationPasses) {
  // Activates by itself when the SystemC machines land: `rtsim run --help` must describe the
  // real command (the placeholder has no --machine option).
  const auto help = run_rtsim("run --help");
  if (help.exit_code != 0 || help.output.find("--machine") == std::string::npos)
    GTEST_SKIP() << "`rtsim run` is not built yet (its --help has no --machine); the real "
                    "`rtsim validate --quick` runs once it is";
  const auto dir = scratch_dir("validate-real");
  const auto r = run_rtsim("validate --quick --jobs 2 --out " + dir.string());
  std::cout << r.output;
  // Exit 0: every figure passes but the known open ones (which do not count).
  EXPECT_EQ(r.exit_code, 0) << "a figure expected to pass failed, or validate itself did";
  const auto doc = nlohmann::json::parse(read_file(dir / "validation.json"));
  EXPECT_EQ(doc["pass"], true);
  for (const auto& id : doc["known_open_failing"])
    EXPECT_TRUE(kOpenFigures.count(id.get<std::string>())) << id;
  for (const auto& run : doc["runs"])
    EXPECT_EQ(run["failure"], "") << run["command"].get<std::string>();
  EXPECT_TRUE(fs::exists(dir / "fig2-18.csv"));
  for (const auto& row : doc["rows"]) {
    const std::string id = row["id"];
    const bool pass = row["pass"];
    const auto open = kOpenFigures.find(id);
    // validation.json says which figures are known open, and why.
    EXPECT_EQ(row["open"].is_string(), open != kOpenFigures.end()) << id;
    if (open == kOpenFigures.end()) {
      EXPECT_TRUE(pass) << id << " (" << row["title"].get<std::string>()
                        << ") is out of tolerance; see the table above";
      EXPECT_TRUE(row["error"].get<std::string>().empty()) << id << ": " << row["error"];
    } else if (pass) {
      std::cout << "NOTE: open figure " << id << " now passes: remove it from kOpenFigures "
                << "and from docs/validation.md\n";
    } else {
      std::cout << "open figure " << id << " still fails (known): " << open->second << "\n";
    }
  }
  fs::remove_all(dir);
}
