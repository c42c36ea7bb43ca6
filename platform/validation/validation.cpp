#include "platform/validation/validation.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "common/csv_field.hpp"
#include "common/seed_citation.hpp"
#include "params/units.hpp"

namespace rtsim::validation {

const char* class_name(FigureClass c) {
  switch (c) {
    case FigureClass::kMeasured:
      return "measured";
    case FigureClass::kDerived:
      return "derived";
    case FigureClass::kQualitative:
      return "qualitative";
  }
  return "?";
}

// ---- Tolerance ----------------------------------------------------------------------------

Tolerance Tolerance::relative(double fraction, std::string why) {
  return {.kind = Kind::kRelative, .value = fraction, .why = std::move(why)};
}
Tolerance Tolerance::absolute(double amount, std::string why) {
  return {.kind = Kind::kAbsolute, .value = amount, .why = std::move(why)};
}
Tolerance Tolerance::above(double bound, std::string why) {
  return {.kind = Kind::kAbove, .value = bound, .why = std::move(why)};
}
Tolerance Tolerance::range(double lo, double hi, std::string why) {
  return {.kind = Kind::kRange, .lo = lo, .hi = hi, .why = std::move(why)};
}

bool Tolerance::accepts(double seed, double simulated) const {
  if (std::isnan(simulated)) return false;
  switch (kind) {
    case Kind::kRelative:
      return std::isfinite(simulated) && std::abs(simulated - seed) <= value * std::abs(seed);
    case Kind::kAbsolute:
      return std::isfinite(simulated) && std::abs(simulated - seed) <= value;
    case Kind::kAbove:
      return simulated > value;
    case Kind::kRange:
      return simulated >= lo && simulated <= hi;
  }
  return false;
}

std::string Tolerance::describe() const {
  switch (kind) {
    case Kind::kRelative: {
      // Percent with as many digits as the tolerance needs: 2% -> "±2%", 1e-6 -> "±0.0001%".
      const double pct = value * 100.0;
      return "±" + format_number(pct) + "%";
    }
    case Kind::kAbsolute:
      return value == 0.0 ? "exact" : "±" + format_number(value);
    case Kind::kAbove:
      return "> " + format_number(value);
    case Kind::kRange:
      if (lo == hi) return "= " + format_number(lo);
      return "[" + format_number(lo) + ", " + format_number(hi) + "]";
  }
  return "?";
}

namespace {

const char* kind_name(Tolerance::Kind k) {
  switch (k) {
    case Tolerance::Kind::kRelative:
      return "relative";
    case Tolerance::Kind::kAbsolute:
      return "absolute";
    case Tolerance::Kind::kAbove:
      return "above";
    case Tolerance::Kind::kRange:
      return "range";
  }
  return "?";
}

// Shortest text that reads back as the same double (CSV keeps full precision).
std::string exact_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

bool is_group_member(const std::string& id, const std::string& group) {
  if (id.size() <= group.size() || id.compare(0, group.size(), group) != 0) return false;
  return std::all_of(id.begin() + static_cast<std::ptrdiff_t>(group.size()), id.end(),
                     [](char c) { return c >= 'a' && c <= 'z'; });
}

}  // namespace

// ---- Runs and plans -------------------------------------------------------------------------

std::string Plan::add_run(RunRequest run) {
  for (const auto& r : runs) {
    if (r.key == run.key) {
      if (r.args != run.args)
        throw std::logic_error("validation plan: two different runs named " + run.key);
      return r.key;
    }
  }
  runs.push_back(std::move(run));
  return runs.back().key;
}

void Plan::classify(const std::vector<std::string>& ids, FigureClass figure_class,
                    const std::vector<AssumptionRef>& assumptions) {
  for (const auto& id : ids) {
    bool found = false;
    for (auto& f : figures) {
      if (f.id != id && !is_group_member(f.id, id)) continue;
      f.figure_class = figure_class;
      f.assumptions = assumptions;
      found = true;
    }
    if (!found) throw std::logic_error("validation plan: classify: no figure " + id);
  }
}

const RunRequest* Plan::find_run(const std::string& key) const {
  for (const auto& r : runs)
    if (r.key == key) return &r;
  return nullptr;
}

Plan select_figures(const Plan& plan, const std::vector<std::string>& ids) {
  if (ids.empty()) return plan;
  std::vector<bool> keep(plan.figures.size(), false);
  for (const auto& id : ids) {
    bool matched = false;
    for (std::size_t i = 0; i < plan.figures.size(); ++i) {
      const auto& fid = plan.figures[i].id;
      if (fid == id || is_group_member(fid, id)) keep[i] = matched = true;
    }
    if (!matched) {
      std::string known;
      for (const auto& f : plan.figures) known += (known.empty() ? "" : ", ") + f.id;
      throw std::invalid_argument("no figure \"" + id + "\"; known figures: " + known);
    }
  }
  Plan out;
  std::vector<std::string> needed;
  for (std::size_t i = 0; i < plan.figures.size(); ++i) {
    if (!keep[i]) continue;
    out.figures.push_back(plan.figures[i]);
    needed.insert(needed.end(), plan.figures[i].runs.begin(), plan.figures[i].runs.end());
  }
  for (const auto& r : plan.runs)
    if (std::find(needed.begin(), needed.end(), r.key) != needed.end()) out.runs.push_back(r);
  for (const auto& a : plan.artifacts) {
    const bool all = std::all_of(a.runs.begin(), a.runs.end(), [&](const std::string& k) {
      return std::find(needed.begin(), needed.end(), k) != needed.end();
    });
    if (all) out.artifacts.push_back(a);
  }
  return out;
}

// ---- Evaluation ----------------------------------------------------------------------------

bool Row::pass() const {
  return error.empty() && simulated.has_value() && tolerance.accepts(seed_value, *simulated);
}

std::optional<double> Row::relative_error() const {
  if (!simulated || !seed_display.empty() || seed_value == 0.0) return std::nullopt;
  return (*simulated - seed_value) / std::abs(seed_value);
}

std::vector<Row> evaluate(const Plan& plan, const RunResults& results) {
  std::vector<Row> rows;
  rows.reserve(plan.figures.size());
  for (const auto& f : plan.figures) {
    Row row{.id = f.id,
            .title = f.title,
            .seed_ref = f.seed_ref,
            .seed_text = f.seed_text,
            .seed_display = f.seed_display,
            .unit = f.unit,
            .workload = f.workload,
            .seed_value = f.seed_value,
            .tolerance = f.tolerance,
            .open = f.open,
            .figure_class = f.figure_class};
    for (const auto& a : f.assumptions) row.assumptions.push_back(a.param);
    for (const auto& key : f.runs) {
      if (const RunRequest* r = plan.find_run(key)) row.commands.push_back(r->command_line());
    }
    try {
      const Measured m = f.measure(results);
      row.simulated = m.value;
      row.note = m.note;
      if (m.reference) row.seed_value = *m.reference;
      if (std::isnan(m.value)) row.error = "the measured value is not a number";
    } catch (const std::exception& e) {
      row.error = e.what();
    }
    if (f.seed_from_run && row.seed_display.empty() && !row.simulated)
      row.seed_display = "(from run)";
    rows.push_back(std::move(row));
  }
  check_classes(plan, results, rows);
  return rows;
}

const nlohmann::json& stats_of(const RunResults& results, const std::string& key) {
  const auto it = results.find(key);
  if (it == results.end()) throw MeasureError("run " + key + " was not executed");
  const RunOutcome& r = it->second;
  if (!r.failure.empty()) throw MeasureError("run " + key + " failed: " + r.failure);
  if (!r.stats) throw MeasureError("run " + key + " left no stats.json");
  return *r.stats;
}

RunRequest machine_run_request(std::string key, const std::string& machine,
                               const std::string& scene, int width, int height,
                               const std::vector<std::string>& params, double cost_hint) {
  RunRequest r;
  r.key = std::move(key);
  r.args = {"run",
            "--machine",
            machine,
            "--scene",
            scene,
            "--width",
            std::to_string(width),
            "--height",
            std::to_string(height),
            "-q"};
  for (const auto& p : params) {
    r.args.push_back("-p");
    r.args.push_back(p);
  }
  r.cost_hint = cost_hint;
  return r;
}

namespace {
const std::string& param_text(const RunResults& r, const std::string& key,
                              const std::string& name) {
  const nlohmann::json& s = stats_of(r, key);
  if (!s.contains("params") || !s["params"].contains(name) || !s["params"][name].is_string())
    throw MeasureError("stats.json of run " + key + " has no parameter " + name);
  return s["params"][name].get_ref<const std::string&>();
}
}  // namespace

Figure stats_figure(std::string id, std::string title, std::string seed_ref, std::string seed_text,
                    double seed_value, std::string unit, Tolerance tolerance, std::string workload,
                    const std::string& key, std::string path, double scale) {
  return Figure{.id = std::move(id),
                .title = std::move(title),
                .seed_ref = std::move(seed_ref),
                .seed_text = std::move(seed_text),
                .seed_value = seed_value,
                .unit = std::move(unit),
                .tolerance = std::move(tolerance),
                .workload = std::move(workload),
                .runs = {key},
                .measure = [key, path, scale](const RunResults& r) {
                  return Measured{stats_number(r, key, path) * scale, "stats.json " + path};
                }};
}

double param_seconds(const RunResults& r, const std::string& key, const std::string& name) {
  return params::parse_quantity(param_text(r, key, name), params::UnitClass::kTime).value;
}

double param_number(const RunResults& r, const std::string& key, const std::string& name) {
  const std::string& text = param_text(r, key, name);
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size()) return v;
  } catch (const std::exception&) {
  }
  throw MeasureError("stats.json of run " + key + ": parameter " + name + " is not a number");
}

double stats_number(const RunResults& results, const std::string& key, const std::string& path) {
  const nlohmann::json* node = &stats_of(results, key);
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t dot = path.find('.', start);
    const std::string part =
        path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (!node->is_object() || !node->contains(part))
      throw MeasureError("stats.json of run " + key + " has no " + path);
    node = &(*node)[part];
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  if (!node->is_number())
    throw MeasureError("stats.json of run " + key + ": " + path + " is not a number");
  return node->get<double>();
}

// ---- Output --------------------------------------------------------------------------------

std::string format_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  const double a = std::abs(v);
  if (a == 0.0) return "0";
  if (v == std::round(v) && a < 1e9) {
    std::snprintf(buf, sizeof buf, "%.0f", v);
  } else if (a >= 1e-3 && a < 1e6) {
    const int mag = static_cast<int>(std::floor(std::log10(a)));
    const int decimals = std::max(0, 3 - mag);
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    // Drop trailing zeros of the fraction ("2.500" -> "2.5"), keeping at least one digit.
    std::string s(buf);
    if (s.find('.') != std::string::npos) {
      while (s.back() == '0') s.pop_back();
      if (s.back() == '.') s.pop_back();
    }
    return s;
  } else if (a >= 1e6 && a < 1e15) {
    // Four significant digits, written out: 1004000, not 1.004e+06.
    const double unit = std::pow(10.0, std::floor(std::log10(a)) - 3);
    std::snprintf(buf, sizeof buf, "%.0f", std::round(v / unit) * unit);
  } else {
    std::snprintf(buf, sizeof buf, "%.4g", v);
  }
  return buf;
}

namespace {

std::string join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string s;
  for (const auto& p : parts) s += (s.empty() ? "" : separator) + p;
  return s;
}

std::string with_unit(double v, const std::string& unit) {
  return unit.empty() ? format_number(v) : format_number(v) + " " + unit;
}

std::string percent(double fraction) {
  char buf[64];
  const double pct = fraction * 100.0;
  // Two decimals; an error below them shows as a bound, not in e-notation.
  if (std::abs(pct) < 0.005 && pct != 0.0)
    std::snprintf(buf, sizeof buf, "%s<0.01%%", pct > 0 ? "+" : "-");
  else
    std::snprintf(buf, sizeof buf, "%+.2f%%", pct);
  return buf;
}

// Display width of a UTF-8 string (the table holds "±" and "µ"-free text otherwise).
std::size_t display_width(const std::string& s) {
  std::size_t n = 0;
  for (unsigned char c : s)
    if ((c & 0xC0) != 0x80) ++n;
  return n;
}

std::string pad(const std::string& s, std::size_t width) {
  const std::size_t w = display_width(s);
  return w >= width ? s : s + std::string(width - w, ' ');
}

/// Words of `text` in lines of at most `width` display columns (a longer word on a line of its
/// own).
std::vector<std::string> wrap(const std::string& text, std::size_t width) {
  std::vector<std::string> lines(1);
  std::istringstream words(text);
  for (std::string w; words >> w;) {
    std::string& last = lines.back();
    if (!last.empty() && display_width(last) + 1 + display_width(w) > width) lines.emplace_back();
    lines.back() += (lines.back().empty() ? "" : " ") + w;
  }
  return lines;
}

/// A terminal's width: what the console output of `rtsim validate` fits in.
constexpr std::size_t kTableWidth = 120;

/// `text` wrapped at kTableWidth columns, its continuation lines indented.
void paragraph(std::ostream& out, const std::string& text) {
  const std::string indent(6, ' ');
  const auto lines = wrap(text, kTableWidth - indent.size());
  for (std::size_t i = 0; i < lines.size(); ++i) out << (i ? indent : "") << lines[i] << "\n";
}

/// The table of `rows` (no notes, no summary), at most kTableWidth columns wide where the
/// numbers allow: the numbers first, then the figure and its source, wrapped.
std::string rows_table(const std::vector<const Row*>& rows) {
  const std::vector<std::string> head = {"id",        "seed",   "simulated",      "error",
                                         "tolerance", "result", "figure (source)"};
  std::vector<std::vector<std::string>> cells;
  for (const Row* row : rows) {
    const Row& r = *row;
    const auto rel = r.relative_error();
    cells.push_back({r.id,
                     r.seed_display.empty() ? with_unit(r.seed_value, r.unit) : r.seed_display,
                     r.simulated ? with_unit(*r.simulated, r.unit) : "-", rel ? percent(*rel) : "-",
                     r.tolerance.describe(),
                     !r.class_error.empty() ? "FAIL (class)"
                     : r.pass()             ? "pass"
                     : r.open.empty()       ? "FAIL"
                                            : "FAIL (open)",
                     r.title + " (" + cite_seeds(r.seed_ref) + ")"});
  }
  const std::size_t last = head.size() - 1;
  std::vector<std::size_t> width(head.size());
  std::size_t indent = 0;  // where the figure's column starts
  for (std::size_t c = 0; c < last; ++c) {
    width[c] = display_width(head[c]);
    for (const auto& row : cells) width[c] = std::max(width[c], display_width(row[c]));
    indent += width[c] + 2;
  }
  const std::size_t figure_width =
      std::max<std::size_t>(kTableWidth - std::min(indent, kTableWidth), 30);
  std::ostringstream out;
  auto line = [&](const std::vector<std::string>& cols) {
    std::string s;
    for (std::size_t c = 0; c < last; ++c) s += pad(cols[c], width[c] + 2);
    const auto figure = wrap(cols[last], figure_width);
    out << s << figure.front() << "\n";
    for (std::size_t i = 1; i < figure.size(); ++i)
      out << std::string(indent, ' ') << figure[i] << "\n";
  };
  line(head);
  std::vector<std::string> rule;
  for (std::size_t c = 0; c < last; ++c) rule.push_back(std::string(width[c], '-'));
  rule.push_back(std::string(std::min(figure_width, display_width(head[last]) + 20), '-'));
  line(rule);
  for (const auto& row : cells) line(row);
  return out.str();
}

}  // namespace

std::string format_table(const std::vector<Row>& rows) {
  // Measured figures, then qualitative ones, then apart the derived rows: they restate the
  // model's parameters against the seed's arithmetic, so they are not reproductions.
  std::vector<const Row*> by_class[3];
  for (const auto& r : rows) by_class[static_cast<int>(r.figure_class)].push_back(&r);
  const auto& measured = by_class[static_cast<int>(FigureClass::kMeasured)];
  const auto& derived = by_class[static_cast<int>(FigureClass::kDerived)];
  const auto& qualitative = by_class[static_cast<int>(FigureClass::kQualitative)];
  std::ostringstream out;
  bool first = true;
  const auto section = [&](const std::vector<const Row*>& part, const char* heading) {
    if (part.empty()) return;
    out << (first ? "" : "\n");
    for (const auto& l : wrap(heading, kTableWidth)) out << l << "\n";
    out << rows_table(part);
    first = false;
  };
  section(measured, "Measured (the figure emerges from a simulated run)");
  section(qualitative, "Qualitative (a shape or an order the seed states without a number)");
  section(derived,
          "Derived (the seed's arithmetic on stated numbers, checked against the model's "
          "parameters: they move with the parameters, so they are not reproductions)");

  bool any_note = false;
  for (const auto& r : rows) {
    if (r.note.empty() && r.error.empty() && r.class_error.empty()) continue;
    if (!any_note) out << "\n";
    any_note = true;
    if (!r.error.empty()) paragraph(out, r.id + ": error: " + r.error);
    if (!r.class_error.empty()) paragraph(out, r.id + ": class error: " + r.class_error);
    if (!r.note.empty()) paragraph(out, r.id + ": " + r.note);
  }
  const auto passing = [](const std::vector<const Row*>& part) {
    return static_cast<std::size_t>(
        std::count_if(part.begin(), part.end(), [](const Row* r) { return r->pass(); }));
  };
  std::ostringstream summary;
  summary << measured.size() << " measured, " << derived.size() << " derived, "
          << qualitative.size() << " qualitative; " << passing(measured) << " of "
          << measured.size() << " measured pass, " << passing(qualitative) << " of "
          << qualitative.size() << " qualitative hold, " << passing(derived) << " of "
          << derived.size() << " derived agree";
  std::size_t open_failing = 0;
  for (const auto& r : rows) {
    if (!r.pass() && !r.open.empty()) {
      if (open_failing++ == 0) summary << " (known open:";
      summary << " " << r.id;
    }
  }
  if (open_failing > 0) summary << "; docs/validation.md)";
  out << "\n";
  paragraph(out, summary.str());
  for (const auto& r : rows) {
    if (!r.pass() && !r.open.empty()) paragraph(out, r.id + " is open: " + r.open);
  }
  return out.str();
}

nlohmann::ordered_json rows_to_json(const std::vector<Row>& rows) {
  auto arr = nlohmann::ordered_json::array();
  for (const auto& r : rows) {
    nlohmann::ordered_json j;
    j["id"] = r.id;
    j["title"] = r.title;
    j["seed_ref"] = r.seed_ref;
    j["seed_text"] = r.seed_text;
    j["unit"] = r.unit;
    j["seed_value"] = r.seed_value;
    j["seed_display"] = r.seed_display;
    // JSON has no inf or nan: such a value is written as null and explained in "error".
    if (r.simulated && std::isfinite(*r.simulated))
      j["simulated_value"] = *r.simulated;
    else
      j["simulated_value"] = nullptr;
    const auto rel = r.relative_error();
    if (rel && std::isfinite(*rel))
      j["relative_error"] = *rel;
    else
      j["relative_error"] = nullptr;
    nlohmann::ordered_json t;
    t["kind"] = kind_name(r.tolerance.kind);
    if (r.tolerance.kind == Tolerance::Kind::kRange) {
      t["lo"] = r.tolerance.lo;
      t["hi"] = r.tolerance.hi;
    } else {
      t["value"] = r.tolerance.value;
    }
    t["text"] = r.tolerance.describe();
    t["why"] = r.tolerance.why;
    j["tolerance"] = t;
    j["pass"] = r.pass();
    j["class"] = class_name(r.figure_class);
    j["assumptions"] = r.assumptions;
    j["formula_params"] = r.formula_params;
    j["class_error"] = r.class_error;
    if (r.open.empty())
      j["open"] = nullptr;
    else
      j["open"] = r.open;
    j["note"] = r.note;
    j["error"] = r.error;
    j["workload"] = r.workload;
    j["commands"] = r.commands;
    arr.push_back(std::move(j));
  }
  return arr;
}

std::string rows_to_csv(const std::vector<Row>& rows) {
  std::ostringstream out;
  out << "id,title,seed_ref,unit,seed_value,seed_display,simulated_value,relative_error,"
         "tolerance,pass,note,error,class,assumptions\n";
  for (const auto& r : rows) {
    const auto rel = r.relative_error();
    out << csv_field(r.id) << ',' << csv_field(r.title) << ',' << csv_field(r.seed_ref) << ','
        << csv_field(r.unit) << ',' << exact_number(r.seed_value) << ','
        << csv_field(r.seed_display) << ',' << (r.simulated ? exact_number(*r.simulated) : "")
        << ',' << (rel ? exact_number(*rel) : "") << ',' << csv_field(r.tolerance.describe()) << ','
        << (r.pass() ? "pass" : "fail") << ',' << csv_field(r.note) << ',' << csv_field(r.error)
        << ',' << class_name(r.figure_class) << ',' << csv_field(join(r.assumptions, " ")) << "\n";
  }
  return out.str();
}

}  // namespace rtsim::validation
