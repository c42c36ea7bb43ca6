// check_classes (validation.hpp): what can be checked of a row's class without running anything
// again. A measured or qualitative row must need its runs; a measured row's verdict must not
// follow a parameter its formula reads directly (issue 35, DESIGN.md "Validation").
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "common/splitmix64.hpp"
#include "platform/validation/validation.hpp"

namespace rtsim::validation {

namespace {

/// The figure's value on `results`, or nothing when it cannot be had (an error, NaN).
std::optional<double> value_on(const Figure& f, const RunResults& results) {
  try {
    const Measured m = f.measure(results);
    if (std::isnan(m.value)) return std::nullopt;
    return m.value;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

/// Whether the figure passes on `results` (its seed value may come from the run).
bool passes_on(const Figure& f, const Tolerance& tolerance, const RunResults& results) {
  try {
    const Measured m = f.measure(results);
    return tolerance.accepts(m.reference.value_or(f.seed_value), m.value);
  } catch (const std::exception&) {
    return false;
  }
}

/// The same value: equal, or both absent.
bool same_value(const std::optional<double>& a, const std::optional<double>& b) {
  if (!a || !b) return !a && !b;
  if (!std::isfinite(*a) || !std::isfinite(*b)) return *a == *b;
  return *a == *b || std::abs(*a - *b) <= 1e-12 * std::max(std::abs(*a), std::abs(*b));
}

/// Every number of `j` but those under the top-level "params" (the parameters the run was given)
/// moved by a pseudo-random factor; one in four becomes 0, so a count of nonzero entries moves
/// too.
void scramble(nlohmann::json& j, SplitMix64& random, bool top) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (top && it.key() == "params") continue;
      scramble(it.value(), random, false);
    }
  } else if (j.is_array()) {
    for (auto& e : j) scramble(e, random, false);
  } else if (j.is_number()) {
    const double x = j.get<double>();
    j = random.below(4) == 0 ? 0.0 : x * random.uniform(0.5, 2.0) + random.uniform(-1.0, 1.0);
  }
}

/// A parameter's text ("333.333 ns", "8 MHz", "0.6") with its number times `factor`; nothing if
/// the text is not a number with an optional unit after one space.
std::optional<std::string> scaled_param_text(const std::string& text, double factor) {
  if (text.empty()) return std::nullopt;
  const char* begin = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (end == begin || !std::isfinite(v)) return std::nullopt;
  const std::string rest(end);
  if (!rest.empty() && rest.front() != ' ') return std::nullopt;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v * factor);
  return std::string(buf) + rest;
}

/// Figure f's row reads its value without its runs' output: with their stats.json scrambled and
/// their folders gone, twice, it never moved.
bool needs_no_run(const Figure& f, const RunResults& results, const std::optional<double>& base) {
  for (std::uint64_t seed : {0x5EEDull, 0xC1A55ull}) {
    RunResults scrambled;
    SplitMix64 random(seed);
    for (const auto& key : f.runs) {
      const auto it = results.find(key);
      if (it == results.end()) continue;
      RunOutcome o = it->second;
      if (o.stats) scramble(*o.stats, random, true);
      // Its other outputs (images) are gone.
      o.out_dir = o.out_dir / "scrambled-outputs-absent";
      scrambled.emplace(key, std::move(o));
    }
    if (!same_value(value_on(f, scrambled), base)) return false;
  }
  return true;
}

}  // namespace

void check_classes(const Plan& plan, const RunResults& results, std::vector<Row>& rows) {
  for (std::size_t i = 0; i < plan.figures.size() && i < rows.size(); ++i) {
    const Figure& f = plan.figures[i];
    Row& row = rows[i];
    if (f.runs.empty()) {
      if (f.figure_class != FigureClass::kDerived)
        row.class_error = std::string("classed ") + class_name(f.figure_class) +
                          " but it runs nothing: a figure without a run is the seed's own "
                          "arithmetic (derived)";
      continue;
    }
    if (f.figure_class == FigureClass::kDerived) continue;
    // Only rows with a value are checked: an error already fails them.
    if (!row.simulated || !row.error.empty()) continue;
    const std::optional<double> base = row.simulated;
    if (needs_no_run(f, results, base)) {
      row.class_error = std::string("classed ") + class_name(f.figure_class) +
                        " but its value does not come from its runs (with every number of their "
                        "stats.json but the parameters scrambled it stays " +
                        format_number(*base) + "): a parameter or a constant is derived";
      continue;
    }
    if (f.figure_class != FigureClass::kMeasured) continue;
    // The parameters the formula reads directly: moved with nothing run again.
    RunResults moved;
    for (const auto& key : f.runs) {
      const auto it = results.find(key);
      if (it != results.end()) moved.emplace(key, it->second);
    }
    const bool base_pass = row.pass();
    for (auto& [key, outcome] : moved) {
      if (!outcome.stats || !outcome.stats->contains("params") ||
          !(*outcome.stats)["params"].is_object())
        continue;
      auto& params = (*outcome.stats)["params"];
      for (auto it = params.begin(); it != params.end(); ++it) {
        if (!it.value().is_string()) continue;
        const std::string original = it.value().get<std::string>();
        bool moves = false;
        for (double factor : {0.5, 2.0}) {
          const auto text = scaled_param_text(original, factor);
          if (!text) break;
          it.value() = *text;
          if (!same_value(value_on(f, moved), base)) moves = true;
          const bool passes = passes_on(f, row.tolerance, moved);
          if (passes != base_pass && row.class_error.empty())
            row.class_error = "classed measured but its verdict follows " + it.key() +
                              ", which its formula reads from the parameters: at " + *text +
                              " it " + (passes ? "passes" : "fails") + " with nothing run again";
        }
        it.value() = original;
        if (moves) {
          bool known = false;
          for (const auto& p : row.formula_params) known = known || p == it.key();
          if (!known) row.formula_params.push_back(it.key());
        }
      }
    }
  }
}

}  // namespace rtsim::validation
