#include "modules/wiring.hpp"

namespace rtsim::modules {

std::vector<Connection>& wiring() {
  static std::vector<Connection> all;
  return all;
}

std::vector<RingStop>& ring_stops() {
  static std::vector<RingStop> all;
  return all;
}

}  // namespace rtsim::modules
