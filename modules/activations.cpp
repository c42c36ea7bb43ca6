#include "modules/activations.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

namespace rtsim::modules {

using activations_detail::Count;

namespace {
/// activation_count's, by the object a WakeQueue's client stands for.
std::unordered_map<const sc_core::sc_object*, Count>& by_object() {
  static std::unordered_map<const sc_core::sc_object*, Count> counts;
  return counts;
}
}  // namespace

void activations_detail::count_first(const sc_core::sc_process_b& p) {
  std::vector<Count>& counts = by_process;
  const auto id = static_cast<std::size_t>(p.proc_id);
  if (id >= counts.size()) counts.resize(std::max(id + 1, 2 * counts.size()));
  Count& c = counts[id];
  if (c.n++ == 0) c.name = p.name();
}

std::uint64_t& activation_count(const sc_core::sc_object& as, std::string_view process) {
  Count& c = by_object()[&as];
  if (c.name.empty()) c.name = std::string(as.name()) + "." + std::string(process);
  return c.n;
}

nlohmann::ordered_json activations_json() {
  std::map<std::string, std::uint64_t> named;  // sorted: the same inputs, the same bytes
  std::uint64_t total = 0;
  const auto add = [&](const Count& c) {
    if (c.n == 0) return;  // counted up front (activation_count), never activated; not a process
    named[c.name] += c.n;
    total += c.n;
  };
  for (const Count& c : activations_detail::by_process) add(c);
  for (const auto& [object, c] : by_object()) add(c);
  nlohmann::ordered_json out;
  out["delta_cycles"] = sc_core::sc_delta_count();
  out["process_activations"] = total;
  out["activations"] = nlohmann::ordered_json::object();
  for (const auto& [name, n] : named) out["activations"][name] = n;
  return out;
}

}  // namespace rtsim::modules
