#include "platform/machines/gaudet_pert/broadcast_mode.hpp"

namespace rtsim::platform::gaudet {

BroadcastMode broadcast_mode(const std::string& name) {
  return name == "direct"         ? BroadcastMode::kDirect
         : name == "non-adaptive" ? BroadcastMode::kNonAdaptive
                                  : BroadcastMode::kAdaptive;
}

BroadcastOrder broadcast_order(const std::string& name) {
  return name == "depth"    ? BroadcastOrder::kDepth
         : name == "random" ? BroadcastOrder::kRandom
                            : BroadcastOrder::kBreadth;
}

const char* mode_name(BroadcastMode m) {
  return m == BroadcastMode::kDirect        ? "direct"
         : m == BroadcastMode::kNonAdaptive ? "non-adaptive"
                                            : "adaptive";
}

const char* order_name(BroadcastOrder o) {
  return o == BroadcastOrder::kDepth    ? "depth"
         : o == BroadcastOrder::kRandom ? "random"
                                        : "breadth";
}

}  // namespace rtsim::platform::gaudet
