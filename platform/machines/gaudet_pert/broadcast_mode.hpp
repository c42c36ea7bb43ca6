#pragma once
// How Gaudet's machine gets the data sets to its processors: the machine's `broadcast.mode` and
// `broadcast.order` (declared in platform/machines/gaudet_pert/machine.cpp).
#include <string>

namespace rtsim::platform::gaudet {

/// How the processors get the data sets (seed 001 §5.1, Fig. 6-9).
enum class BroadcastMode {
  kAdaptive,     ///< only packets some BIC asked for are sent (§5.1.2, L835-L837)
  kNonAdaptive,  ///< every packet every cycle (L837, L1047)
  kDirect,       ///< no broadcast: every processor holds its whole data set (L806, L1103)
};

/// Order of the ID list in the Broadcast Processors' memories (Fig. 6-11, L1019).
enum class BroadcastOrder { kBreadth, kDepth, kRandom };

BroadcastMode broadcast_mode(const std::string& name);
BroadcastOrder broadcast_order(const std::string& name);
const char* mode_name(BroadcastMode m);
const char* order_name(BroadcastOrder o);

}  // namespace rtsim::platform::gaudet
