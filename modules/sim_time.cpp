#include "modules/sim_time.hpp"

#include <atomic>

namespace rtsim::modules {

namespace {
std::atomic<bool> overflowed{false};
}  // namespace

void time_overflow() {
  overflowed = true;
  throw TimeOverflow();
}

bool time_overflowed() { return overflowed; }

}  // namespace rtsim::modules
