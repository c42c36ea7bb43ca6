#pragma once
// Connections that are not TLM sockets, recorded at elaboration for `rtsim describe` (which finds
// socket bindings itself): a BIC listening on a broadcast bus, a node on a ring. A machine's
// blocks call connect() where they wire such a connection, and ring_stop() where they put a
// module on a ring. Used by gaudet-pert's buses and the token ring's channel (pxpl5-raytrace,
// ullner-array on a ring).
#include <string>
#include <string_view>
#include <vector>

namespace rtsim::modules {

struct Connection {
  std::string from, to;  ///< hierarchical names
  std::string what;      ///< "broadcast", ...
};

/// Every connection recorded in this process (one simulation per process).
std::vector<Connection>& wiring();

/// A child's hierarchical name under `parent` ("pipe" + "link_out" -> "pipe.link_out"): the
/// name of a block a module builds that is not an sc_module child of it (a Link, a class of
/// processors in a connection).
inline std::string child_name(std::string_view parent, std::string_view child) {
  std::string name(parent);
  name += '.';
  name += child;
  return name;
}

inline void connect(std::string from, std::string to, std::string what) {
  wiring().push_back({std::move(from), std::move(to), std::move(what)});
}

/// A module on a ring, at its position in the ring's order (the token passes 0, 1, ... n-1, 0):
/// `rtsim describe` draws a ring as the ring it is.
struct RingStop {
  std::string ring;  ///< the ring's hierarchical name
  std::size_t position = 0;
  std::string module;  ///< the module at that node
};

/// Every ring stop recorded in this process.
std::vector<RingStop>& ring_stops();

inline void ring_stop(std::string ring, std::size_t position, std::string module) {
  ring_stops().push_back({std::move(ring), position, std::move(module)});
}

}  // namespace rtsim::modules
