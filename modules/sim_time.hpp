#pragma once
// Time helpers. SystemC's time resolution is 1 ps (its default); every delay parameter is a
// whole number of picoseconds (platform/params checks it), so sums and multiples are exact.
// Used by every machine.
#include <cstdint>
#include <systemc>

namespace rtsim::modules {

/// n x t, exactly (integer picoseconds; sc_time * double would round through a double).
inline sc_core::sc_time times(const sc_core::sc_time& t, std::uint64_t n) {
  return sc_core::sc_time::from_value(t.value() * n);
}

inline sc_core::sc_time from_ps(std::int64_t ps) {
  return sc_core::sc_time::from_value(static_cast<sc_core::sc_time::value_type>(ps));
}

inline double seconds(const sc_core::sc_time& t) { return t.to_seconds(); }

}  // namespace rtsim::modules
