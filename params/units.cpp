#include "params/units.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>

#include "common/leading_plus.hpp"

namespace rtsim::params {
namespace {

// Accepted spellings per class, smallest unit first. "µs" is spelled with the micro sign U+00B5;
// parse_quantity also reads a Greek mu U+03BC there, which some editors substitute.
constexpr std::array<Unit, 6> kTimeUnits{{{"ps", 1e-12, true},
                                          {"ns", 1e-9, true},
                                          {"us", 1e-6, true},
                                          {"\u00b5s", 1e-6, false},
                                          {"ms", 1e-3, true},
                                          {"s", 1.0, true}}};
constexpr std::array<Unit, 4> kFrequencyUnits{
    {{"Hz", 1.0, true}, {"kHz", 1e3, true}, {"MHz", 1e6, true}, {"GHz", 1e9, true}}};
constexpr std::array<Unit, 4> kBitRateUnits{
    {{"bit/s", 1.0, true}, {"kbit/s", 1e3, true}, {"Mbit/s", 1e6, true}, {"Gbit/s", 1e9, true}}};
// Sizes are binary (KiB = 1024 B), as memory sizes were in these machines' day.
constexpr std::array<Unit, 8> kDataSizeUnits{{{"bit", 1.0, true},
                                              {"bits", 1.0, false},
                                              {"B", 8.0, true},
                                              {"byte", 8.0, false},
                                              {"bytes", 8.0, false},
                                              {"KiB", 8.0 * 1024, true},
                                              {"MiB", 8.0 * 1024 * 1024, true},
                                              {"GiB", 8.0 * 1024 * 1024 * 1024, true}}};

constexpr std::string_view kMicroSign = "\u00b5";
constexpr std::string_view kGreekMu = "\u03bc";

constexpr std::array<UnitClass, 4> kPhysicalClasses{UnitClass::kTime, UnitClass::kFrequency,
                                                    UnitClass::kBitRate, UnitClass::kDataSize};

std::string_view example_of(UnitClass c) {
  switch (c) {
    case UnitClass::kTime:
      return "400 ns";
    case UnitClass::kFrequency:
      return "5 MHz";
    case UnitClass::kBitRate:
      return "5 Gbit/s";
    case UnitClass::kDataSize:
      return "64 KiB";
    case UnitClass::kDimensionless:
      break;
  }
  return "2.5";
}

const Unit* find_unit(UnitClass c, std::string_view symbol) {
  for (const Unit& u : units_of(c)) {
    if (u.symbol == symbol) return &u;
  }
  return nullptr;
}

// Sub-unit scales (1e-9) are not exact doubles but their reciprocals (1e9) are: dividing by the
// reciprocal rounds once, so "400 ns" gives the same double as the literal 400e-9.
double to_base(double number, const Unit& u) {
  return u.scale < 1.0 ? number / std::round(1.0 / u.scale) : number * u.scale;
}
double from_base(double value, const Unit& u) {
  return u.scale < 1.0 ? value * std::round(1.0 / u.scale) : value / u.scale;
}

std::string_view trim(std::string_view s) {
  const auto is_space = [](char ch) { return ch == ' ' || ch == '\t'; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

// Built by appending: GCC 12 misreports `"\"" + std::string(s)` under -Wrestrict (PR 105329).
std::string quoted(std::string_view s) {
  std::string out(1, '"');
  out += s;
  out += '"';
  return out;
}

// Up to 15 significant digits: every decimal with 15 digits survives a trip through a double, so
// "333.333 ns" prints as written rather than as 333.33299999999997.
std::string format_number(double v) {
  std::array<char, 64> buf{};
  const auto r =
      std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, 15);
  return std::string(buf.data(), r.ptr);
}

}  // namespace

std::string_view unit_class_name(UnitClass c) {
  switch (c) {
    case UnitClass::kTime:
      return "time";
    case UnitClass::kFrequency:
      return "frequency";
    case UnitClass::kBitRate:
      return "bit rate";
    case UnitClass::kDataSize:
      return "data size";
    case UnitClass::kDimensionless:
      break;
  }
  return "number";
}

std::string_view base_unit(UnitClass c) {
  switch (c) {
    case UnitClass::kTime:
      return "s";
    case UnitClass::kFrequency:
      return "Hz";
    case UnitClass::kBitRate:
      return "bit/s";
    case UnitClass::kDataSize:
      return "bit";
    case UnitClass::kDimensionless:
      break;
  }
  return "";
}

std::span<const Unit> units_of(UnitClass c) {
  switch (c) {
    case UnitClass::kTime:
      return kTimeUnits;
    case UnitClass::kFrequency:
      return kFrequencyUnits;
    case UnitClass::kBitRate:
      return kBitRateUnits;
    case UnitClass::kDataSize:
      return kDataSizeUnits;
    case UnitClass::kDimensionless:
      break;
  }
  return {};
}

std::string expected_form(UnitClass c) {
  std::string out =
      "expected a " + std::string(unit_class_name(c)) + " such as " + quoted(example_of(c));
  const auto units = units_of(c);
  if (!units.empty()) {
    out += "; units: ";
    for (std::size_t i = 0; i < units.size(); ++i) {
      if (i > 0) out += ", ";
      out += units[i].symbol;
    }
  }
  return out;
}

Quantity parse_quantity(std::string_view text, UnitClass expected) {
  const std::string_view s = trim(text);
  const auto fail = [&](const std::string& what) {
    throw UnitError(what + "; " + expected_form(expected));
  };

  double number = 0.0;
  const std::string_view digits = strip_leading_plus(s);  // "+1 us", as in scene files
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), number);
  if (ec == std::errc::invalid_argument) fail(quoted(s) + " is not a number");
  if (ec == std::errc::result_out_of_range) fail(quoted(s) + " is out of range");
  if (!std::isfinite(number)) fail(quoted(s) + " is not a finite number");

  std::string symbol(trim(s.substr(static_cast<std::size_t>(end - s.data()))));
  if (symbol.starts_with(kGreekMu)) symbol.replace(0, kGreekMu.size(), kMicroSign);
  if (expected == UnitClass::kDimensionless && symbol.empty()) return {number, expected};
  if (symbol.empty()) fail(quoted(s) + " has no unit");
  if (const Unit* u = find_unit(expected, symbol)) {
    const double value = to_base(number, *u);
    if (!std::isfinite(value)) fail(quoted(s) + " is out of range");
    return {value, expected};
  }
  for (UnitClass other : kPhysicalClasses) {
    if (find_unit(other, symbol) != nullptr) {
      fail(quoted(s) + " is a " + std::string(unit_class_name(other)));
    }
  }
  fail(quoted(s) + " has an unknown unit " + quoted(symbol));
  return {};  // not reached
}

std::int64_t Quantity::to_ps() const {
  if (unit_class != UnitClass::kTime) {
    throw UnitError("a " + std::string(unit_class_name(unit_class)) + " is not a time");
  }
  // The decimal text was rounded once to a double and scaled once, so a whole number of
  // picoseconds arrives within a few ulps of an integer; anything further off was not whole.
  const double ps = value * 1e12;
  const double whole = std::round(ps);
  const double tolerance =
      4.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(ps));
  // 2^63 is exactly representable; every double below it fits an int64.
  if (!(std::abs(whole) < 9223372036854775808.0)) {
    throw UnitError(format_quantity(*this) + " is beyond the int64 picosecond range");
  }
  if (std::abs(ps - whole) > tolerance) {
    throw UnitError(format_quantity(*this) + " is not a whole number of picoseconds");
  }
  return static_cast<std::int64_t>(whole);
}

std::string format_quantity(const Quantity& q) {
  const auto units = units_of(q.unit_class);
  if (units.empty()) return format_number(q.value);

  // The largest output unit not bigger than |value|; the smallest one for tiny values; the base
  // unit for zero. A data size that is not whole bytes stays in bits.
  const double magnitude = std::abs(q.value);
  const bool whole_bytes = std::fmod(magnitude, 8.0) == 0.0;
  const Unit* chosen = nullptr;
  for (const Unit& u : units) {
    if (!u.for_output) continue;
    if (q.unit_class == UnitClass::kDataSize && !whole_bytes && u.scale > 1.0) continue;
    if (chosen == nullptr || (magnitude == 0.0 ? u.scale == 1.0 : u.scale <= magnitude)) {
      chosen = &u;
    }
  }
  return format_number(from_base(q.value, *chosen)) + " " + std::string(chosen->symbol);
}

}  // namespace rtsim::params
