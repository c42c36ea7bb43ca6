#pragma once
// The unit of each number stats.json holds, declared where the number is declared: a kit
// statistic by its kind (a Counter counts, a Duration is seconds, a Busy's utilization is a
// fraction) or by the unit its module gives it (a link's `bits`), a machine's own section and the
// keys every run shares by a table beside the code that writes them. stats.json carries the
// run's schema as `units` ({pattern: unit}); the console, `rtsim diff`, the reports and the sweep
// report format each number from it (app/number_text.hpp format_in_unit), and
// tests/stats_units_test.cpp checks every number of every machine's stats.json has one.
//
// A pattern is a dotted stats path in which `*` stands for any characters ("modules.node*.link_e
// .bits", "array.messages_sent_by_type.*"); a module instance's digits are a class's `*`
// (modules/stat_classes.hpp). Used by modules/statistics, the machines and app/.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace rtsim::modules {

enum class StatUnit {
  seconds,   ///< a time ("s")
  rate,      ///< events per second ("/s")
  count,     ///< events or things, no unit ("count")
  fraction,  ///< a part of a whole, 0..1, shown as a percentage ("fraction")
  ratio,     ///< a figure of no unit that is not a count: a mean, a speed-up ("ratio")
  bytes,     ///< "bytes"
  bits,      ///< "bits"
  words,     ///< memory words of the machine ("words")
};

/// The name stats.json's `units` writes ("s", "/s", "count", ...).
std::string_view unit_name(StatUnit unit);
/// The unit of a name unit_name gives; none for another text.
std::optional<StatUnit> parse_unit(std::string_view name);

/// Whether `path` matches `pattern` (`*`: any characters, the dots included).
bool unit_pattern_matches(std::string_view pattern, std::string_view path);

/// A run's units: patterns and their units, the first declared that matches a path wins.
class UnitSchema {
 public:
  UnitSchema() = default;
  UnitSchema(std::initializer_list<std::pair<std::string, StatUnit>> entries);

  /// Declares `pattern`'s unit (a pattern declared before keeps its first unit).
  void add(std::string pattern, StatUnit unit);
  /// Declares every entry of `other` with `prefix` in front ("array." + its keys).
  void add(const UnitSchema& other, const std::string& prefix = "");
  /// The unit of a stats path (`modules.node12.link_e.bits`); none when nothing declares it.
  std::optional<StatUnit> unit_of(std::string_view path) const;
  bool empty() const { return entries_.empty(); }
  const std::vector<std::pair<std::string, StatUnit>>& entries() const { return entries_; }

  /// stats.json `units`: {pattern: unit name}, in declaration order.
  nlohmann::ordered_json to_json() const;
  /// The schema a stats.json carries (`units`); empty for a file written before it had one.
  static UnitSchema from_stats(const nlohmann::ordered_json& stats);

 private:
  std::vector<std::pair<std::string, StatUnit>> entries_;
  std::unordered_map<std::string, StatUnit> index_;  ///< every pattern, as written
  std::vector<std::size_t> wild_;                    ///< the entries with a `*`
};

}  // namespace rtsim::modules
