#pragma once
// Numbers as people read them, on the console and in the reports: a few significant digits, no
// exponent, times in the engineering unit that suits them ("55.29 µs", "226.5 ms", "36.76 h").
#include <string>
#include <string_view>

#include "modules/stat_unit.hpp"

namespace rtsim::app {

/// Integers whole; others to `digits` significant digits (%g: an exponent only far from 1).
std::string format_number(double v, int digits = 4);
/// `v` to `digits` significant digits in fixed notation: "55.29", "0.1234", "12000".
std::string format_significant(double v, int digits = 4);
/// Seconds in ns, µs, ms, s, min or h, 4 significant digits: "55.29 µs", "2.517 h". Below a
/// picosecond (SystemC's resolution: rounding left-overs such as -2.7e-21) it is "0 s".
std::string format_seconds(double s);
/// Whether a stats.json name holds seconds: one ending in _s ("simulated_time_s"), or a statistic
/// of one ("ray_latency_s.p99"); not a rate ("rays_per_s").
bool names_seconds(std::string_view name);
/// Whether a stats.json name holds a fraction of a whole, shown as a percentage: a utilisation
/// ("chain_utilization"), a busy fraction, a share.
bool names_fraction(std::string_view name);
/// A stats.json figure called `name` (its last segment, or a dotted path) as a person reads it:
/// seconds in their engineering unit, a fraction as a percentage, a whole number as it is, any
/// other to 4 significant digits; never an exponent.
std::string format_figure(std::string_view name, double value);
/// `value` in `unit` as a person reads it: seconds in their engineering unit, a rate as
/// "915751/s", a count as the number, a fraction as a percentage, bytes in kB, MB or GB, bits
/// and words with their unit ("1024 bits"); never an exponent.
std::string format_in_unit(modules::StatUnit unit, double value);
/// The figure at stats path `path` in the unit `units` declares for it (stats.json `units`);
/// by its name (format_figure) where nothing declares one (a file written before units were).
std::string format_figure(const modules::UnitSchema& units, std::string_view path, double value);
/// A relative change as a signed percentage, 3 significant digits: 3.76 -> "+376%", -0.807 ->
/// "-80.7%", 0 -> "0%".
std::string format_change(double relative);
/// A fraction as a percentage with one decimal: 0.9994 -> "99.9%".
std::string format_percent(double fraction);

}  // namespace rtsim::app
