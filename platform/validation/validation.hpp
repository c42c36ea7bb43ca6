#pragma once
// The validation framework behind `rtsim validate`: a figure from a seed (what the seed says,
// with its line), the runs of the rtsim binary it needs, how its simulated value is read from
// their stats.json, and the tolerance it is judged with and why.
//
// A Plan holds the runs and the figures. Runs are executed by platform/runs/run_queue.hpp (each
// `rtsim run` is its own process: SystemC allows one simulation per process); evaluate() turns the
// runs' results into one Row per figure; the rows are written as a text table, JSON and CSV.
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "platform/runs/run_request.hpp"

namespace rtsim::validation {

/// What kind of reproduction a figure is (DESIGN.md "Validation"). A figure equal to a parameter
/// or a product of parameters is never measured; evaluate() checks what it can of that.
enum class FigureClass {
  /// Read from a simulated run in which it emerges from the modules' interaction: a frame time,
  /// a throughput counted from completed jobs, a latency from the probe, a utilisation.
  kMeasured,
  /// Arithmetic the seed itself does on stated numbers (a cycle = cycles x clock, the thesis's
  /// simple analysis), checked against the model's parameters: it moves with them by nature.
  kDerived,
  /// A shape or an order the seed states without a number ("steeper on the left", "most idle").
  kQualitative,
};

/// "measured", "derived", "qualitative".
const char* class_name(FigureClass c);

/// An assumption (a parameter whose source is not a seed line) a figure's runs depend on, and
/// how `rtsim validate --sensitivity` moves it: by the factors asked for (default x0.5 and x2),
/// or to the values stated here (a range the seed's own numbers bound, the other choices of a
/// string parameter).
struct AssumptionRef {
  std::string param{};                ///< "node.clock"
  std::vector<std::string> values{};  ///< empty: the factors; else these values, as for -p
  std::string why{};                  ///< why these values (docs/validation.md)
};

/// How a simulated value is judged against the seed's value.
struct Tolerance {
  enum class Kind {
    kRelative,  ///< |simulated - seed| <= value * |seed|
    kAbsolute,  ///< |simulated - seed| <= value
    kAbove,     ///< simulated > value (a qualitative "more than" figure)
    kRange,     ///< lo <= simulated <= hi
  };
  Kind kind = Kind::kRelative;
  double value = 0.0;
  double lo = 0.0;
  double hi = 0.0;
  std::string why;  ///< the reason this tolerance, and not a tighter one, is right

  static Tolerance relative(double fraction, std::string why);
  static Tolerance absolute(double amount, std::string why);
  static Tolerance above(double bound, std::string why);
  static Tolerance range(double lo, double hi, std::string why);

  /// Whether `simulated` passes against `seed`. A non-finite value never passes.
  bool accepts(double seed, double simulated) const;
  /// Short form for the table: "±2%", "±3", "> 1", "[2, 29]".
  std::string describe() const;
};

// The runs a plan needs are platform/runs' requests.
using runs::RunOutcome;
using runs::RunRequest;
using runs::RunResults;

/// `rtsim run --machine MACHINE --scene SCENE --width W --height H -q -p P...`: the request of a
/// figure's run.
RunRequest machine_run_request(std::string key, const std::string& machine,
                               const std::string& scene, int width, int height,
                               const std::vector<std::string>& params, double cost_hint);

/// Thrown by a figure's measure function when its value cannot be had (a run failed, a
/// stats.json key is missing); the message goes into the row.
struct MeasureError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A simulated value and how it was obtained (quick-mode scaling, the points used...).
struct Measured {
  double value = 0.0;
  std::string note{};
  /// The seed's value when it depends on the run (a formula evaluated on the run's own counts,
  /// like Gaudet's T_t = R_t (T_s + T_i O)); replaces Figure::seed_value in the row.
  std::optional<double> reference{};
};

/// One seed figure.
struct Figure {
  std::string id;         ///< "V4"; a trailing lower-case letter marks a member of a group ("V2a")
  std::string title;      ///< what is measured
  std::string seed_ref;   ///< "seed 000 L590"
  std::string seed_text;  ///< the seed's words or derivation, for the docs and the JSON
  double seed_value = 0.0;
  /// For a qualitative figure ("steeper on the left"), what the table shows instead of
  /// seed_value; such a row has no relative error.
  std::string seed_display{};
  /// The seed's value is a formula on the run's counts (Measured::reference), not a constant.
  bool seed_from_run = false;
  std::string unit;  ///< the unit of seed_value and of the measured value ("us", "s", "")
  Tolerance tolerance;
  std::string workload;           ///< what is run, in words
  std::vector<std::string> runs;  ///< keys of the RunRequests whose results it reads
  std::function<Measured(const RunResults&)> measure;
  /// A known open figure: why the model does not reproduce it yet (docs/validation.md). It is
  /// still judged; a failure shows as "FAIL (open)" and validation.json carries the reason.
  std::string open{};
  /// Measured, derived or qualitative. A derived row restates the model's parameters (a
  /// substage's cycles times the clock): it checks that the configuration is the seed's, it
  /// cannot fail unless a parameter is changed, so it is printed apart.
  FigureClass figure_class = FigureClass::kMeasured;
  /// The assumptions the figure's runs depend on: `validate --sensitivity` moves each.
  std::vector<AssumptionRef> assumptions{};
};

/// A figure's verdict: a row of the table.
struct Row {
  std::string id{}, title{}, seed_ref{}, seed_text{}, seed_display{}, unit{}, workload{};
  double seed_value = 0.0;
  std::optional<double> simulated{};
  Tolerance tolerance{};
  std::string note{};                   ///< from Measured::note
  std::string error{};                  ///< why there is no value (then the row fails)
  std::vector<std::string> commands{};  ///< command lines of its runs
  std::string open{};                   ///< Figure::open
  FigureClass figure_class = FigureClass::kMeasured;
  std::vector<std::string> assumptions{};  ///< Figure::assumptions, the parameters' names
  /// The class does not hold (check_classes): a measured or qualitative row whose value does
  /// not come from its runs, or a measured row whose verdict follows a parameter its formula
  /// reads directly. Fails the validation, like an error.
  std::string class_error{};
  /// Parameters of its runs that the row's formula reads directly (from stats.json's params):
  /// moving one moves the value without a run.
  std::vector<std::string> formula_params{};

  bool pass() const;
  /// Passes, or is a known open figure that fails with a value (an error still counts): what
  /// `rtsim validate`'s exit status judges. A class error is never expected.
  bool as_expected() const {
    return class_error.empty() && (pass() || (!open.empty() && error.empty()));
  }
  /// (simulated - seed) / |seed|; empty without a value, for a qualitative figure, or when
  /// the seed value is 0.
  std::optional<double> relative_error() const;
};

/// Side output written after the runs (e.g. the two curves of Fig. 2-18 as CSV).
struct Artifact {
  std::string file_name;
  std::vector<std::string> runs;  ///< keys it reads; it is written only if all were selected
  std::function<std::string(const RunResults&)> contents;
};

/// Size and mode of a validation: quick shrinks images so the suite runs in CI.
struct PlanOptions {
  bool quick = false;
};

struct Plan {
  std::vector<RunRequest> runs;
  std::vector<Figure> figures;
  std::vector<Artifact> artifacts;

  /// Adds a run unless one with the same key exists (figures share runs); returns the key (a
  /// copy: a reference into `runs` would dangle once a later run grows it).
  std::string add_run(RunRequest run);
  /// Sets the class and the assumptions of the figures named `ids` (exact ids, or groups: "P9"
  /// names P9a, P9b, ...), for figures built in loops or by helpers. std::logic_error if an id
  /// names none.
  void classify(const std::vector<std::string>& ids, FigureClass figure_class,
                const std::vector<AssumptionRef>& assumptions = {});
  const RunRequest* find_run(const std::string& key) const;
};

/// Keep only the figures named by `ids` (an exact id, or a group: "V2" keeps V2a, V2b, ...)
/// and the runs they need. Throws std::invalid_argument naming an id that matches nothing.
Plan select_figures(const Plan& plan, const std::vector<std::string>& ids);

/// The rows of every figure of the plan, from the runs' results, with their classes checked
/// (check_classes).
std::vector<Row> evaluate(const Plan& plan, const RunResults& results);

/// Checks what can be checked of each row's class, into Row::class_error and
/// Row::formula_params:
///  - a measured or qualitative row must need its runs: its value is evaluated again on the
///    runs' stats.json with every number outside `params` scrambled, and must move (else it is a
///    parameter or a constant: derived);
///  - a row of runs cannot be derived from no run, and a row without runs must be derived;
///  - a measured row's verdict must not follow a parameter its formula reads directly: each
///    number in its runs' `params` is moved x0.5 and x2 with nothing run again, and the verdict
///    must stay (the parameters it moves the value at all are its formula_params).
void check_classes(const Plan& plan, const RunResults& results, std::vector<Row>& rows);

/// Readers for the measure functions. Each throws MeasureError with a clear message.
const nlohmann::json& stats_of(const RunResults& results, const std::string& key);
/// A figure whose value is one number of one run's stats.json (`path`, times `scale`): the
/// common case of a figures file.
Figure stats_figure(std::string id, std::string title, std::string seed_ref, std::string seed_text,
                    double seed_value, std::string unit, Tolerance tolerance, std::string workload,
                    const std::string& key, std::string path, double scale);
/// A time parameter of a run, in seconds, from its stats.json `params` ("760 us").
double param_seconds(const RunResults& results, const std::string& key, const std::string& name);
/// A plain-number parameter of a run (a count, a ratio), from its stats.json `params` ("4").
double param_number(const RunResults& results, const std::string& key, const std::string& name);
/// Value at a dotted path ("peripheral.time_per_ray_s") of a run's stats.json.
double stats_number(const RunResults& results, const std::string& key, const std::string& path);

/// Output.
std::string format_number(double v);
std::string format_table(const std::vector<Row>& rows);
nlohmann::ordered_json rows_to_json(const std::vector<Row>& rows);
std::string rows_to_csv(const std::vector<Row>& rows);

}  // namespace rtsim::validation
