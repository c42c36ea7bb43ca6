#include "modules/trace/vcd_trace.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <queue>
#include <stdexcept>
#include <system_error>
#include <systemc>

namespace rtsim::modules {

namespace {

/// Identifiers are made of the printable ASCII characters '!' .. '~' (IEEE 1364 §18.2.1).
constexpr char kFirstIdChar = '!';
constexpr std::size_t kIdChars = '~' - '!' + 1;

std::vector<std::string> split_name(const std::string& name) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t dot = name.find('.', begin);
    parts.push_back(name.substr(begin, dot - begin));
    if (dot == std::string::npos) break;
    begin = dot + 1;
  }
  return parts;
}

/// VCD names are single tokens: whitespace would end them.
std::string token(std::string s) {
  for (char& c : s)
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') c = '_';
  return s;
}

std::string binary(long v) {
  if (v <= 0) return "0";  // levels are never negative (see level_steps.hpp)
  std::string out;
  for (auto u = static_cast<unsigned long>(v); u != 0; u >>= 1) out += (u & 1) ? '1' : '0';
  std::reverse(out.begin(), out.end());
  return out;
}

/// One scope of the hierarchy: its signals and its sub-scopes, in order of first appearance.
struct Scope {
  std::string name;
  std::vector<std::size_t> signals;
  std::vector<Scope> children;
  Scope& child(const std::string& n) {
    for (Scope& c : children)
      if (c.name == n) return c;
    children.push_back(Scope{n, {}, {}});
    return children.back();
  }
};

}  // namespace

std::string vcd_identifier(std::size_t index) {
  std::string id;
  do {
    id += static_cast<char>(kFirstIdChar + index % kIdChars);
    index /= kIdChars;
  } while (index != 0);
  return id;
}

std::string vcd_timescale() {
  const double res = sc_core::sc_get_time_resolution().to_seconds();
  const int exponent = static_cast<int>(std::lround(std::log10(res)));
  // SystemC resolutions are powers of ten from 1 fs; VCD units go in steps of 1000.
  static const std::map<int, const char*> kUnits = {{-15, "fs"}, {-12, "ps"}, {-9, "ns"},
                                                    {-6, "us"},  {-3, "ms"},  {0, "s"}};
  const int unit = exponent >= 0 ? 0 : -(((-exponent) + 2) / 3) * 3;
  const auto it = kUnits.find(unit);
  if (it == kUnits.end()) throw std::logic_error("VcdTrace: unsupported time resolution");
  long mantissa = 1;
  for (int i = unit; i < exponent; ++i) mantissa *= 10;
  return std::to_string(mantissa) + " " + it->second;
}

VcdTrace::VcdTrace(std::filesystem::path path) : path_(std::move(path)) {}

VcdTrace::~VcdTrace() { abandon(); }

void VcdTrace::signal(const std::string& hierarchical_name, std::vector<LevelChange> changes,
                      Kind kind) {
  if (done_) throw std::logic_error("VcdTrace: " + hierarchical_name + " added after close()");
  for (const std::string& part : split_name(hierarchical_name))
    if (part.empty())
      throw std::invalid_argument("VcdTrace: signal name \"" + hierarchical_name +
                                  "\" has an empty segment");
  for (const Signal& s : signals_)
    if (s.name == hierarchical_name)
      throw std::invalid_argument("VcdTrace: signal " + hierarchical_name + " added twice");
  for (std::size_t i = 1; i < changes.size(); ++i)
    if (changes[i].t < changes[i - 1].t)
      throw std::invalid_argument("VcdTrace: changes of " + hierarchical_name +
                                  " are out of time order");
  signals_.push_back(Signal{hierarchical_name, std::move(changes), kind});
}

void VcdTrace::write(std::ostream& out, std::uint64_t from, std::uint64_t to,
                     std::size_t max_changes) {
  const std::size_t n = signals_.size();
  std::vector<bool> is_bit(n, true);
  for (std::size_t i = 0; i < n; ++i) {
    is_bit[i] = signals_[i].kind == Kind::kLevel;
    for (const LevelChange& c : signals_[i].changes)
      if (c.level != 0 && c.level != 1) is_bit[i] = false;
  }
  // Appends, not `literal + std::string&&`: GCC 12 -O2 reports a false -Wrestrict on that
  // (GCC bug 105651), fatal under -Werror.
  const auto value = [&](std::size_t i, long v) {
    std::string out;
    if (is_bit[i]) {
      out += v != 0 ? '1' : '0';
    } else {
      out += 'b';
      out += binary(v);
      out += ' ';
    }
    out += vcd_identifier(i);
    return out;
  };

  out << "$version rtsim $end\n$timescale " << vcd_timescale() << " $end\n";
  Scope root;
  for (std::size_t i = 0; i < n; ++i) {
    const std::vector<std::string> parts = split_name(signals_[i].name);
    Scope* s = &root;
    for (std::size_t k = 0; k + 1 < parts.size(); ++k) s = &s->child(parts[k]);
    s->signals.push_back(i);
  }
  const std::function<void(const Scope&)> declare = [&](const Scope& s) {
    for (std::size_t i : s.signals) {
      out << "$var " << (is_bit[i] ? "wire 1 " : "integer 32 ") << vcd_identifier(i) << ' '
          << token(split_name(signals_[i].name).back()) << " $end\n";
    }
    for (const Scope& c : s.children) {
      out << "$scope module " << token(c.name) << " $end\n";
      declare(c);
      out << "$upscope $end\n";
    }
  };
  declare(root);
  out << "$enddefinitions $end\n";

  // The values at `from`, then every change after it, all signals merged in time order (ties in
  // signal order, so the bytes do not depend on anything but the signals).
  std::vector<std::size_t> next(n, 0);
  out << '#' << from << "\n$dumpvars\n";
  for (std::size_t i = 0; i < n; ++i) {
    const auto& ch = signals_[i].changes;
    const auto it = std::upper_bound(ch.begin(), ch.end(), from,
                                     [](std::uint64_t t, const LevelChange& c) { return t < c.t; });
    next[i] = static_cast<std::size_t>(it - ch.begin());
    out << value(i, next[i] == 0 ? 0 : ch[next[i] - 1].level) << '\n';
  }
  out << "$end\n";
  using Entry = std::pair<std::uint64_t, std::size_t>;  // (time, signal)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap;
  for (std::size_t i = 0; i < n; ++i)
    if (next[i] < signals_[i].changes.size()) heap.push({signals_[i].changes[next[i]].t, i});
  std::uint64_t stamp = from;
  while (!heap.empty()) {
    const auto [t, i] = heap.top();
    heap.pop();
    if (t > to) continue;
    if (max_changes != 0 && written_ >= max_changes) {
      if (dropped_++ == 0) first_dropped_ = t;  // in time order: the first is the earliest
    } else {
      if (t != stamp) out << '#' << t << '\n';
      stamp = t;
      out << value(i, signals_[i].changes[next[i]].level) << '\n';
      ++written_;
    }
    if (++next[i] < signals_[i].changes.size()) heap.push({signals_[i].changes[next[i]].t, i});
  }
  // The values hold up to `to`: a last time stamp makes viewers draw them there (not when the
  // dump was cut short: the values after the last change written are unknown).
  if (dropped_ == 0 && to > stamp) out << '#' << to << '\n';
}

void VcdTrace::close(std::uint64_t from, std::uint64_t to, std::size_t max_changes) {
  if (done_) return;
  done_ = true;
  if (to < from) to = from;
  std::filesystem::path partial = path_;
  partial += ".partial";
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write trace file " + partial.string());
    write(out, from, to, max_changes);
    out.close();
    if (!out) throw std::runtime_error("error writing trace file " + partial.string());
  }
  std::error_code ec;
  std::filesystem::rename(partial, path_, ec);
  if (ec)
    throw std::runtime_error("cannot rename " + partial.string() + " to " + path_.string() + ": " +
                             ec.message());
}

void VcdTrace::abandon() {
  if (done_) return;
  done_ = true;
  std::filesystem::path partial = path_;
  partial += ".partial";
  std::error_code ec;
  std::filesystem::remove(partial, ec);
}

}  // namespace rtsim::modules
