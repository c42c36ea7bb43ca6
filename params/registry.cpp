#include "params/registry.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "common/leading_plus.hpp"
#include "common/suggest.hpp"
#include "params/toml_file.hpp"
#include "params/toml_leaves.hpp"
#include "params/units.hpp"

namespace rtsim::params {
namespace {

using detail::Param;

// A value that does not fit its parameter; the message already names the parameter. Callers turn
// it into an InputError with file and line, or into a logic_error for a bad declaration.
class BadValue : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::optional<UnitClass> unit_class_of(ParamKind kind) {
  switch (kind) {
    case ParamKind::kTime:
      return UnitClass::kTime;
    case ParamKind::kFrequency:
      return UnitClass::kFrequency;
    case ParamKind::kBitRate:
      return UnitClass::kBitRate;
    case ParamKind::kDataSize:
      return UnitClass::kDataSize;
    default:
      return std::nullopt;
  }
}

// Built by appending: GCC 12 misreports `"\"" + std::string(s)` under -Wrestrict (PR 105329).
std::string quoted(std::string_view s) {
  std::string out(1, '"');
  out += s;
  out += '"';
  return out;
}

std::string_view trim(std::string_view s) {
  const auto is_space = [](char ch) { return ch == ' ' || ch == '\t'; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

std::string_view strip_quotes(std::string_view s) {
  if (s.size() >= 2 && s.front() == s.back() && (s.front() == '"' || s.front() == '\'')) {
    return s.substr(1, s.size() - 2);
  }
  return s;
}

std::string join(const std::vector<std::string>& items, std::string_view last_separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += (i + 1 == items.size()) ? last_separator : ", ";
    out += items[i];
  }
  return out;
}

std::string format_value(ParamKind kind, const ParamValue& v) {
  switch (kind) {
    case ParamKind::kInt:
      return std::to_string(std::get<std::int64_t>(v));
    case ParamKind::kDouble: {
      // The shortest text that reads back exactly; without an exponent where a person would
      // not write one (1000000, not 1e+06; 0.0001, not 1e-04).
      const double d = std::get<double>(v);
      const double a = std::abs(d);
      char buf[64];
      const auto fixed = a == 0.0 || (a >= 1e-6 && a < 1e15);
      const auto r = fixed ? std::to_chars(buf, buf + sizeof buf, d, std::chars_format::fixed)
                           : std::to_chars(buf, buf + sizeof buf, d);
      return std::string(buf, r.ptr);
    }
    case ParamKind::kBool:
      return std::get<bool>(v) ? "true" : "false";
    case ParamKind::kString:
      return std::get<std::string>(v);
    default:
      return format_quantity({std::get<double>(v), *unit_class_of(kind)});
  }
}

// "an integer from 1 to 256", "one of: scanline, tiled", "a time of at least 1 ns".
std::string expectation(const Param& p) {
  const ParamKind kind = p.spec.kind;
  std::string what;
  switch (kind) {
    case ParamKind::kInt:
      what = "an integer";
      break;
    case ParamKind::kDouble:
      what = "a number";
      break;
    case ParamKind::kBool:
      return "true or false";
    case ParamKind::kString:
      return p.spec.allowed.empty() ? "a string" : "one of: " + join(p.spec.allowed, ", ");
    default:
      what = "a " + std::string(unit_class_name(*unit_class_of(kind)));
  }
  if (p.min && p.max) {
    what += " from " + format_value(kind, *p.min) + " to " + format_value(kind, *p.max);
  } else if (p.min) {
    what += " of at least " + format_value(kind, *p.min);
  } else if (p.max) {
    what += " of at most " + format_value(kind, *p.max);
  }
  return what;
}

[[noreturn]] void reject(const Param& p, const std::string& got) {
  throw BadValue("parameter '" + p.spec.name + "' expects " + expectation(p) + "; got " + got);
}

// Reads text written as in a config file or on the command line (already unquoted).
ParamValue parse_text(const Param& p, std::string_view text) {
  const std::string_view number = strip_leading_plus(text);  // "+1", as in scene files
  const char* first = number.data();
  const char* last = text.data() + text.size();
  switch (p.spec.kind) {
    case ParamKind::kInt: {
      std::int64_t v = 0;
      const auto r = std::from_chars(first, last, v);
      if (r.ec != std::errc() || r.ptr != last) reject(p, quoted(text));
      return v;
    }
    case ParamKind::kDouble: {
      double v = 0.0;
      const auto r = std::from_chars(first, last, v);
      if (r.ec != std::errc() || r.ptr != last || !std::isfinite(v)) reject(p, quoted(text));
      return v;
    }
    case ParamKind::kBool:
      if (text == "true") return true;
      if (text == "false") return false;
      reject(p, quoted(text));
    case ParamKind::kString:
      return std::string(text);
    default:
      try {
        return parse_quantity(text, *unit_class_of(p.spec.kind)).value;
      } catch (const UnitError& e) {
        throw BadValue("parameter '" + p.spec.name + "': " + e.what());
      }
  }
}

// Finite, in range, allowed values, and for times a whole number of picoseconds (so get_time_ps is
// exact).
void check(const Param& p, const ParamValue& v) {
  if (const double* d = std::get_if<double>(&v); d && !std::isfinite(*d)) {
    reject(p, format_value(p.spec.kind, v));
  }
  if ((p.min && v < *p.min) || (p.max && *p.max < v)) reject(p, format_value(p.spec.kind, v));
  if (p.spec.kind == ParamKind::kString && !p.spec.allowed.empty()) {
    const std::string& s = std::get<std::string>(v);
    const auto& allowed = p.spec.allowed;
    if (std::find(allowed.begin(), allowed.end(), s) != allowed.end()) return;
    const auto near = closest_names(s, {allowed.begin(), allowed.end()}, 1);
    reject(p, quoted(s) + (near.empty() ? "" : " (did you mean " + quoted(near.front()) + "?)"));
  }
  if (p.spec.kind == ParamKind::kTime) {
    try {
      Quantity{std::get<double>(v), UnitClass::kTime}.to_ps();
    } catch (const UnitError& e) {
      throw BadValue("parameter '" + p.spec.name + "': " + e.what());
    }
  }
}

std::string describe(const toml::node& node) {
  if (const auto* s = node.as_string()) return "a string " + quoted(s->get());
  if (const auto* i = node.as_integer()) return "an integer " + std::to_string(i->get());
  if (node.is_floating_point()) return "a float";
  if (const auto* b = node.as_boolean()) return b->get() ? "a boolean true" : "a boolean false";
  if (node.is_array()) return "an array";
  if (node.is_date()) return "a date";
  if (node.is_time()) return "a time of day";
  if (node.is_date_time()) return "a date-time";
  return "a table";
}

// A TOML value by the parameter's kind. Types must match, except that an integer may be given
// for a double; a bare number for a value with units is reported as "has no unit".
ParamValue from_toml(const Param& p, const toml::node& node) {
  const ParamKind kind = p.spec.kind;
  const bool has_unit = unit_class_of(kind).has_value();
  if (const auto* s = node.as_string(); s && (kind == ParamKind::kString || has_unit)) {
    return parse_text(p, s->get());
  }
  if (const auto* i = node.as_integer()) {
    if (kind == ParamKind::kInt) return i->get();
    if (kind == ParamKind::kDouble) return static_cast<double>(i->get());
    if (has_unit) parse_text(p, std::to_string(i->get()));  // throws: no unit
  }
  if (const auto* f = node.as_floating_point()) {
    if (kind == ParamKind::kDouble) return f->get();
    if (has_unit) parse_text(p, format_value(ParamKind::kDouble, f->get()));  // throws: no unit
  }
  if (const auto* b = node.as_boolean(); b && kind == ParamKind::kBool) return b->get();
  reject(p, describe(node));
}

bool valid_name(std::string_view name) {
  bool segment_empty = true;
  for (char ch : name) {
    if (ch == '.') {
      if (segment_empty) return false;
      segment_empty = true;
    } else if ((ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
               ch == '_') {
      segment_empty = false;
    } else {
      return false;
    }
  }
  return !segment_empty;
}

}  // namespace

std::string_view kind_name(ParamKind kind) {
  switch (kind) {
    case ParamKind::kInt:
      return "int";
    case ParamKind::kDouble:
      return "double";
    case ParamKind::kBool:
      return "bool";
    case ParamKind::kString:
      return "string";
    case ParamKind::kTime:
      return "time";
    case ParamKind::kFrequency:
      return "frequency";
    case ParamKind::kBitRate:
      return "bitrate";
    case ParamKind::kDataSize:
      return "datasize";
  }
  return "?";
}

void ParamRegistry::declare(ParamSpec spec) {
  const std::string name = spec.name;
  const auto fail = [&](const std::string& why) {
    throw std::logic_error("declaring parameter '" + name + "': " + why);
  };
  if (!valid_name(name)) fail("use dot-separated segments of letters, digits and '_'");
  if (params_.contains(name)) fail("already declared");
  for (std::size_t dot = name.find('.'); dot != std::string::npos; dot = name.find('.', dot + 1)) {
    if (params_.contains(name.substr(0, dot))) fail("'" + name.substr(0, dot) + "' is a parameter");
  }
  const std::string as_prefix = name + ".";
  if (auto it = params_.lower_bound(as_prefix);
      it != params_.end() && it->first.starts_with(as_prefix)) {
    fail("'" + it->first + "' is a parameter below it");
  }
  if (!spec.unit.empty() && unit_class_of(spec.kind)) fail("the value's unit is given with it");
  const bool is_string = spec.kind == ParamKind::kString;
  if (!spec.allowed.empty() && !is_string) fail("only strings take allowed values");
  if ((!spec.min.empty() || !spec.max.empty()) && (is_string || spec.kind == ParamKind::kBool)) {
    fail("strings and bools take no bounds");
  }

  Param p{.spec = std::move(spec)};
  try {
    if (!p.spec.min.empty()) p.min = parse_text(p, p.spec.min);
    if (!p.spec.max.empty()) p.max = parse_text(p, p.spec.max);
    p.default_value = parse_text(p, p.spec.default_value);
    check(p, p.default_value);
  } catch (const BadValue& e) {
    fail(e.what());
  }
  p.value = p.default_value;
  params_.emplace(name, std::move(p));
}

bool ParamRegistry::contains(std::string_view name) const { return params_.contains(name); }

bool ParamRegistry::affects_image(std::string_view name) const {
  const Param* p = resolve(name);
  return p != nullptr && p->spec.affects_image;
}

void ParamRegistry::declare_family(InstanceFamily family) {
  if (!valid_name(family.cls) || family.cls.find('.') != std::string::npos)
    throw std::logic_error("declaring family '" + family.cls + "': the class is one segment");
  if (family.members.empty() == family.count_param.empty())
    throw std::logic_error("declaring family '" + family.cls +
                           "': give its members or the parameter counting them");
  families_.push_back(std::move(family));
}

std::string ParamRegistry::class_path(std::string_view path) const {
  const std::size_t dot = std::min(path.find('.'), path.size());
  const std::string_view first = path.substr(0, dot);
  for (const auto& f : families_)
    if (is_member(f, first)) return f.cls + std::string(path.substr(dot));
  return std::string(path);
}

bool ParamRegistry::is_member(const InstanceFamily& f, std::string_view first) {
  if (!f.members.empty())
    return std::find(f.members.begin(), f.members.end(), first) != f.members.end();
  const std::string_view index = first.substr(std::min(first.size(), f.cls.size()));
  return first.starts_with(f.cls) && !index.empty() && index.size() <= 9 &&
         std::all_of(index.begin(), index.end(), [](char c) { return c >= '0' && c <= '9'; }) &&
         (index == "0" || index[0] != '0');
}

std::string ParamRegistry::class_of(std::string_view name) const {
  const std::size_t dot = name.find('.');
  if (dot == std::string_view::npos) return {};
  const std::string_view first = name.substr(0, dot);
  for (const auto& f : families_) {
    if (!is_member(f, first)) continue;
    std::string cls = f.cls + std::string(name.substr(dot));
    const auto it = params_.find(cls);
    if (it != params_.end() && it->second.spec.per_instance && it->second.instance_of.empty())
      return cls;
  }
  return {};
}

const Param* ParamRegistry::resolve(std::string_view name) const {
  const auto it = params_.find(name);
  if (it != params_.end() && (it->second.instance_of.empty() || it->second.where_set != "default"))
    return &it->second;
  const std::string cls = class_of(name);
  if (cls.empty()) return nullptr;
  return &params_.find(cls)->second;
}

void ParamRegistry::check_instances() const {
  for (const auto& [name, p] : params_) {
    if (p.instance_of.empty() || p.where_set == "default") continue;
    const std::string_view first = std::string_view(name).substr(0, name.find('.'));
    for (const auto& f : families_) {
      // The numbered family this instance belongs to (the same membership test as its reads).
      if (f.count_param.empty() || !is_member(f, first)) continue;
      const auto index = std::stoll(std::string(first.substr(f.cls.size())));
      const auto count = std::get<std::int64_t>(params_.at(f.count_param).value);
      if (index < count) continue;
      throw InputError(p.where_set == "-p" ? "-p " + name : p.where_set, 0,
                       "'" + name + "' sets " + std::string(first) +
                           ", which this run does not build: " + f.count_param + " is " +
                           std::to_string(count) + " (" + f.cls + "0.." + f.cls +
                           std::to_string(count - 1) + ")");
    }
  }
}

void ParamRegistry::set_user(std::string user, std::string listing,
                             std::vector<std::string> names_used_elsewhere) {
  user_ = std::move(user);
  listing_ = std::move(listing);
  used_elsewhere_ = std::move(names_used_elsewhere);
  std::sort(used_elsewhere_.begin(), used_elsewhere_.end());
}

Param& ParamRegistry::find_for_input(std::string_view name, const std::string& file,
                                     std::size_t line) {
  if (auto it = params_.find(name); it != params_.end()) return it->second;
  // One instance's value of a class parameter: kept beside it, read in its place.
  if (const std::string cls = class_of(name); !cls.empty()) {
    Param p = params_.at(cls);
    p.spec.name = std::string(name);
    p.instance_of = cls;
    p.where_set = "default";  // until the caller sets it
    p.read = false;
    return params_.emplace(std::string(name), std::move(p)).first->second;
  }
  std::vector<std::string_view> names;
  names.reserve(params_.size());
  for (const auto& entry : params_) names.push_back(entry.first);
  std::vector<std::string> near = closest_names(name, names);
  for (auto& n : near) n = "'" + n + "'";
  const bool elsewhere =
      std::binary_search(used_elsewhere_.begin(), used_elsewhere_.end(), name, std::less<>());
  std::string message = elsewhere ? "parameter '" + std::string(name) + "' is not used by " +
                                        user_ + " (it would change nothing); "
                                  : "unknown parameter '" + std::string(name) + "'; ";
  message += near.empty()
                 ? "`" + listing_ + (elsewhere ? "` lists what it uses" : "` lists them all")
                 : "did you mean " + join(near, " or ") + "?";
  throw InputError(file, line, message);
}

const Param& ParamRegistry::find(std::string_view name, ParamKind kind) const {
  const Param* p = resolve(name);
  if (!p) throw std::logic_error("undeclared parameter '" + std::string(name) + "'");
  if (p->spec.kind != kind) {
    throw std::logic_error("parameter '" + std::string(name) + "' is declared as " +
                           std::string(kind_name(p->spec.kind)) + ", read as " +
                           std::string(kind_name(kind)));
  }
  p->read = true;
  // An instance's value read stands for its class parameter too (unread()).
  if (!p->instance_of.empty()) params_.at(p->instance_of).read = true;
  return *p;
}

std::vector<std::string> ParamRegistry::unread() const {
  std::vector<std::string> out;
  for (const auto& [name, p] : params_)
    if (!p.read && p.instance_of.empty()) out.push_back(name);
  return out;
}

void ParamRegistry::load_toml_file(const std::string& path) {
  load_toml_string(read_input_file(path, "config file", kMaxConfigFileBytes, "kMaxConfigFileBytes"),
                   path);
}

void ParamRegistry::load_toml_string(std::string_view text, const std::string& origin) {
  const toml::table root = parse_toml(text, origin);
  const TomlLeaves leaves = toml_leaves_in_file_order(root);
  // One parameter set twice in one file (a quoted dotted key and a table, say): which one was
  // meant is not for us to guess.
  std::map<std::string_view, std::size_t> first_line;
  for (const auto& [name, node] : leaves) {
    const std::size_t line = node->source().begin.line;
    const auto [it, fresh] = first_line.emplace(name, line);
    if (!fresh)
      throw InputError(origin, line,
                       "parameter '" + name + "' is set twice in this file, here and on line " +
                           std::to_string(it->second) + "; keep one");
  }

  // Check everything before changing anything, so a bad file leaves the registry as it was.
  std::vector<std::pair<Param*, ParamValue>> updates;
  for (const auto& [name, node] : leaves) {
    const std::size_t line = node->source().begin.line;
    Param& p = find_for_input(name, origin, line);
    try {
      ParamValue v = from_toml(p, *node);
      check(p, v);
      updates.emplace_back(&p, std::move(v));
    } catch (const BadValue& e) {
      throw InputError(origin, line, e.what());
    }
  }
  for (std::size_t i = 0; i < updates.size(); ++i) {
    auto& [p, v] = updates[i];
    p->value = std::move(v);
    p->where_set = origin + ":" + std::to_string(leaves[i].second->source().begin.line);
  }
}

void ParamRegistry::apply_override(std::string_view assignment) {
  const std::size_t eq = assignment.find('=');
  const std::string_view name = trim(assignment.substr(0, eq));
  if (eq == std::string_view::npos || name.empty()) {
    throw InputError("", 0,
                     "-p expects name=value (e.g. -p peripheral.grid.divisions=11), got '" +
                         std::string(assignment) + "'");
  }
  Param& p = find_for_input(name, "", 0);
  try {
    ParamValue v = parse_text(p, strip_quotes(trim(assignment.substr(eq + 1))));
    check(p, v);
    p.value = std::move(v);
    p.where_set = "-p";
  } catch (const BadValue& e) {
    throw InputError("", 0, e.what());
  }
}

std::int64_t ParamRegistry::get_int(std::string_view name) const {
  return std::get<std::int64_t>(find(name, ParamKind::kInt).value);
}
double ParamRegistry::get_double(std::string_view name) const {
  return std::get<double>(find(name, ParamKind::kDouble).value);
}
bool ParamRegistry::get_bool(std::string_view name) const {
  return std::get<bool>(find(name, ParamKind::kBool).value);
}
const std::string& ParamRegistry::get_string(std::string_view name) const {
  return std::get<std::string>(find(name, ParamKind::kString).value);
}
double ParamRegistry::get_time_s(std::string_view name) const {
  return std::get<double>(find(name, ParamKind::kTime).value);
}
std::int64_t ParamRegistry::get_time_ps(std::string_view name) const {
  return Quantity{get_time_s(name), UnitClass::kTime}.to_ps();
}
double ParamRegistry::get_frequency_hz(std::string_view name) const {
  return std::get<double>(find(name, ParamKind::kFrequency).value);
}
double ParamRegistry::get_bitrate_bps(std::string_view name) const {
  return std::get<double>(find(name, ParamKind::kBitRate).value);
}
double ParamRegistry::get_data_size_bits(std::string_view name) const {
  return std::get<double>(find(name, ParamKind::kDataSize).value);
}

std::string ParamRegistry::value_text(std::string_view name) const {
  const Param* p = resolve(name);
  if (!p) throw std::logic_error("undeclared parameter '" + std::string(name) + "'");
  return format_value(p->spec.kind, p->value);
}

const std::string& ParamRegistry::where_set(std::string_view name) const {
  const Param* p = resolve(name);
  if (!p) throw std::logic_error("undeclared parameter '" + std::string(name) + "'");
  return p->where_set;
}

std::vector<ParamEntry> ParamRegistry::list() const {
  std::vector<ParamEntry> out;
  out.reserve(params_.size());
  for (const auto& [name, p] : params_) {
    if (!p.instance_of.empty() && p.where_set == "default") continue;  // never set
    const ParamKind kind = p.spec.kind;
    const auto unit_class = unit_class_of(kind);
    out.push_back({.name = name,
                   .kind = kind,
                   .value = p.value,
                   .value_text = format_value(kind, p.value),
                   .default_text = format_value(kind, p.default_value),
                   .unit = unit_class ? std::string(base_unit(*unit_class)) : p.spec.unit,
                   .description = p.spec.description,
                   .source = p.spec.source,
                   .where_set = p.where_set,
                   .instance_of = p.instance_of,
                   .per_instance = p.spec.per_instance,
                   .affects_image = p.spec.affects_image,
                   .min_text = p.min ? format_value(kind, *p.min) : std::string(),
                   .max_text = p.max ? format_value(kind, *p.max) : std::string(),
                   .allowed = p.spec.allowed});
  }
  return out;
}

}  // namespace rtsim::params
