#include "platform/sweep/sweep_file.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "common/suggest.hpp"
#include "params/toml_file.hpp"
#include "params/toml_leaves.hpp"

namespace rtsim::sweep {

namespace fs = std::filesystem;

namespace {

using Json = nlohmann::ordered_json;

// The largest image side `rtsim run` takes (its --width/--height check).
constexpr std::int64_t kMaxImageSide = 16384;
/// Largest integer a log range may name: its points are computed in doubles, which hold every
/// integer up to 2^53 exactly.
constexpr std::int64_t kMaxExactInteger = std::int64_t{1} << 53;

std::size_t line_of(const toml::node& node) { return node.source().begin.line; }

std::string in_quotes(std::string_view s) {
  std::string out(1, '\'');
  out += s;
  out += '\'';
  return out;
}

std::string join(const std::vector<std::string>& items, std::string_view separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += separator;
    out += items[i];
  }
  return out;
}

std::string describe(const toml::node& node) {
  if (const auto* s = node.as_string()) return "a string \"" + s->get() + "\"";
  if (const auto* i = node.as_integer()) return "an integer " + std::to_string(i->get());
  if (node.is_floating_point()) return "a float";
  if (const auto* b = node.as_boolean()) return b->get() ? "true" : "false";
  if (node.is_array()) return "an array";
  if (node.is_table()) return "a table";
  return "a date or time";
}

// Shortest text that reads back as the same double.
std::string exact_text(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// A computed value (a range step) written with 15 significant digits, so 0.1 + 2 * 0.1 is "0.3"
// and not "0.30000000000000004".
double tidy(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  return std::strtod(buf, nullptr);
}

class Reader {
 public:
  Reader(std::string origin, fs::path base_dir)
      : origin_(std::move(origin)), base_dir_(std::move(base_dir)) {}

  SweepFile read(std::string_view text);

 private:
  [[noreturn]] void fail(std::size_t line, const std::string& message) const {
    throw InputError(origin_, line, message);
  }

  void check_keys(const toml::table& table, const std::vector<std::string_view>& allowed,
                  const std::string& where) const;
  Value scalar(const toml::node& node, const std::string& what) const;
  std::vector<Value> range_values(const toml::table& range, const std::string& name) const;
  std::vector<std::int64_t> integer_range(std::int64_t start, std::int64_t stop,
                                          std::optional<std::int64_t> step,
                                          std::optional<std::int64_t> count, std::size_t line,
                                          const std::string& where) const;
  AxisMember member(const toml::table& table, const std::string& where) const;
  void check_run_option_values(const AxisMember& m) const;
  void check_run_flag_value(const std::string& name, const Value& v) const;
  void check_run_option_value(const std::string& name, const Value& v) const;
  Axis axis(const toml::table& table, std::size_t index) const;
  void use_name(const std::string& name, std::size_t line);
  void read_machine_or_scene(const toml::table& root, std::string_view singular,
                             std::string_view plural, SweepFile& out, std::vector<Axis>& leading);
  void read_configs(const toml::node& node, SweepFile& out) const;
  void read_params(const toml::table& params, SweepFile& out);

  std::string origin_;
  fs::path base_dir_;
  std::set<std::string, std::less<>> used_;  // names set or varied so far
};

void Reader::check_keys(const toml::table& table, const std::vector<std::string_view>& allowed,
                        const std::string& where) const {
  // toml++ keeps keys sorted; report the first unknown one in file order.
  const toml::node* first = nullptr;
  std::string first_key;
  for (const auto& [key, node] : table) {
    if (std::find(allowed.begin(), allowed.end(), key.str()) != allowed.end()) continue;
    if (!first || node.source().begin < first->source().begin) {
      first = &node;
      first_key = std::string(key.str());
    }
  }
  if (!first) return;
  std::string message = "unknown key " + in_quotes(first_key) + " in " + where;
  const auto near = closest_names(first_key, allowed);
  if (!near.empty()) {
    std::vector<std::string> q;
    for (const auto& n : near) q.push_back(in_quotes(n));
    message += "; did you mean " + join(q, " or ") + "?";
  } else {
    std::vector<std::string> q;
    for (const auto& a : allowed) q.push_back(in_quotes(a));
    message += "; expected one of " + join(q, ", ");
  }
  fail(line_of(*first), message);
}

Value Reader::scalar(const toml::node& node, const std::string& what) const {
  Value v;
  v.line = line_of(node);
  if (const auto* i = node.as_integer()) {
    v.text = std::to_string(i->get());
    v.json = i->get();
  } else if (const auto* f = node.as_floating_point()) {
    if (!std::isfinite(f->get())) fail(v.line, what + " must be a finite number");
    v.text = exact_text(f->get());
    v.json = f->get();
  } else if (const auto* b = node.as_boolean()) {
    v.text = b->get() ? "true" : "false";
    v.json = b->get();
  } else if (const auto* s = node.as_string()) {
    v.text = s->get();
    v.json = s->get();
  } else {
    fail(v.line, what + " must be a number, a string or true/false; got " + describe(node));
  }
  return v;
}

std::vector<Value> Reader::range_values(const toml::table& range, const std::string& name) const {
  const std::size_t line = line_of(range);
  const std::string where = "the range of " + in_quotes(name);
  check_keys(range, {"start", "stop", "step", "count", "scale", "unit"}, where);

  std::string scale = "linear";
  if (const auto* node = range.get("scale")) {
    const auto* s = node->as_string();
    if (!s || (s->get() != "linear" && s->get() != "log"))
      fail(line_of(*node), where + ": scale must be \"linear\" or \"log\"; got " + describe(*node));
    scale = s->get();
  }
  const bool log = scale == "log";

  // start, stop and step: numbers. When all are integers the range is counted and generated in
  // integers, so every int64 value is exact; otherwise in doubles.
  struct Bound {
    double real = 0.0;
    std::optional<std::int64_t> integer{};
  };
  const auto number = [&](const char* key, bool required) -> std::optional<Bound> {
    const toml::node* node = range.get(key);
    if (!node) {
      if (required) fail(line, where + " needs '" + key + "'");
      return std::nullopt;
    }
    if (const auto* i = node->as_integer()) return Bound{static_cast<double>(i->get()), i->get()};
    if (const auto* f = node->as_floating_point(); f && std::isfinite(f->get()))
      return Bound{f->get(), std::nullopt};
    fail(line_of(*node), where + ": '" + key + "' must be a number; got " + describe(*node));
  };
  const Bound start = *number("start", true);
  const Bound stop = *number("stop", true);
  const std::optional<Bound> step = number("step", false);
  const bool integers = start.integer && stop.integer && (!step || step->integer);

  std::optional<std::int64_t> count;
  if (const auto* node = range.get("count")) {
    const auto* i = node->as_integer();
    if (!i || i->get() < 1 || static_cast<std::size_t>(i->get()) > kMaxPoints)
      fail(line_of(*node), where + ": 'count' must be an integer from 1 to " +
                               std::to_string(kMaxPoints) + "; got " + describe(*node));
    count = i->get();
  }
  std::string unit;
  if (const auto* node = range.get("unit")) {
    const auto* s = node->as_string();
    if (!s || s->get().empty())
      fail(line_of(*node),
           where + ": 'unit' must be a unit such as \"ns\"; got " + describe(*node));
    unit = s->get();
  }
  if (log && step) fail(line, where + ": a log range takes 'count', not 'step'");
  if (!log && count && step) fail(line, where + ": give 'step' or 'count', not both");
  if (count && *count == 1 && start.real != stop.real)
    fail(line, where +
                   ": 'count' = 1 names start alone, not stop; give a count from 2, or "
                   "start = stop for one value");

  std::vector<double> raw;
  std::vector<std::int64_t> raw_integers;
  if (integers && !log) {
    raw_integers =
        integer_range(*start.integer, *stop.integer,
                      step ? step->integer : std::optional<std::int64_t>{}, count, line, where);
  } else if (log) {
    if (!count) fail(line, where + ": a log range needs 'count'");
    if (!(start.real > 0 && stop.real > 0))
      fail(line, where + ": a log range needs start and stop above 0");
    if (integers && std::max(start.real, stop.real) > static_cast<double>(kMaxExactInteger))
      fail(line, where + ": an integer log range reaches at most 2^53 = " +
                     std::to_string(kMaxExactInteger) + " (its points are computed in doubles)");
    for (std::int64_t k = 0; k < *count; ++k) {
      if (k == 0) {
        raw.push_back(start.real);
      } else if (k == *count - 1) {
        raw.push_back(stop.real);
      } else {
        const double t = static_cast<double>(k) / static_cast<double>(*count - 1);
        // Equal ratios between neighbours, in logarithms: stop / start itself may overflow
        // (1e-308 to 1e308).
        raw.push_back(
            std::exp(std::log(start.real) + t * (std::log(stop.real) - std::log(start.real))));
      }
    }
  } else if (count) {
    // stop - start may overflow (-1e308 to 1e308): then each point is the weighted mean of the
    // two, which cannot.
    const bool span_finite = std::isfinite(stop.real - start.real);
    for (std::int64_t k = 0; k < *count; ++k) {
      const double t = *count == 1 ? 0.0 : static_cast<double>(k) / static_cast<double>(*count - 1);
      raw.push_back(k == *count - 1 && *count > 1 ? stop.real
                    : span_finite                 ? start.real + (stop.real - start.real) * t
                                                  : start.real * (1.0 - t) + stop.real * t);
    }
  } else {
    const double s = step ? step->real : 1.0;  // {start = 0.5, stop = 3.5} is 0.5, 1.5, ...
    if (s == 0) fail(line, where + ": 'step' must not be 0");
    const double span = (stop.real - start.real) / s;
    if (span < 0)
      fail(line, where + ": step " + exact_text(s) + " goes away from stop " +
                     exact_text(stop.real) + " (from start " + exact_text(start.real) + ")");
    // Too many values (or more than a double counts: a step of 1e-300) is said as such, before
    // the count is turned into an integer.
    if (!(span < static_cast<double>(kMaxPoints)))
      fail(line, where + " has " +
                     (span < 1e18 ? std::to_string(static_cast<long long>(std::floor(span)) + 1)
                                  : exact_text(std::floor(span) + 1)) +
                     " values, more than " + std::to_string(kMaxPoints) + "; use a larger step");
    // A step that lands on stop within rounding includes it.
    const double n = std::floor(span + 1e-9) + 1;
    if (n > static_cast<double>(kMaxPoints))
      fail(line, where + " has " + std::to_string(static_cast<long long>(n)) +
                     " values, more than " + std::to_string(kMaxPoints));
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(n); ++k)
      raw.push_back(start.real + static_cast<double>(k) * s);
  }
  for (const double x : raw)
    if (!std::isfinite(x))
      fail(line, where + " reaches " + exact_text(x) +
                     ", beyond the range of a double; keep "
                     "start, stop and step within +-1.7e308");
  // Integer log ranges round each point to the nearest integer.
  if (integers && log)
    for (double x : raw) raw_integers.push_back(static_cast<std::int64_t>(std::llround(x)));

  std::vector<Value> values;
  const std::size_t n = integers ? raw_integers.size() : raw.size();
  for (std::size_t k = 0; k < n; ++k) {
    Value v;
    v.line = line;
    if (integers) {
      v.text = std::to_string(raw_integers[k]);
      v.json = raw_integers[k];
    } else {
      const double t = tidy(raw[k]);
      v.text = exact_text(t);
      v.json = t;
    }
    if (!unit.empty()) {
      v.text += " " + unit;
      v.json = v.text;
    }
    // Rounding may make neighbours equal (a log range over few integers): each value once.
    if (!values.empty() && values.back().text == v.text) continue;
    values.push_back(std::move(v));
  }
  return values;
}

// An all-integer linear range, counted and generated in 128-bit integers: every int64 start, stop
// and step is exact, and no count or value can overflow (|stop - start| < 2^64, k <= kMaxPoints).
std::vector<std::int64_t> Reader::integer_range(std::int64_t start, std::int64_t stop,
                                                std::optional<std::int64_t> step,
                                                std::optional<std::int64_t> count, std::size_t line,
                                                const std::string& where) const {
  __extension__ typedef __int128 Wide;  // GCC and clang; -Wpedantic knows no __int128
  const auto text = [](Wide v) {        // v >= 0
    std::string digits;
    do {
      digits.insert(digits.begin(), static_cast<char>('0' + static_cast<int>(v % 10)));
      v /= 10;
    } while (v > 0);
    return digits;
  };
  const Wide span = Wide{stop} - Wide{start};
  std::vector<std::int64_t> out;
  if (count) {
    // Point k is start + span * k / (count - 1), rounded half away from zero as llround rounds.
    const Wide den = *count > 1 ? *count - 1 : 1;
    for (std::int64_t k = 0; k < *count; ++k) {
      const Wide num = Wide{start} * den + span * k;
      Wide q = num / den;
      const Wide r = num % den;
      if (2 * (r < 0 ? -r : r) >= den) q += num < 0 ? -1 : 1;
      out.push_back(static_cast<std::int64_t>(q));
    }
    return out;
  }
  const std::int64_t s = step.value_or(1);  // {start = 1, stop = 30} is 1, 2, ..., 30
  if (s == 0) fail(line, where + ": 'step' must not be 0");
  if (span != 0 && (span < 0) != (s < 0))
    fail(line, where + ": step " + std::to_string(s) + " goes away from stop " +
                   std::to_string(stop) + " (from start " + std::to_string(start) + ")");
  const Wide n = span / s + 1;  // span and step have one sign: the quotient is the floor
  if (n > static_cast<Wide>(kMaxPoints)) {
    fail(line, where + " has " + text(n) + " values, more than " + std::to_string(kMaxPoints) +
                   "; use a larger step");
  }
  for (Wide k = 0; k < n; ++k) out.push_back(static_cast<std::int64_t>(Wide{start} + k * s));
  return out;
}

void Reader::check_run_option_value(const std::string& name, const Value& v) const {
  if (name == kMachine || name == kScene) {
    if (!v.json.is_string() || v.text.empty())
      fail(v.line, in_quotes(name) + " values are names (strings); got " + v.json.dump());
  } else if (name == kWidth || name == kHeight) {
    if (!v.json.is_number_integer() || v.json.get<std::int64_t>() < 1 ||
        v.json.get<std::int64_t>() > kMaxImageSide)
      fail(v.line, in_quotes(name) + " must be an integer from 1 to " +
                       std::to_string(kMaxImageSide) + " (pixels); got " + v.json.dump());
  } else if (is_run_flag(name)) {
    check_run_flag_value(name, v);
  }
}

void Reader::check_run_flag_value(const std::string& name, const Value& v) const {
  const auto integer_in = [&](std::int64_t lo, std::int64_t hi, const std::string& what) {
    if (!v.json.is_number_integer() || v.json.get<std::int64_t>() < lo ||
        v.json.get<std::int64_t>() > hi)
      fail(v.line, in_quotes(name) + " must be " + what + "; got " + v.json.dump());
  };
  if (name == "sample") {
    integer_in(0, 1000000, "0 (the whole frame in detail) or K from 2 to 1000000");
    if (v.json.get<std::int64_t>() == 1)
      fail(v.line, "'sample' = 1 would simulate every window: write 0 for the whole frame");
  } else if (name == "sample-window") {
    integer_in(1, 1000000, "an integer from 1 to 1000000 (rows, or regions, a window)");
  } else if (name == "sample-warmup") {
    integer_in(0, 1000000, "an integer from 0 to 1000000 (windows)");
  } else if (name == "sample-work-stride") {
    integer_in(0, 4096, "an integer from 0 (the systematic estimate) to 4096 (pixels)");
  } else if (name == "trace-max-events") {
    integer_in(1, 1000000000,
               "an integer from 1 to 1000000000 (a sweep's traces are capped: each point writes "
               "its own)");
  } else if (name == "latency-probe") {
    if (!v.json.is_boolean())
      fail(v.line, "'latency-probe' is true or false; got " + v.json.dump());
  } else if (name == "image") {
    if (v.text != "all" && v.text != "png" && v.text != "none")
      fail(v.line,
           "'image' is \"all\", \"png\" or \"none\" (a timing-only point); got " + v.json.dump());
  } else if (name == "trace") {
    bool ok = v.json.is_string() && !v.text.empty();
    std::size_t start = 0;
    while (ok && start <= v.text.size()) {
      const std::size_t comma = v.text.find(',', start);
      const std::string part =
          v.text.substr(start, comma == std::string::npos ? comma : comma - start);
      ok = part == "vcd" || part == "perfetto" || (part == "none" && v.text == "none");
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    if (!ok)
      fail(v.line,
           "'trace' is \"vcd\", \"perfetto\", \"vcd,perfetto\" or \"none\"; got " + v.json.dump());
  } else if (name == "sample-error") {
    // "1%" or "0.5%": the run reads it (rtsim run --sample-error); "none" is the whole frame.
    const std::string& t = v.text;
    char* end = nullptr;
    const double x = v.json.is_string() ? std::strtod(t.c_str(), &end) : 0.0;
    const bool percent =
        v.json.is_string() && end != t.c_str() && std::string(end) == "%" && x > 0 && x < 100;
    if (!percent && t != "none")
      fail(v.line,
           "'sample-error' is a percentage such as \"1%\" (the run's target error), "
           "or \"none\"; got " +
               v.json.dump());
  }
}

void Reader::check_run_option_values(const AxisMember& m) const {
  for (const auto& v : m.values) check_run_option_value(m.name, v);
}

AxisMember Reader::member(const toml::table& table, const std::string& where) const {
  AxisMember m;
  m.line = line_of(table);
  const toml::node* param = table.get("param");
  if (!param) fail(m.line, where + " needs 'param' (the parameter it varies) or 'zip'");
  const auto* name = param->as_string();
  if (!name || name->get().empty())
    fail(line_of(*param), where + ": 'param' must be a parameter name; got " + describe(*param));
  m.name = name->get();
  m.line = line_of(*param);
  const std::string of = "the axis of " + in_quotes(m.name);

  const toml::node* values = table.get("values");
  const toml::node* range = table.get("range");
  if (values && range) fail(line_of(*range), of + ": give 'values' or 'range', not both");
  if (!values && !range) fail(m.line, of + " needs 'values' (a list) or 'range'");
  if (values) {
    const auto* array = values->as_array();
    if (!array)
      fail(line_of(*values),
           of + ": 'values' must be a list, e.g. [1, 2, 4]; got " + describe(*values));
    if (array->empty()) fail(line_of(*values), of + ": 'values' is empty");
    for (const auto& node : *array) {
      Value v = scalar(node, "a value of " + in_quotes(m.name));
      if (v.line == 0) v.line = line_of(*values);
      m.values.push_back(std::move(v));
    }
  } else {
    const auto* t = range->as_table();
    if (!t)
      fail(line_of(*range),
           of + ": 'range' must be a table, e.g. { start = 1, stop = 30, step = 1 }; got " +
               describe(*range));
    m.values = range_values(*t, m.name);
    if (m.values.empty()) fail(line_of(*range), of + ": the range gives no values");
  }
  check_run_option_values(m);
  return m;
}

Axis Reader::axis(const toml::table& table, std::size_t index) const {
  Axis a;
  a.line = line_of(table);
  const std::string where = "axis " + std::to_string(index + 1);
  if (const toml::node* zip = table.get("zip")) {
    check_keys(table, {"zip"}, where + " (a zipped axis has only 'zip')");
    const auto* array = zip->as_array();
    if (!array || array->empty())
      fail(line_of(*zip), where + ": 'zip' must be a list of { param = ..., values = [...] }");
    for (const auto& node : *array) {
      const auto* t = node.as_table();
      if (!t)
        fail(line_of(node), where +
                                ": each entry of 'zip' must be a table { param = ..., "
                                "values = [...] } or { param = ..., range = {...} }; got " +
                                describe(node));
      check_keys(*t, {"param", "values", "range"}, "an entry of 'zip' (" + where + ")");
      a.members.push_back(member(*t, "an entry of 'zip' (" + where + ")"));
    }
    const AxisMember& first = a.members.front();
    for (const auto& m : a.members) {
      if (m.values.size() != first.values.size())
        fail(m.line, "zipped axis: " + in_quotes(first.name) + " has " +
                         std::to_string(first.values.size()) + " values but " + in_quotes(m.name) +
                         " has " + std::to_string(m.values.size()) +
                         " (zipped parameters advance together)");
    }
  } else {
    check_keys(table, {"param", "values", "range"}, where);
    a.members.push_back(member(table, where));
    // A plain axis lists each value once (a zipped one may repeat a value against others).
    const AxisMember& m = a.members.front();
    std::set<std::string, std::less<>> seen;
    for (const auto& v : m.values) {
      if (!seen.insert(v.text).second)
        fail(v.line, "the axis of " + in_quotes(m.name) + " lists " + in_quotes(v.text) + " twice");
    }
  }
  return a;
}

void Reader::use_name(const std::string& name, std::size_t line) {
  if (!used_.insert(name).second)
    fail(line, in_quotes(name) +
                   " is set or varied twice in this sweep (each name once: in "
                   "[params], at the top level, or in one axis)");
}

void Reader::read_machine_or_scene(const toml::table& root, std::string_view singular,
                                   std::string_view plural, SweepFile& out,
                                   std::vector<Axis>& leading) {
  const toml::node* a = root.get(singular);
  const toml::node* b = root.get(plural);
  if (a && b)
    fail(line_of(*b),
         "give either " + in_quotes(singular) + " or " + in_quotes(plural) + ", not both");
  const toml::node* node = a ? a : b;
  if (!node) return;
  const std::string name(singular);
  const std::string what = in_quotes(std::string(a ? singular : plural));
  if (const auto* array = node->as_array()) {
    if (array->empty()) fail(line_of(*node), what + " is an empty list");
    Axis axis;
    axis.line = line_of(*node);
    AxisMember m{.name = name, .line = line_of(*node), .values = {}};
    std::set<std::string, std::less<>> seen;
    for (const auto& item : *array) {
      if (!item.is_string())
        fail(line_of(*node), what + " must list names (strings); got " + describe(item));
      Value v = scalar(item, what);
      if (v.line == 0) v.line = line_of(*node);
      if (!seen.insert(v.text).second)
        fail(v.line, what + " lists " + in_quotes(v.text) + " twice");
      m.values.push_back(std::move(v));
    }
    check_run_option_values(m);
    axis.members.push_back(std::move(m));
    use_name(name, axis.line);
    leading.push_back(std::move(axis));
  } else if (node->is_string()) {
    Value v = scalar(*node, what);
    check_run_option_value(name, v);
    use_name(name, v.line);
    out.fixed.push_back({name, std::move(v)});
  } else {
    fail(line_of(*node), what + " must be a name or a list of names; got " + describe(*node));
  }
}

void Reader::read_configs(const toml::node& node, SweepFile& out) const {
  std::vector<const toml::node*> items;
  if (const auto* array = node.as_array()) {
    for (const auto& item : *array) items.push_back(&item);
  } else {
    items.push_back(&node);
  }
  for (const toml::node* item : items) {
    const std::size_t line = line_of(*item) ? line_of(*item) : line_of(node);
    const auto* s = item->as_string();
    if (!s || s->get().empty())
      fail(line, "'configs' must be a config file or a list of them; got " + describe(*item));
    fs::path path = s->get();
    if (path.is_relative()) path = base_dir_ / path;
    path = path.lexically_normal();
    std::error_code ec;
    if (fs::exists(path, ec) && !fs::is_regular_file(path, ec))
      fail(line, "config file " + in_quotes(s->get()) + " is not a regular file (" + path.string() +
                     " is a folder, a device or a pipe)");
    if (!fs::is_regular_file(path, ec))
      fail(line, "config file " + in_quotes(s->get()) + " not found (looked for " + path.string() +
                     "; relative paths are read from the sweep file's folder)");
    out.configs.emplace_back(path, line);
  }
}

void Reader::read_params(const toml::table& params, SweepFile& out) {
  // `[params.shade] max_depth = 0` and `"shade.max_depth" = 0` are the same (as in configs).
  const params::TomlLeaves leaves = params::toml_leaves_in_file_order(params);
  for (const auto& [name, node] : leaves) {
    const std::size_t line = line_of(*node);
    if (is_run_option(name))
      fail(line, in_quotes(name) +
                     " is an option of `rtsim run`, not a parameter: set it at the top "
                     "level (" +
                     name + " = ...) or vary it in an [[axes]] entry");
    if (node->is_array())
      fail(line, "[params] sets one value per parameter; to vary " + in_quotes(name) +
                     ", add an [[axes]] entry with param = \"" + name + "\"");
    Value v = scalar(*node, "parameter " + in_quotes(name));
    use_name(name, line);
    out.fixed.push_back({name, std::move(v)});
  }
}

SweepFile Reader::read(std::string_view text) {
  const toml::table root = params::parse_toml(text, origin_);
  check_keys(root,
             {"name",
              "description",
              "machine",
              "machines",
              "scene",
              "scenes",
              "width",
              "height",
              "sample",
              "sample-error",
              "sample-window",
              "sample-warmup",
              "sample-work-stride",
              "image",
              "latency-probe",
              "trace",
              "trace-max-events",
              "share-images",
              "configs",
              "params",
              "axes"},
             "the sweep file");

  SweepFile out;
  out.origin = origin_;
  out.base_dir = base_dir_;
  if (const toml::node* n = root.get("name")) {
    const auto* s = n->as_string();
    if (!s) fail(line_of(*n), "'name' must be a string; got " + describe(*n));
    out.name = s->get();
  }
  if (const toml::node* n = root.get("description"); n && !n->is_string())
    fail(line_of(*n), "'description' must be a string; got " + describe(*n));
  if (const toml::node* n = root.get("share-images")) {
    const auto* b = n->as_boolean();
    if (!b) fail(line_of(*n), "'share-images' must be true or false; got " + describe(*n));
    out.share_images = b->get();
  }

  std::vector<Axis> leading;
  read_machine_or_scene(root, kMachine, "machines", out, leading);
  read_machine_or_scene(root, kScene, "scenes", out, leading);
  std::vector<std::string_view> single = {kWidth, kHeight};
  single.insert(single.end(), std::begin(kRunFlags), std::end(kRunFlags));
  for (std::string_view key : single) {
    if (const toml::node* n = root.get(key)) {
      if (n->is_array())
        fail(line_of(*n), in_quotes(key) +
                              " takes one value; to vary it, add an [[axes]] entry "
                              "with param = \"" +
                              std::string(key) + "\"");
      Value v = scalar(*n, in_quotes(key));
      check_run_option_value(std::string(key), v);
      use_name(std::string(key), v.line);
      out.fixed.push_back({std::string(key), std::move(v)});
    }
  }
  if (const toml::node* n = root.get("configs")) read_configs(*n, out);
  if (const toml::node* n = root.get("params")) {
    const auto* t = n->as_table();
    if (!t) fail(line_of(*n), "'params' must be a table of name = value; got " + describe(*n));
    read_params(*t, out);
  }

  out.axes = std::move(leading);
  if (const toml::node* n = root.get("axes")) {
    const auto* array = n->as_array();
    if (!array)
      fail(line_of(*n),
           "'axes' must be a list of tables: write each as [[axes]]; got " + describe(*n));
    for (std::size_t i = 0; i < array->size(); ++i) {
      const auto* t = (*array)[i].as_table();
      if (!t)
        fail(line_of((*array)[i]) ? line_of((*array)[i]) : line_of(*n),
             "each entry of 'axes' must be a table ([[axes]] param = ..., values = [...]); got " +
                 describe((*array)[i]));
      Axis a = axis(*t, i);
      for (const auto& m : a.members) use_name(m.name, m.line);
      out.axes.push_back(std::move(a));
    }
  }

  if (!used_.contains(kMachine))
    fail(0,
         "the sweep names no machine: add machine = \"NAME\" (or a list; `rtsim list "
         "machines`)");
  if (!used_.contains(kScene))
    fail(0,
         "the sweep names no scene: add scene = \"builtin:NAME\" or a scene file (or a list; "
         "`rtsim list scenes`)");
  if (used_.contains("trace-max-events") && !used_.contains("trace"))
    fail(0, "'trace-max-events' caps traces: add trace = \"vcd\" (or \"perfetto\")");
  if (used_.contains("sample") && used_.contains("sample-error"))
    fail(0, "give 'sample' (K) or 'sample-error' (K chosen for an error), not both");

  std::size_t points = 1;
  for (const auto& a : out.axes) {
    if (points > kMaxPoints / a.size())
      fail(a.line, "the sweep has more than " + std::to_string(kMaxPoints) +
                       " points (the product of the axes' sizes); split it or use coarser steps");
    points *= a.size();
  }
  return out;
}

}  // namespace

bool is_run_flag(std::string_view name) {
  for (std::string_view f : kRunFlags)
    if (name == f) return true;
  return false;
}

bool is_run_option(std::string_view name) {
  return name == kMachine || name == kScene || name == kWidth || name == kHeight ||
         is_run_flag(name);
}

std::vector<std::string> SweepFile::swept_columns() const {
  std::vector<std::string> names;
  for (const auto& a : axes)
    for (const auto& m : a.members)
      if (!is_run_option(m.name) || is_run_flag(m.name)) names.push_back(m.name);
  return names;
}

std::size_t SweepFile::point_count() const {
  std::size_t n = 1;
  for (const auto& a : axes) n *= a.size();
  return n;
}

std::vector<std::string> SweepFile::swept_params() const {
  std::vector<std::string> names;
  for (const auto& a : axes)
    for (const auto& m : a.members)
      if (!is_run_option(m.name)) names.push_back(m.name);
  return names;
}

SweepFile parse_sweep(std::string_view text, const std::string& origin, const fs::path& base_dir) {
  return Reader(origin, base_dir).read(text);
}

SweepFile read_sweep_file(const std::string& path) {
  const std::string text =
      read_input_file(path, "sweep file", kMaxConfigFileBytes, "kMaxConfigFileBytes");
  std::error_code ec;
  const fs::path dir = fs::absolute(fs::path(path), ec).parent_path();
  return parse_sweep(text, path, dir);
}

}  // namespace rtsim::sweep
