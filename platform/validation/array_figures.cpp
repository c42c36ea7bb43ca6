#include "platform/validation/array_figures.hpp"

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "params/units.hpp"
#include "platform/validation/figure_registry.hpp"
#include "platform/validation/ullner_figures.hpp"

namespace rtsim::validation {

namespace {

// Seed values (seed 000 L891-L895).
constexpr double kPeripheralFetchBits = 20 * 32;  // "six hundred forty bits at once"
constexpr double kNodeFetchBits = 16;             // "a sixteen bit path to memory"
constexpr double kProcessorsToMatch = 40;         // L891
constexpr double kHundredSpeedUp = 2.5;           // "250% as fast", L891

RunRequest machine_run(std::string key, const char* machine, int side,
                       const std::vector<std::string>& params) {
  return machine_run_request(std::move(key), machine, "builtin:ullner-cubes", side, side, params,
                             40.0 * side * side);
}

/// A time parameter of a run, in seconds, from its stats.json `params`.
double param_seconds(const RunResults& r, const std::string& key, const std::string& name) {
  const nlohmann::json& s = stats_of(r, key);
  if (!s.contains("params") || !s["params"].contains(name) || !s["params"][name].is_string())
    throw MeasureError("stats.json of run " + key + " has no parameter " + name);
  return params::parse_quantity(s["params"][name].get<std::string>(), params::UnitClass::kTime)
      .value;
}

/// Max / mean of the processors' busy fractions: 1 is perfect balance.
double imbalance(const RunResults& r, const std::string& key) {
  const nlohmann::json& s = stats_of(r, key);
  if (!s.contains("array") || !s["array"].contains("node_busy_fraction"))
    throw MeasureError("stats.json of run " + key + " has no array.node_busy_fraction");
  std::vector<double> b;
  for (const auto& row : s["array"]["node_busy_fraction"])
    for (const auto& x : row) b.push_back(x.get<double>());
  const double mean = std::accumulate(b.begin(), b.end(), 0.0) / static_cast<double>(b.size());
  if (!(mean > 0)) throw MeasureError("run " + key + ": no processor was busy");
  return *std::max_element(b.begin(), b.end()) / mean;
}

}  // namespace

namespace {
void add_array_figures(Plan& plan, const PlanOptions& options) {
  const int side = options.quick ? 32 : 64;
  const std::string size = std::to_string(side) + "x" + std::to_string(side);
  // ullner-cubes' eye looks most along y: depth along y is the eye in front (Fig. 2-29), along
  // x the eye to the side of the processors' columns (Fig. 2-30).
  const std::string front = plan.add_run(machine_run("array-front", kArrayMachine, side, {}));
  const std::string side_straight =
      plan.add_run(machine_run("array-side", kArrayMachine, side, {"array.depth_axis=x"}));
  const std::string side_torus = plan.add_run(machine_run(
      "array-side-torus", kArrayMachine, side, {"array.depth_axis=x", "array.mapping=torus"}));
  const std::string peripheral = plan.add_run(
      machine_run("array-peripheral", kUllnerMachine, side, {"peripheral.grid.divisions=8"}));

  // V17: the bandwidth arithmetic of L891 on the runs' own parameters.
  auto processors_to_match = [front, peripheral](const RunResults& r) {
    const double node = kNodeFetchBits / param_seconds(r, front, "node.memory_cycle");
    const double per =
        kPeripheralFetchBits / param_seconds(r, peripheral, "peripheral.intersect_interval");
    return per / node;
  };
  plan.figures.push_back(Figure{
      .id = "V17a",
      .title = "Array processors whose fetch bandwidth matches the peripheral's",
      .seed_ref = "seed 000 L891",
      .seed_text = "the peripheral fetches 640 bits at once, a processor's memory path is 16 bits: "
                   "\"about forty processors\" match it",
      .seed_value = kProcessorsToMatch,
      .unit = "processors",
      .tolerance = Tolerance::relative(
          1e-6,
          "arithmetic on the runs' parameters: 640 bits per peripheral.intersect_interval "
          "over 16 bits per node.memory_cycle (both 1/3 us, as L891 supposes)"),
      .workload = "the parameters of the V18 and V19 runs",
      .runs = {front, peripheral},
      .measure =
          [processors_to_match](const RunResults& r) {
            return Measured{processors_to_match(r),
                            "(640 bits / intersect interval) / (16 bits / memory cycle)"};
          },
  });
  plan.figures.push_back(Figure{
      .id = "V17b",
      .title = "100 array processors against the peripheral, fetch bandwidth",
      .seed_ref = "seed 000 L891",
      .seed_text = "\"an array of 100 processors would be 250% as fast as the original ray "
                   "tracing peripheral\" (ignoring the other memory demands and early rejection, "
                   "L893)",
      .seed_value = kHundredSpeedUp,
      .unit = "x",
      .tolerance = Tolerance::relative(1e-6, "the same arithmetic: 100 / V17a"),
      .workload = "as V17a",
      .runs = {front, peripheral},
      .measure =
          [processors_to_match](const RunResults& r) {
            return Measured{100.0 / processors_to_match(r),
                            "simulated frame times on one scene: docs/validation.md"};
          },
  });

  const std::string workload = "builtin:ullner-cubes at " + size + ", 8 x 8 processors";
  plan.figures.push_back(Figure{
      .id = "V18a",
      .title = "Array, eye to the side, straight mapping: load piles onto an edge",
      .seed_ref = "seed 000 L862",
      .seed_text = "with the eye to the side \"the processors on that edge of the array receive "
                   "all of the vision rays\" (Fig. 2-30), where the eye in front spreads them "
                   "(Fig. 2-29)",
      .seed_value = 1.0,
      .seed_display = "imbalance side / front > 1",
      .unit = "",
      .tolerance = Tolerance::above(
          1.0,
          "qualitative: the busiest processor's share over the mean grows when the view "
          "runs across the columns"),
      .workload = workload + "; depth along y (eye in front) and along x (eye to the side)",
      .runs = {front, side_straight},
      .measure =
          [front, side_straight](const RunResults& r) {
            const double f = imbalance(r, front), s = imbalance(r, side_straight);
            return Measured{
                s / f, "max/mean busy: side " + format_number(s) + ", front " + format_number(f)};
          },
  });
  plan.figures.push_back(Figure{
      .id = "V18b",
      .title = "Array, eye to the side: the skewed torus restores the balance",
      .seed_ref = "seed 000 L866-L881",
      .seed_text = "skewing the mapping (Figs. 2-31, 2-32) spreads a side view's rays over the "
                   "processors; the torus is needed for any viewpoint",
      .seed_value = 1.0,
      .seed_display = "imbalance torus / straight < 1",
      .unit = "",
      .tolerance = Tolerance::range(
          0.0, 1.0, "qualitative: the torus's max/mean busy is below the straight mapping's"),
      .workload = workload + ", depth along x; straight and torus mappings",
      .runs = {side_straight, side_torus},
      .measure =
          [side_straight, side_torus](const RunResults& r) {
            const double s = imbalance(r, side_straight), t = imbalance(r, side_torus);
            return Measured{t / s, "max/mean busy: torus " + format_number(t) + ", straight " +
                                       format_number(s)};
          },
  });
  plan.figures.push_back(Figure{
      .id = "V19",
      .title = "Array against the peripheral, \"if built today\"",
      .seed_ref = "seed 000 L895",
      .seed_text = "\"If built today, a ray tracing array might be just a few times faster than "
                   "the original ray tracing peripheral\"",
      .seed_value = 0.0,
      .seed_display = "a few times: [2, 10]",
      .unit = "x",
      .tolerance = Tolerance::range(
          2.0, 10.0,
          "\"a few times\"; the peripheral at its best grid (8 per axis here) with "
          "its default host, the array with its default processors"),
      .workload = "builtin:ullner-cubes at " + size +
                  ": ullner-peripheral (grid 8) against ullner-array (8 x 8, straight)",
      .runs = {front, peripheral},
      .measure =
          [front, peripheral](const RunResults& r) {
            const double p = stats_number(r, peripheral, "simulated_time_s");
            const double a = stats_number(r, front, "simulated_time_s");
            return Measured{p / a, "frame " + format_number(p) + " s on the peripheral, " +
                                       format_number(a) + " s on the array"};
          },
  });
}

const RegisterFigures kRegistered(kArrayMachine, add_array_figures);

}  // namespace

}  // namespace rtsim::validation
