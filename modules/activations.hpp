#pragma once
// Process activations: how often each of the model's SystemC processes ran (a thread's return
// from a wait, an event-driven processor's activation). A module with nothing to do should cost
// none: no polling, no clock ticks while idle. Every wait of the kit and the machines goes
// through sim_wait (and every activation of an event-driven Processor through its resume()),
// which counts it; stats.json `simulation` reports the counts with SystemC's delta cycles
// (docs/stats.md), so two scenes' runs show what an idle module costs.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string_view>
#include <systemc>
#include <utility>

namespace rtsim::modules {

/// The current process ran once more (called after each wait and at each method activation).
void count_activation();

/// The count of the activations of `as`'s `process` ("node12" + "activate": named as the
/// SC_METHOD it stands for would be), to add to directly: a stable address, which a processor run
/// by a WakeQueue (one SystemC process for many) keeps rather than look itself up each time.
std::uint64_t& activation_count(const sc_core::sc_object& as, std::string_view process);
/// sc_core::wait, counted: the process resumes once each time it returns.
template <class... Args>
void sim_wait(Args&&... args) {
  sc_core::wait(std::forward<Args>(args)...);
  count_activation();
}

/// stats.json `simulation`: `delta_cycles` (SystemC's), `process_activations` (all processes),
/// `activations` (by process name, those that ran).
nlohmann::ordered_json activations_json();

}  // namespace rtsim::modules
