#include "app/number_text.hpp"

#include <cmath>
#include <cstdio>

namespace rtsim::app {

std::string format_number(double v, int digits) {
  if (!std::isfinite(v)) return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
  char buf[64];
  if (v == std::round(v) && std::abs(v) < 1e15)
    std::snprintf(buf, sizeof buf, "%.0f", v);
  else
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

std::string format_significant(double v, int digits) {
  if (!std::isfinite(v)) return format_number(v);
  if (v == 0.0) return "0";
  // Digits before the point, after rounding to `digits` significant ones (999.96 -> "1000").
  const int before = static_cast<int>(std::floor(std::log10(std::abs(v)))) + 1;
  int decimals = std::max(0, digits - before);
  const double rounded = std::round(v * std::pow(10.0, decimals)) / std::pow(10.0, decimals);
  if (std::abs(rounded) >= std::pow(10.0, before)) decimals = std::max(0, decimals - 1);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string format_seconds(double s) {
  if (!std::isfinite(s)) return format_number(s);
  const double a = std::abs(s);
  if (a < 1e-12) return "0 s";
  struct Unit {
    double seconds;
    const char* name;
  };
  // From the largest down: the first unit the value reaches one of.
  static constexpr Unit kUnits[] = {{3600.0, "h"}, {60.0, "min"}, {1.0, "s"},
                                    {1e-3, "ms"},  {1e-6, "µs"},  {1e-9, "ns"}};
  for (const Unit& u : kUnits) {
    // Judged as rounded for showing: 0.99996 ms is "1.000 ms", not "1000 µs".
    if (std::stod(format_significant(a / u.seconds)) >= 1.0 || u.seconds == 1e-9)
      return format_significant(s / u.seconds) + " " + u.name;
  }
  return format_number(s) + " s";
}

bool names_seconds(std::string_view name) {
  // A rate ("rays_per_s", "throughput_rpi_per_s") is per second, not seconds.
  const auto seconds = [](std::string_view n) { return !n.ends_with("_per_s"); };
  if (name.ends_with("_s")) return seconds(name);
  // A summary of times ("ray_latency_s.p99") holds times, except its count of samples.
  const std::size_t dot = name.find("_s.");
  return dot != std::string_view::npos && seconds(name.substr(0, dot + 2)) &&
         !name.ends_with(".count") && !name.ends_with(".counts");
}

bool names_fraction(std::string_view name) {
  name = name.substr(name.rfind('.') + 1);  // the last segment (npos + 1 is 0: all of it)
  return name.ends_with("utilization") || name.ends_with("utilisation") ||
         name.find("fraction") != std::string_view::npos || name == "share" ||
         name.ends_with("_share");
}

namespace {
/// A whole number as it is, another to 4 significant digits.
std::string plain(double x) {
  if (x == std::round(x) && std::abs(x) < 1e15) return format_number(x);
  return format_significant(x, 4);
}
}  // namespace

std::string format_figure(std::string_view name, double x) {
  if (names_seconds(name)) return format_seconds(x);
  if (names_fraction(name)) return format_percent(x);
  return plain(x);
}

std::string format_in_unit(modules::StatUnit unit, double x) {
  using modules::StatUnit;
  if (!std::isfinite(x)) return format_number(x);
  switch (unit) {
    case StatUnit::seconds:
      return format_seconds(x);
    case StatUnit::rate:
      return plain(x) + "/s";
    case StatUnit::fraction:
      return format_percent(x);
    case StatUnit::bytes: {
      const double a = std::abs(x);
      if (a >= 1e9) return format_significant(x / 1e9) + " GB";
      if (a >= 1e6) return format_significant(x / 1e6) + " MB";
      if (a >= 1e3) return format_significant(x / 1e3) + " kB";
      return plain(x) + " bytes";
    }
    case StatUnit::bits:
      return plain(x) + " bits";
    case StatUnit::words:
      return plain(x) + " words";
    case StatUnit::count:
    case StatUnit::ratio:
      break;
  }
  return plain(x);
}

std::string format_figure(const modules::UnitSchema& units, std::string_view path, double x) {
  if (const auto unit = units.unit_of(path)) return format_in_unit(*unit, x);
  return format_figure(path, x);
}

std::string format_change(double relative) {
  if (!std::isfinite(relative)) return format_number(relative);
  if (relative == 0.0) return "0%";
  std::string text = relative > 0 ? "+" : "";
  text += format_significant(100.0 * relative, 3);
  text += '%';
  return text;
}

std::string format_percent(double fraction) {
  if (!std::isfinite(fraction)) return format_number(fraction);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f%%", 100.0 * fraction);
  return buf;
}

}  // namespace rtsim::app
