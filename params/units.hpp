#pragma once
// Physical quantities written the way an architect writes them: "400 ns", "5 MHz", "5 Gbit/s",
// "64 KiB". A Quantity holds its value in the SI base unit of its class (seconds, hertz, bit/s,
// bits) as a double; a time also converts exactly to integer picoseconds, SystemC's resolution.
//
// Spellings are case-sensitive, as in SI ("ms" is a millisecond, "Ms" is nothing). A space
// between number and unit is optional.
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

namespace rtsim::params {

enum class UnitClass { kDimensionless, kTime, kFrequency, kBitRate, kDataSize };

/// One accepted spelling: `scale` base units per one of this unit ("ns" -> 1e-9 s). Output uses
/// only the spellings marked `for_output` (ASCII "us", not "µs"; "bit", not "bits").
struct Unit {
  std::string_view symbol;
  double scale;
  bool for_output;
};

/// Bad quantity text, or a time that is not a whole number of picoseconds. The message says what
/// is wrong and what was expected; the registry prefixes the parameter name and turns it into an
/// InputError with file and line.
class UnitError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct Quantity {
  double value = 0.0;  ///< in the SI base unit of unit_class (s, Hz, bit/s, bit)
  UnitClass unit_class = UnitClass::kDimensionless;

  /// A time as integer picoseconds. Throws UnitError if not a time, not a whole number of
  /// picoseconds, or beyond int64 (about 106 days).
  std::int64_t to_ps() const;
};

/// "time", "frequency", "bit rate", "data size", "number".
std::string_view unit_class_name(UnitClass c);
/// The unit a Quantity's value is in: "s", "Hz", "bit/s", "bit"; "" for dimensionless.
std::string_view base_unit(UnitClass c);
/// Every accepted spelling of the class, in increasing scale (empty for dimensionless).
std::span<const Unit> units_of(UnitClass c);
/// `expected a time such as "400 ns"; units: ps, ns, us, µs, ms, s` — the tail of every error.
std::string expected_form(UnitClass c);

/// Parses "<number> [unit]" where the unit must belong to `expected` (dimensionless: no unit).
/// The number is a decimal floating-point literal ("5.6", "1e3", "-2"); inf and NaN are rejected.
Quantity parse_quantity(std::string_view text, UnitClass expected);

/// A readable string that parse_quantity reads back: the largest unit that keeps the number at or
/// above 1, up to 15 significant digits ("333.333 ns", "5 MHz", "64 KiB", "12 bit"). A data size
/// that is not a whole number of bytes is written in bits.
std::string format_quantity(const Quantity& q);

}  // namespace rtsim::params
