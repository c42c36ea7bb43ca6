#include "platform/validation/figure_registry.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace rtsim::validation {
namespace {

struct Registered {
  std::string machine;
  AddFigures add;
};

std::vector<Registered>& registered() {
  static std::vector<Registered> all;
  return all;
}

}  // namespace

RegisterFigures::RegisterFigures(std::string machine, AddFigures add) {
  registered().push_back({std::move(machine), add});
}

Plan make_validation_plan(const PlanOptions& options) {
  // By machine, whatever order the files' registrations ran in; a file's own order kept.
  std::vector<Registered> in_order = registered();
  std::stable_sort(in_order.begin(), in_order.end(),
                   [](const Registered& a, const Registered& b) { return a.machine < b.machine; });
  Plan plan;
  for (const Registered& r : in_order) r.add(plan, options);
  return plan;
}

}  // namespace rtsim::validation
