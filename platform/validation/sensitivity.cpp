#include "platform/validation/sensitivity.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "common/input_error.hpp"
#include "params/registry.hpp"
#include "platform/machine.hpp"
#include "platform/machine_registry.hpp"

namespace rtsim::validation {

namespace {

/// The registry a run reads: its machine's parameters with the run's -p applied. Null for a run
/// with no machine (`rtsim render`).
std::unique_ptr<params::ParamRegistry> registry_of(const RunRequest& run) {
  const std::string machine = machine_of(run);
  if (machine.empty()) return nullptr;
  const platform::Machine* m = platform::machine_named(machine);
  if (m == nullptr) return nullptr;
  auto r = std::make_unique<params::ParamRegistry>();
  platform::declare_params_of(m, *r);
  for (std::size_t i = 0; i + 1 < run.args.size(); ++i)
    if (run.args[i] == "-p") r->apply_override(run.args[i + 1]);
  return r;
}

/// Whether the run sets `param` itself with -p.
bool run_sets(const RunRequest& run, const std::string& param) {
  for (std::size_t i = 0; i + 1 < run.args.size(); ++i)
    if (run.args[i] == "-p" && run.args[i + 1].rfind(param + "=", 0) == 0) return true;
  return false;
}

std::optional<params::ParamEntry> entry_of(const params::ParamRegistry& r, const std::string& p) {
  for (auto& e : r.list())
    if (e.name == p) return e;
  return std::nullopt;
}

std::string number_text(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

/// The value `e` takes moved by `factor`, written as for -p; nothing for a kind without a number.
std::optional<std::string> scaled(const params::ParamEntry& e, double factor) {
  using params::ParamKind;
  // A whole number that an int64 holds, else nothing (a factor too large for the parameter).
  const auto whole = [](double x) -> std::optional<std::string> {
    if (!std::isfinite(x) || std::abs(x) > 9e18) return std::nullopt;
    return std::to_string(std::llround(x));
  };
  const auto real = [](double x) -> std::optional<std::string> {
    if (!std::isfinite(x)) return std::nullopt;
    return number_text(x);
  };
  switch (e.kind) {
    case ParamKind::kInt:
      return whole(static_cast<double>(std::get<std::int64_t>(e.value)) * factor);
    case ParamKind::kDouble:
      return real(std::get<double>(e.value) * factor);
    case ParamKind::kTime: {  // whole picoseconds (SystemC's resolution; the registry checks it)
      const auto ps = whole(std::get<double>(e.value) * factor * 1e12);
      return ps ? std::optional(*ps + " ps") : std::nullopt;
    }
    case ParamKind::kFrequency:
    case ParamKind::kBitRate:
    case ParamKind::kDataSize: {
      const char* unit = e.kind == ParamKind::kFrequency ? " Hz"
                         : e.kind == ParamKind::kBitRate ? " bit/s"
                                                         : " bit";
      const auto v = real(std::get<double>(e.value) * factor);
      return v ? std::optional(*v + unit) : std::nullopt;
    }
    case ParamKind::kBool:
    case ParamKind::kString:
      return std::nullopt;
  }
  return std::nullopt;
}

/// The other values of a bool or a string with allowed values, besides the default.
std::vector<std::string> alternatives(const params::ParamEntry& e) {
  if (e.kind == params::ParamKind::kBool) return {e.default_text == "true" ? "false" : "true"};
  std::vector<std::string> out;
  for (const auto& a : e.allowed)
    if (a != e.default_text) out.push_back(a);
  return out;
}

std::string factor_label(double f) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "x%g", f);
  return buf;
}

std::string key_part(const std::string& s) {
  std::string out;
  for (char c : s) {
    const bool plain = std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-';
    out += plain ? c : '_';
  }
  return out;
}

const Figure* figure_named(const Plan& plan, const std::string& id) {
  for (const auto& f : plan.figures)
    if (f.id == id) return &f;
  return nullptr;
}

const Row* row_named(const std::vector<Row>& rows, const std::string& id) {
  for (const auto& r : rows)
    if (r.id == id) return &r;
  return nullptr;
}

/// A finite number, or null (JSON has no inf or nan).
nlohmann::ordered_json number_or_null(std::optional<double> v) {
  if (v && std::isfinite(*v)) return *v;
  return nullptr;
}

std::string percent_text(double fraction) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%+.1f%%", fraction * 100.0);
  return buf;
}

}  // namespace

bool is_assumption_source(std::string_view source) {
  std::string lower(source);
  for (auto& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower.find("assumption") != std::string::npos;
}

std::string machine_of(const RunRequest& run) {
  for (std::size_t i = 0; i + 1 < run.args.size(); ++i)
    if (run.args[i] == "--machine") return run.args[i + 1];
  return {};
}

std::string assumption_problem(const Plan& plan, const Figure& f, const AssumptionRef& a) {
  bool read = false;
  std::string machines;
  for (const auto& key : f.runs) {
    const RunRequest* run = plan.find_run(key);
    if (run == nullptr) continue;
    std::unique_ptr<params::ParamRegistry> r;
    try {
      r = registry_of(*run);
    } catch (const std::exception& e) {
      return "run " + key + "'s parameters do not apply: " + e.what();
    }
    if (!r) continue;
    if (machines.find(machine_of(*run)) == std::string::npos)
      machines += (machines.empty() ? "" : ", ") + machine_of(*run);
    if (!r->contains(a.param)) continue;
    read = true;
    const auto e = entry_of(*r, a.param);
    if (!e) return a.param + " is not listed by its machine";
    if (!is_assumption_source(e->source))
      return a.param + "'s source is not an assumption: " + e->source;
    for (const auto& v : a.values) {
      params::ParamRegistry moved = *r;
      try {
        moved.apply_override(a.param + "=" + v);
      } catch (const InputError& err) {
        return "stated value " + v + ": " + err.message();
      }
    }
    if (a.values.empty() && !scaled(*e, 1.0) && alternatives(*e).empty())
      return a.param + " is free text: state the values to try";
  }
  if (!read)
    return "no run of " + f.id + " is on a machine that reads " + a.param +
           " (its machines: " + (machines.empty() ? "none" : machines) + ")";
  return {};
}

SensitivityPlan make_sensitivity_plan(const Plan& plan, const SensitivityOptions& options) {
  SensitivityPlan sp;
  // Perturbations by (param, label), in the order the figures name them.
  const auto find_or_add = [&](const std::string& param, const std::string& label,
                               double factor) -> Perturbation& {
    for (auto& p : sp.perturbations)
      if (p.param == param && p.label == label) return p;
    sp.perturbations.push_back(Perturbation{.param = param, .label = label, .factor = factor});
    return sp.perturbations.back();
  };
  std::map<std::string, std::unique_ptr<params::ParamRegistry>> registries;
  const auto registry = [&](const RunRequest& run) -> const params::ParamRegistry* {
    auto it = registries.find(run.key);
    if (it == registries.end()) it = registries.emplace(run.key, registry_of(run)).first;
    return it->second.get();
  };

  for (const auto& f : plan.figures) {
    if (f.figure_class == FigureClass::kDerived) continue;
    for (const auto& a : f.assumptions) {
      if (const auto problem = assumption_problem(plan, f, a); !problem.empty())
        throw std::logic_error("validation plan: " + f.id + " names assumption " + a.param + ": " +
                               problem);
      // The moves: stated values, else the factors (numbers) or the other values (choices).
      struct Move {
        std::string label;
        double factor;
        std::string value;
      };
      std::vector<Move> moves;
      for (const auto& v : a.values) moves.push_back({"= " + v, 0.0, v});
      if (moves.empty()) {
        for (const auto& key : f.runs) {
          const RunRequest* run = plan.find_run(key);
          const auto* r = run ? registry(*run) : nullptr;
          if (r == nullptr || !r->contains(a.param)) continue;
          const auto e = entry_of(*r, a.param);
          if (scaled(*e, 1.0)) {
            for (double factor : options.factors)
              moves.push_back({factor_label(factor), factor, ""});
          } else {
            for (const auto& v : alternatives(*e)) moves.push_back({"= " + v, 0.0, v});
          }
          break;
        }
      }
      for (const auto& move : moves) {
        Perturbation& p = find_or_add(a.param, move.label, move.factor);
        if (std::find(p.figures.begin(), p.figures.end(), f.id) == p.figures.end())
          p.figures.push_back(f.id);
        for (const auto& key : f.runs) {
          if (p.runs.count(key)) continue;
          const RunRequest* run = plan.find_run(key);
          const auto* r = run ? registry(*run) : nullptr;
          if (r == nullptr || !r->contains(a.param)) continue;
          std::string value = move.value;
          if (move.factor == 0.0) {
            if (run_sets(*run, a.param)) continue;  // it studies this parameter: kept
          } else {
            const auto moved_text = scaled(*entry_of(*r, a.param), move.factor);
            if (!moved_text) continue;  // out of any range the parameter could hold
            value = *moved_text;
          }
          params::ParamRegistry moved = *r;
          try {
            moved.apply_override(a.param + "=" + value);
          } catch (const InputError&) {
            continue;  // outside its bounds: this run keeps its value
          }
          if (moved.value_text(a.param) == r->value_text(a.param)) continue;  // no move
          RunRequest perturbed = *run;
          perturbed.key = key + "~" + key_part(a.param) + "~" + key_part(move.label);
          perturbed.args.push_back("-p");
          perturbed.args.push_back(a.param + "=" + value);
          p.runs[key] = perturbed.key;
          p.values[key] = moved.value_text(a.param);
          sp.runs.push_back(std::move(perturbed));
        }
      }
    }
  }
  for (auto& p : sp.perturbations)
    if (p.runs.empty())
      p.skipped =
          "no run's value moves (" + p.label + " is outside the bounds, or the runs set it)";
  return sp;
}

std::vector<SensitivityEntry> evaluate_sensitivity(const Plan& plan,
                                                   const std::vector<Row>& base_rows,
                                                   const SensitivityPlan& sensitivity,
                                                   const RunResults& results) {
  std::vector<SensitivityEntry> entries;
  for (const auto& p : sensitivity.perturbations) {
    for (const auto& id : p.figures) {
      const Figure* f = figure_named(plan, id);
      const Row* base = row_named(base_rows, id);
      if (f == nullptr || base == nullptr) continue;
      RunResults view;
      bool moved = false;
      for (const auto& key : f->runs) {
        const auto pk = p.runs.find(key);
        const std::string& source = pk == p.runs.end() ? key : pk->second;
        moved = moved || pk != p.runs.end();
        const auto it = results.find(source);
        if (it != results.end()) view.emplace(key, it->second);
      }
      if (!moved) continue;
      SensitivityEntry e{.figure = id, .param = p.param, .label = p.label, .factor = p.factor};
      try {
        const Measured m = f->measure(view);
        e.simulated = m.value;
        e.pass = !std::isnan(m.value) &&
                 base->tolerance.accepts(m.reference.value_or(f->seed_value), m.value);
        if (base->simulated && std::isfinite(m.value) && *base->simulated != 0.0)
          e.relative_change = (m.value - *base->simulated) / std::abs(*base->simulated);
      } catch (const std::exception& ex) {
        e.error = ex.what();
      }
      e.flips = e.pass != base->pass();
      entries.push_back(std::move(e));
    }
  }
  return entries;
}

std::string holds_over(const Row& base, const std::vector<const SensitivityEntry*>& entries) {
  std::vector<const SensitivityEntry*> factors, values;
  for (const auto* e : entries) (e->factor > 0 ? factors : values).push_back(e);
  std::sort(factors.begin(), factors.end(),
            [](const auto* a, const auto* b) { return a->factor < b->factor; });
  std::ostringstream out;
  out << "the base verdict (" << (base.pass() ? "pass" : "fail") << ") holds";
  std::string changes;
  if (!factors.empty()) {
    double lo = 1.0, hi = 1.0;
    // Walk out from the base (x1) while the verdict stays.
    for (auto it = factors.rbegin(); it != factors.rend(); ++it) {
      if ((*it)->factor >= 1.0) continue;
      if ((*it)->flips) break;
      lo = (*it)->factor;
    }
    for (const auto* e : factors) {
      if (e->factor <= 1.0) continue;
      if (e->flips) break;
      hi = e->factor;
    }
    out << " over " << factor_label(lo) << ".." << factor_label(hi);
    for (const auto* e : factors)
      if (e->flips) changes += (changes.empty() ? "" : ", ") + e->label;
  }
  std::string same;
  for (const auto* e : values) {
    if (e->flips)
      changes += (changes.empty() ? "" : ", ") + e->label;
    else
      same += (same.empty() ? "" : ", ") + e->label;
  }
  if (!values.empty())
    out << (factors.empty() ? "" : " and") << " at " << (same.empty() ? "no stated value" : same);
  if (!changes.empty()) out << "; it changes at " << changes;
  return out.str();
}

std::string format_sensitivity(const std::vector<Row>& base_rows,
                               const std::vector<SensitivityEntry>& entries) {
  std::ostringstream out;
  out << "Sensitivity: each figure's value as one assumption moves (the base run's value, then "
         "each move's value, change and verdict)\n";
  std::vector<std::string> depends;
  for (const auto& base : base_rows) {
    // This figure's entries, by assumption in the order they came.
    std::vector<std::string> params;
    for (const auto& e : entries)
      if (e.figure == base.id && std::find(params.begin(), params.end(), e.param) == params.end())
        params.push_back(e.param);
    if (params.empty()) continue;
    out << "\n"
        << base.id << " (" << class_name(base.figure_class) << ", "
        << (base.simulated ? format_number(*base.simulated) : std::string("-"))
        << (base.unit.empty() ? "" : " " + base.unit) << ", " << base.tolerance.describe() << ", "
        << (base.pass() ? "pass" : "FAIL") << ")\n";
    std::string depends_line;
    for (const auto& param : params) {
      std::vector<const SensitivityEntry*> mine;
      out << "  " << param;
      for (const auto& e : entries) {
        if (e.figure != base.id || e.param != param) continue;
        mine.push_back(&e);
        out << "  " << e.label << ": ";
        if (!e.error.empty() || !e.simulated) {
          out << "error";
        } else {
          out << format_number(*e.simulated);
          if (e.relative_change) out << " (" << percent_text(*e.relative_change) << ")";
        }
        out << (e.pass ? " pass" : " FAIL") << (e.flips ? " <- verdict changes" : "");
      }
      out << "\n";
      const bool flips = std::any_of(mine.begin(), mine.end(), [](auto* e) { return e->flips; });
      if (flips)
        depends_line += (depends_line.empty() ? "" : "; ") + param + ": " + holds_over(base, mine);
    }
    if (!depends_line.empty()) depends.push_back(base.id + ": " + depends_line);
  }
  out << "\nVerdicts that depend on an assumption (" << depends.size() << "):\n";
  for (const auto& d : depends) out << "  " << d << "\n";
  if (depends.empty()) out << "  none: every verdict holds over every move tried\n";
  return out.str();
}

nlohmann::ordered_json sensitivity_to_json(const std::vector<Row>& base_rows,
                                           const SensitivityPlan& sensitivity,
                                           const std::vector<SensitivityEntry>& entries) {
  nlohmann::ordered_json doc;
  auto perturbations = nlohmann::ordered_json::array();
  for (const auto& p : sensitivity.perturbations) {
    nlohmann::ordered_json j;
    j["param"] = p.param;
    j["label"] = p.label;
    j["factor"] = number_or_null(p.factor > 0 ? std::optional(p.factor) : std::nullopt);
    j["figures"] = p.figures;
    auto runs = nlohmann::ordered_json::object();
    for (const auto& [base, key] : p.runs)
      runs[base] = {{"key", key}, {"value", p.values.at(base)}};
    j["runs"] = runs;
    j["skipped"] = p.skipped;
    perturbations.push_back(std::move(j));
  }
  doc["perturbations"] = perturbations;
  auto rows = nlohmann::ordered_json::array();
  for (const auto& r : base_rows) {
    nlohmann::ordered_json j;
    j["id"] = r.id;
    j["class"] = class_name(r.figure_class);
    j["unit"] = r.unit;
    j["simulated_value"] = number_or_null(r.simulated);
    j["tolerance"] = r.tolerance.describe();
    j["pass"] = r.pass();
    j["assumptions"] = r.assumptions;
    rows.push_back(std::move(j));
  }
  doc["base"] = rows;
  auto list = nlohmann::ordered_json::array();
  for (const auto& e : entries) {
    nlohmann::ordered_json j;
    j["figure"] = e.figure;
    j["param"] = e.param;
    j["label"] = e.label;
    j["factor"] = number_or_null(e.factor > 0 ? std::optional(e.factor) : std::nullopt);
    j["simulated_value"] = number_or_null(e.simulated);
    j["relative_change"] = number_or_null(e.relative_change);
    j["pass"] = e.pass;
    j["flips"] = e.flips;
    j["error"] = e.error;
    list.push_back(std::move(j));
  }
  doc["entries"] = list;
  auto depends = nlohmann::ordered_json::array();
  for (const auto& base : base_rows) {
    std::map<std::string, std::vector<const SensitivityEntry*>> by_param;
    for (const auto& e : entries)
      if (e.figure == base.id) by_param[e.param].push_back(&e);
    for (const auto& [param, mine] : by_param) {
      std::vector<std::string> changes;
      for (const auto* e : mine)
        if (e->flips) changes.push_back(e->label);
      if (changes.empty()) continue;
      depends.push_back({{"figure", base.id},
                         {"param", param},
                         {"verdict_changes_at", changes},
                         {"holds_over", holds_over(base, mine)}});
    }
  }
  doc["verdict_depends"] = depends;
  return doc;
}

}  // namespace rtsim::validation
