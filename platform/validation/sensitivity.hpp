#pragma once
// `rtsim validate --sensitivity`: each assumption a figure names (a parameter whose source is not
// a seed line) is moved, by factors (default x0.5 and x2) or to the values the figure states, in
// every run of the figure whose machine reads it; the figures are evaluated again on those runs,
// and the report says which assumptions move which figure, by how much, and whether the verdict
// changes (issue 35, DESIGN.md "Validation").
//
//   SensitivityPlan sp = make_sensitivity_plan(plan, {});
//   ... run plan.runs and sp.runs (run_queue.hpp, or MPI ranks) into `results` ...
//   auto entries = evaluate_sensitivity(plan, base_rows, sp, results);
//   std::cout << format_sensitivity(base_rows, entries);
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "platform/validation/validation.hpp"

namespace rtsim::validation {

/// Whether a parameter's source says it is an assumption (not a seed line): "assumption" in it.
/// Settings of the simulator, a study or a test say so instead and are not assumptions.
bool is_assumption_source(std::string_view source);

/// The machine a run request runs (its --machine), or "" (`rtsim render`).
std::string machine_of(const RunRequest& run);

/// Why `a` cannot be moved for figure `f` of `plan`, or "" if it can: no run of f is on a
/// machine that reads it, its source is not an assumption, or a stated value does not parse.
std::string assumption_problem(const Plan& plan, const Figure& f, const AssumptionRef& a);

struct SensitivityOptions {
  std::vector<double> factors = {0.5, 2.0};  ///< for numeric assumptions without stated values
};

/// One move of one assumption, and the runs it needs again.
struct Perturbation {
  std::string param;
  std::string label;                   ///< "x0.5", "x2", "= after_handing_out"
  double factor = 0.0;                 ///< 0 for a stated value
  std::vector<std::string> figures{};  ///< ids of the figures that name it so
  /// Base run key -> the perturbed run's key, and the value it is given (as for -p). A run
  /// that sets the parameter itself keeps a stated value (it is studying that parameter);
  /// a factor scales its own value.
  std::map<std::string, std::string> runs{};
  std::map<std::string, std::string> values{};
  std::string skipped{};  ///< why nothing runs (no other value within its bounds)
};

struct SensitivityPlan {
  std::vector<Perturbation> perturbations{};
  std::vector<RunRequest> runs{};  ///< the perturbed runs (the base runs are the plan's)
};

/// The perturbations of every assumption the plan's figures name (derived figures name none).
/// std::logic_error for an assumption_problem (a programming error in a figures file).
SensitivityPlan make_sensitivity_plan(const Plan& plan, const SensitivityOptions& options);

/// A figure under one perturbation.
struct SensitivityEntry {
  std::string figure, param, label;
  double factor = 0.0;
  std::optional<double> simulated{};
  std::string error{};
  std::optional<double> relative_change{};  ///< (moved - base) / |base|
  bool pass = false;
  bool flips = false;  ///< the verdict differs from the base run's
};

/// Every figure under every perturbation that names it, from the base and perturbed runs.
std::vector<SensitivityEntry> evaluate_sensitivity(const Plan& plan,
                                                   const std::vector<Row>& base_rows,
                                                   const SensitivityPlan& sensitivity,
                                                   const RunResults& results);

/// Over which of the moves tried of one assumption a figure keeps its base verdict: "the base
/// verdict (pass) holds over x1..x2; it changes at x0.5", or for stated values "... holds at
/// = 0.9; it changes at = 0.3".
std::string holds_over(const Row& base, const std::vector<const SensitivityEntry*>& entries);

/// The report: per figure, each assumption's moves (value, change, verdict), then the figures
/// whose verdict depends on an assumption.
std::string format_sensitivity(const std::vector<Row>& base_rows,
                               const std::vector<SensitivityEntry>& entries);

/// validation-sensitivity.json's "perturbations", "entries" and "verdict_depends".
nlohmann::ordered_json sensitivity_to_json(const std::vector<Row>& base_rows,
                                           const SensitivityPlan& sensitivity,
                                           const std::vector<SensitivityEntry>& entries);

}  // namespace rtsim::validation
