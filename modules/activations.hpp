#pragma once
// Process activations: how often each of the model's SystemC processes ran (a thread's return
// from a wait, an event-driven processor's activation). A module with nothing to do should cost
// none: no polling, no clock ticks while idle. Every wait of the kit and the machines goes
// through sim_wait (and every activation of an event-driven Processor through its resume()),
// which counts it; stats.json `simulation` reports the counts with SystemC's delta cycles
// (docs/stats.md), so two scenes' runs show what an idle module costs.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <systemc>
#include <utility>
#include <vector>

namespace rtsim::modules {

namespace activations_detail {
/// A process's count, by the kernel's number for it (sc_process_b::proc_id: 0, 1, 2, ... in the
/// order the processes were made; none is made where an ended one was). A wait then costs an
/// index, not a lookup: gaudet-pert's processors switch at every wait (1.1 M times at 1 PERT).
struct Count {
  std::uint64_t n = 0;
  std::string name;  ///< taken at its first activation: SystemC deletes a thread that has ended
};
inline std::vector<Count> by_process;
/// The first activation of `p`: room for its count, and its name.
void count_first(const sc_core::sc_process_b& p);
}  // namespace activations_detail

/// The current process ran once more (called after each wait and at each method activation).
/// Inline: it runs at every wait of every thread.
inline void count_activation() {
  // The kernel's pointer to the running process: no handle (and its reference count) a wait.
  const sc_core::sc_process_b* p = sc_core::sc_get_current_process_b();
  if (p == nullptr || p->proc_id < 0) return;
  const auto id = static_cast<std::size_t>(p->proc_id);
  std::vector<activations_detail::Count>& counts = activations_detail::by_process;
  if (id < counts.size() && counts[id].n != 0) {
    ++counts[id].n;
    return;
  }
  activations_detail::count_first(*p);
}

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
