#include "modules/removal_order.hpp"

namespace rtsim::modules {

namespace {

/// A module near the registry's front: nothing but its place.
class FrontModule final : public sc_core::sc_module {
 public:
  explicit FrontModule(const sc_core::sc_module_name& name) : sc_core::sc_module(name) {}
  const char* kind() const override { return RemovalOrder::kKind; }
};

}  // namespace

RemovalOrder::RemovalOrder() {
  for (auto& m : front_)
    m = std::make_unique<FrontModule>(sc_core::sc_gen_unique_name("removal_order"));
}

RemovalOrder::~RemovalOrder() { release(); }

void RemovalOrder::release() {
  for (auto& m : front_) m.reset();
}

}  // namespace rtsim::modules
