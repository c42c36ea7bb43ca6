#include "modules/wiring.hpp"

namespace rtsim::modules {

std::vector<Connection>& wiring() {
  static std::vector<Connection> all;
  return all;
}

}  // namespace rtsim::modules
