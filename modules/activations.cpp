#include "modules/activations.hpp"

#include <map>
#include <string>
#include <unordered_map>

namespace rtsim::modules {

namespace {
struct Count {
  std::string name;  ///< taken at its first activation: SystemC deletes a thread that has ended
  std::uint64_t n = 0;
};
/// By process (all made at elaboration: none is made where an ended one was).
std::unordered_map<const sc_core::sc_object*, Count>& counts() {
  static std::unordered_map<const sc_core::sc_object*, Count> by_process;
  return by_process;
}
}  // namespace

void count_activation() {
  // The kernel's pointer to the running process: no handle (and its reference count) a wait.
  const sc_core::sc_object* p = sc_core::sc_get_current_process_b();
  if (p == nullptr) return;
  // Consecutive activations are often the same process's (a thread catching up its time).
  static const sc_core::sc_object* last = nullptr;
  static Count* last_count = nullptr;
  if (p != last) {
    last = p;
    last_count = &counts()[p];
  }
  if (last_count->n++ == 0) last_count->name = p->name();
}

std::uint64_t& activation_count(const sc_core::sc_object& as, std::string_view process) {
  Count& c = counts()[&as];
  if (c.name.empty()) c.name = std::string(as.name()) + "." + std::string(process);
  return c.n;
}

nlohmann::ordered_json activations_json() {
  std::map<std::string, std::uint64_t> named;  // sorted: the same inputs, the same bytes
  std::uint64_t total = 0;
  for (const auto& [process, c] : counts()) {
    if (c.n == 0) continue;  // counted up front (activation_count), never activated
    named[c.name] += c.n;
    total += c.n;
  }
  nlohmann::ordered_json out;
  out["delta_cycles"] = sc_core::sc_delta_count();
  out["process_activations"] = total;
  out["activations"] = nlohmann::ordered_json::object();
  for (const auto& [name, n] : named) out["activations"][name] = n;
  return out;
}

}  // namespace rtsim::modules
