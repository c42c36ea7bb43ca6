#pragma once
// Time helpers. SystemC's time resolution is 1 ps (its default); every delay parameter is a
// whole number of picoseconds (params/ checks it), so sums and multiples are exact.
//
// Simulated time is a 64-bit count of picoseconds: it ends 2^64 ps (about 213 days) after the
// start. The kit's time arithmetic (times, plus, LocalClock) throws TimeOverflow where it would
// pass that end, instead of wrapping round to a small, wrong number; MachineRun turns it into
// bad input (the parameters made the frame too long). Used by every machine.
#include <cstdint>
#include <stdexcept>
#include <systemc>
#include <type_traits>

namespace rtsim::modules {

class TimeOverflow : public std::overflow_error {
 public:
  TimeOverflow()
      : std::overflow_error(
            "simulated time passed 2^64 ps (about 213 days), the end of SystemC's time") {}
};

/// Records that simulated time overflowed (SystemC may wrap the exception thrown from a
/// process into its own report) and throws TimeOverflow.
[[noreturn]] void time_overflow();
/// Whether time_overflow() was called in this process.
bool time_overflowed();

namespace sim_time_detail {
/// While a WakeQueue runs its clients ahead of SystemC (modules/wake_queue.hpp): the time of
/// the wake it runs; else null.
inline const sc_core::sc_time* ahead = nullptr;
}  // namespace sim_time_detail

/// SystemC's own time: sc_core::sc_time_stamp(), inline (that function is a call into the
/// library). A delay handed to SystemC (an event's notify, a wait) counts from this time.
inline const sc_core::sc_time& systemc_now() {
  return sc_core::sc_get_curr_simcontext()->time_stamp();
}

/// The simulated time now, as the model sees it: SystemC's, or, while a WakeQueue runs its
/// clients ahead of SystemC, the time of the wake it runs. Every step of a processor, every
/// message and every wake asks it (about nine million times in a 32 x 32 array's run).
inline const sc_core::sc_time& sim_now() {
  if (sim_time_detail::ahead != nullptr) return *sim_time_detail::ahead;
  return systemc_now();
}

/// The time of `v` ticks (picoseconds), as sc_time::from_value gives it but inline: from_value
/// is a call into the library that checks the time resolution each time (a few percent of a
/// large array's run, where every step of a processor's time is made this way). The resolution
/// is fixed long before: every parameter is an sc_time with a unit. sc_time is standard-layout
/// with the tick count its only member, so its address is the count's.
inline sc_core::sc_time from_ticks(sc_core::sc_time::value_type v) {
  static_assert(std::is_standard_layout_v<sc_core::sc_time> &&
                sizeof(sc_core::sc_time) == sizeof(sc_core::sc_time::value_type));
  sc_core::sc_time t;
  *reinterpret_cast<sc_core::sc_time::value_type*>(&t) = v;
  return t;
}

/// n x t, exactly (integer picoseconds; sc_time * double would round through a double).
inline sc_core::sc_time times(const sc_core::sc_time& t, std::uint64_t n) {
  sc_core::sc_time::value_type v = 0;
  if (__builtin_mul_overflow(t.value(), n, &v)) time_overflow();
  return from_ticks(v);
}

/// a + b, exactly, or TimeOverflow.
inline sc_core::sc_time plus(const sc_core::sc_time& a, const sc_core::sc_time& b) {
  sc_core::sc_time::value_type v = 0;
  if (__builtin_add_overflow(a.value(), b.value(), &v)) time_overflow();
  sc_core::sc_time sum(a);  // += is inline; from_value is a call into the library, with checks
  sum += b;
  return sum;
}

inline sc_core::sc_time from_ps(std::int64_t ps) {
  return from_ticks(static_cast<sc_core::sc_time::value_type>(ps));
}

inline double seconds(const sc_core::sc_time& t) { return t.to_seconds(); }

}  // namespace rtsim::modules
