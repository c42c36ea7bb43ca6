// `rtsim list scenes|machines|params|assumptions`.
#include <fnmatch.h>

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <string_view>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/configuration.hpp"
#include "common/input_error.hpp"
#include "common/seed_citation.hpp"
#include "common/suggest.hpp"
#include "platform/machine.hpp"
#include "platform/machine_registry.hpp"
#include "platform/validation/figure_registry.hpp"
#include "platform/validation/sensitivity.hpp"
#include "scenes/scene_loader.hpp"

namespace rtsim::app {
namespace {

void list_scenes(const std::string& format) {
  if (format == "json") {
    nlohmann::ordered_json all = nlohmann::ordered_json::array();
    for (const auto& info : scenes::builtin_scenes())
      all.push_back({{"name", info.name},
                     {"scene", std::string(scenes::kBuiltinPrefix) + info.name},
                     {"description", info.description}});
    std::cout << all.dump(2) << "\n";
    return;
  }
  std::cout << "Built-in scenes (use as --scene builtin:NAME):\n";
  // The names' column as wide as the longest name and two spaces.
  std::size_t width = 0;
  for (const auto& info : scenes::builtin_scenes()) width = std::max(width, info.name.size());
  for (const auto& info : scenes::builtin_scenes())
    std::cout << "  " << std::left << std::setw(static_cast<int>(width + 2)) << info.name
              << info.description << "\n";
  std::cout << "Files: .nff (Haines' Neutral File Format) and .bpt (bicubic Bezier patches).\n";
}

void list_machines(const std::string& format) {
  if (format == "json") {
    // For scripts and tests: every registered machine, so none needs a list of its own.
    nlohmann::ordered_json all = nlohmann::ordered_json::array();
    for (const platform::Machine* m : platform::machines())
      all.push_back({{"name", m->name()},
                     {"description", m->description()},
                     {"sample_scene", m->sample_scene()},
                     {"test_runs", m->info().test_runs},
                     {"benchmark_runs", m->info().benchmark_runs},
                     {"samples", m->info().samples}});
    std::cout << all.dump(2) << "\n";
    return;
  }
  std::cout << "Machines (rtsim run --machine NAME; rtsim list params --machine NAME):\n";
  // The names' column, two spaces wider than the longest name.
  std::size_t width = std::string_view("(none)").size();
  for (const platform::Machine* m : platform::machines()) width = std::max(width, m->name().size());
  const int column = static_cast<int>(width + 2);
  for (const platform::Machine* m : platform::machines())
    std::cout << "  " << std::left << std::setw(column) << m->name() << cite_seeds(m->description())
              << "\n";
  std::cout << "  " << std::left << std::setw(column) << "(none)"
            << "rtsim render: the functional renderer, firmware with no timing\n";
}

/// A pattern no name matches, its mistyped parts corrected: each dot-separated part with no
/// wildcard that is no name's part becomes the closest part that is ("arry.*" -> "array.*"). ""
/// if that changes nothing or still matches no name.
std::string corrected_pattern(const std::string& pattern,
                              const std::vector<std::string_view>& names) {
  std::set<std::string, std::less<>> parts;
  for (std::string_view n : names)
    for (std::size_t at = 0; at <= n.size();) {
      const std::size_t dot = std::min(n.find('.', at), n.size());
      parts.emplace(n.substr(at, dot - at));
      at = dot + 1;
    }
  const std::vector<std::string_view> part_list(parts.begin(), parts.end());
  std::string out;
  for (std::size_t at = 0; at <= pattern.size();) {
    const std::size_t dot = std::min(pattern.find('.', at), pattern.size());
    std::string part = pattern.substr(at, dot - at);
    if (part.find_first_of("*?[") == std::string::npos && !parts.contains(part))
      if (const auto close = closest_names(part, part_list, 1); !close.empty())
        part = close.front();
    out += (at == 0 ? "" : ".") + part;
    at = dot + 1;
  }
  if (out == pattern) return {};
  for (std::string_view n : names)
    if (::fnmatch(out.c_str(), std::string(n).c_str(), 0) == 0) return out;
  return {};
}

/// The entries `list params PATTERN --changed` shows. A pattern no name matches is bad input,
/// with the closest names.
std::vector<params::ParamEntry> select_params(std::vector<params::ParamEntry> all,
                                              const ListArgs& args) {
  std::vector<params::ParamEntry> out;
  for (auto& e : all) {
    // No FNM_PERIOD or FNM_PATHNAME: '*' matches dots too ("pert.*" is every PERT parameter).
    if (!args.pattern.empty() && ::fnmatch(args.pattern.c_str(), e.name.c_str(), 0) != 0) continue;
    if (args.changed && e.value_text == e.default_text) continue;
    out.push_back(std::move(e));
  }
  if (out.empty() && !args.pattern.empty() && !args.changed) {
    std::vector<std::string_view> names;
    for (const auto& e : all) names.push_back(e.name);
    std::string msg = "no parameter" +
                      (args.machine.empty() ? std::string() : " of " + args.machine) +
                      " matches '" + args.pattern + "'";
    if (const std::string fixed = corrected_pattern(args.pattern, names); !fixed.empty())
      msg += "; did you mean '" + fixed + "'?";
    else
      msg += did_you_mean(args.pattern, names);
    msg += " ('*' matches any characters, dots included: 'pert.*', '*word_time')";
    throw InputError("list params", 0, msg);
  }
  return out;
}

void list_params(const ListArgs& args) {
  const platform::Machine* machine =
      args.machine.empty() ? nullptr : &platform::find_machine(args.machine);
  const auto registry = build_registry(args.config, machine);
  const auto entries = select_params(registry.list(), args);
  if (entries.empty()) {
    std::cout << "every parameter"
              << (args.pattern.empty() ? "" : " matching '" + args.pattern + "'")
              << " is at its default\n";
    return;
  }
  if (args.format == "json") {
    // One object a parameter, for scripts (tests/param_bounds_test.cpp runs every bound).
    nlohmann::ordered_json all = nlohmann::ordered_json::array();
    for (const auto& e : entries) {
      nlohmann::ordered_json j;
      j["name"] = e.name;
      j["kind"] = params::kind_name(e.kind);
      j["value"] = e.value_text;
      j["default"] = e.default_text;
      j["unit"] = e.unit;
      j["min"] = e.min_text;
      j["max"] = e.max_text;
      j["allowed"] = e.allowed;
      j["set_by"] = e.where_set;
      j["description"] = e.description;
      j["source"] = e.source;
      j["affects_image"] = e.affects_image;
      all.push_back(std::move(j));
    }
    std::cout << all.dump(2) << "\n";
    return;
  }
  if (args.format == "markdown") {
    std::cout << "| name | default | unit | image | description | source |\n"
                 "|---|---|---|---|---|---|\n";
    for (const auto& e : entries)
      std::cout << "| `" << e.name << "` | `" << e.default_text << "` | " << e.unit << " | "
                << (e.affects_image ? "yes" : "") << " | " << e.description << " | "
                << cite_seeds(e.source) << " |\n";
    return;
  }
  std::size_t name_w = 4, value_w = 5;
  for (const auto& e : entries) {
    name_w = std::max(name_w, e.name.size());
    value_w = std::max(value_w, e.value_text.size());
  }
  std::cout << std::left << std::setw(static_cast<int>(name_w + 2)) << "name"
            << std::setw(static_cast<int>(value_w + 2)) << "value"
            << "set by\n";
  for (const auto& e : entries) {
    std::cout << std::left << std::setw(static_cast<int>(name_w + 2)) << e.name
              << std::setw(static_cast<int>(value_w + 2)) << e.value_text << e.where_set << "\n"
              << "    " << e.description << "\n"
              << "    default " << e.default_text << (e.unit.empty() ? "" : " (" + e.unit + ")")
              << "; source: " << cite_seeds(e.source)
              << (e.affects_image ? "; the image depends on it" : "") << "\n";
  }
}

/// The figures of `rtsim validate` that name `param` as an assumption of a run on `machine`.
std::vector<std::string> figures_naming(const validation::Plan& plan, const std::string& machine,
                                        const std::string& param) {
  std::vector<std::string> ids;
  for (const auto& f : plan.figures) {
    bool on_machine = false;
    for (const auto& key : f.runs)
      if (const auto* r = plan.find_run(key); r && validation::machine_of(*r) == machine)
        on_machine = true;
    if (!on_machine) continue;
    for (const auto& a : f.assumptions)
      if (a.param == param) ids.push_back(f.id);
  }
  return ids;
}

/// `rtsim list assumptions`: every parameter whose source is an assumption, by machine, with
/// its reason and the validation figures whose runs rest on it (DESIGN.md "Validation").
void list_assumptions(const ListArgs& args) {
  const validation::Plan plan = validation::make_validation_plan({.quick = true});
  std::vector<const platform::Machine*> chosen;
  if (args.machine.empty())
    chosen = platform::machines();
  else
    chosen.push_back(&platform::find_machine(args.machine));
  const bool md = args.format == "markdown";
  for (const platform::Machine* m : chosen) {
    params::ParamRegistry registry;
    platform::declare_params_of(m, registry);
    std::vector<params::ParamEntry> mine;
    for (auto& e : registry.list())
      if (validation::is_assumption_source(e.source)) mine.push_back(std::move(e));
    if (md) {
      std::cout << "\n## `" << m->name() << "` (" << mine.size() << " assumptions)\n\n"
                << "| parameter | value | reason | figures that name it |\n|---|---|---|---|\n";
    } else {
      std::cout << m->name() << ": " << mine.size() << " assumptions\n";
    }
    for (const auto& e : mine) {
      std::string figures;
      for (const auto& id : figures_naming(plan, m->name(), e.name))
        figures += (figures.empty() ? "" : ", ") + id;
      if (md) {
        std::string reason = cite_seeds(e.source);
        for (auto& c : reason)
          if (c == '|') c = '/';
        std::cout << "| `" << e.name << "` | `" << e.value_text << "` | " << reason << " | "
                  << figures << " |\n";
      } else {
        std::cout << "  " << e.name << " = " << e.value_text << "\n    " << cite_seeds(e.source)
                  << "\n";
        if (!figures.empty()) std::cout << "    figures that name it: " << figures << "\n";
      }
    }
  }
}

}  // namespace

int run_list(const ListArgs& args) {
  if (args.format == "markdown" && args.what != "params" && args.what != "assumptions")
    throw InputError("list " + args.what, 0,
                     "--format markdown is for `rtsim list params` and `rtsim list assumptions`");
  if (args.format == "json" && args.what == "assumptions")
    throw InputError("list assumptions", 0,
                     "--format json is for `rtsim list params` (its "
                     "sources say which are assumptions)");
  if (args.what != "params" && (!args.pattern.empty() || args.changed))
    throw InputError("list " + args.what, 0, "a pattern and --changed go with `rtsim list params`");
  if (args.what != "params" && args.what != "assumptions" && !args.machine.empty())
    throw InputError("list " + args.what, 0,
                     "--machine goes with `rtsim list params` and `rtsim list assumptions`");
  if (args.what == "scenes") list_scenes(args.format);
  if (args.what == "machines") list_machines(args.format);
  if (args.what == "params") list_params(args);
  if (args.what == "assumptions") list_assumptions(args);
  return kExitOk;
}

}  // namespace rtsim::app
