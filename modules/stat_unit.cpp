#include "modules/stat_unit.hpp"

#include <array>

#include "modules/stat_classes.hpp"

namespace rtsim::modules {

namespace {
constexpr std::array<std::pair<StatUnit, std::string_view>, 8> kNames = {{
    {StatUnit::seconds, "s"},
    {StatUnit::rate, "/s"},
    {StatUnit::count, "count"},
    {StatUnit::fraction, "fraction"},
    {StatUnit::ratio, "ratio"},
    {StatUnit::bytes, "bytes"},
    {StatUnit::bits, "bits"},
    {StatUnit::words, "words"},
}};
}  // namespace

std::string_view unit_name(StatUnit unit) {
  for (const auto& [u, name] : kNames)
    if (u == unit) return name;
  return "?";
}

std::optional<StatUnit> parse_unit(std::string_view name) {
  for (const auto& [u, n] : kNames)
    if (n == name) return u;
  return std::nullopt;
}

bool unit_pattern_matches(std::string_view pattern, std::string_view path) {
  // Glob with `*` only, by backtracking to the last star (linear for one star, as most have).
  std::size_t p = 0, s = 0, star = std::string_view::npos, resume = 0;
  while (s < path.size()) {
    if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      resume = s;
    } else if (p < pattern.size() && pattern[p] == path[s]) {
      ++p;
      ++s;
    } else if (star != std::string_view::npos) {
      p = star + 1;
      s = ++resume;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

UnitSchema::UnitSchema(std::initializer_list<std::pair<std::string, StatUnit>> entries) {
  for (const auto& [pattern, unit] : entries) add(pattern, unit);
}

void UnitSchema::add(std::string pattern, StatUnit unit) {
  if (!index_.emplace(pattern, unit).second) return;
  if (pattern.find('*') != std::string::npos) wild_.push_back(entries_.size());
  entries_.emplace_back(std::move(pattern), unit);
}

void UnitSchema::add(const UnitSchema& other, const std::string& prefix) {
  for (const auto& [pattern, unit] : other.entries_) add(prefix + pattern, unit);
}

std::optional<StatUnit> UnitSchema::unit_of(std::string_view path) const {
  const std::string key(path);
  if (const auto it = index_.find(key); it != index_.end()) return it->second;
  // A module instance's path under its class's name ("modules.node12.busy_s" ->
  // "modules.node*.busy_s"), as the modules' statistics declare it.
  if (const auto it = index_.find(instance_class(path)); it != index_.end()) return it->second;
  for (std::size_t i : wild_)
    if (unit_pattern_matches(entries_[i].first, path)) return entries_[i].second;
  // A class aggregate is in its key's unit: module_classes.CLASS.KEY.{min,mean,max,sum} is in
  // the unit of modules.CLASS.KEY (modules/stat_classes.hpp).
  constexpr std::string_view kClasses = "module_classes.";
  if (path.starts_with(kClasses)) {
    const std::size_t dot = path.rfind('.');
    const std::string_view agg = path.substr(dot + 1);
    if (agg == "min" || agg == "mean" || agg == "max" || agg == "sum")
      return unit_of("modules." + std::string(path.substr(kClasses.size(), dot - kClasses.size())));
  }
  return std::nullopt;
}

nlohmann::ordered_json UnitSchema::to_json() const {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  auto& o = j.get_ref<nlohmann::ordered_json::object_t&>();
  for (const auto& [pattern, unit] : entries_) o.emplace_back(pattern, unit_name(unit));
  return j;
}

UnitSchema UnitSchema::from_stats(const nlohmann::ordered_json& stats) {
  UnitSchema schema;
  const auto it = stats.find("units");
  if (it == stats.end() || !it->is_object()) return schema;
  for (const auto& [pattern, name] : it->items())
    if (name.is_string())
      if (const auto unit = parse_unit(name.get<std::string>())) schema.add(pattern, *unit);
  return schema;
}

}  // namespace rtsim::modules
