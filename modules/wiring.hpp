#pragma once
// Connections that are not TLM sockets, recorded at elaboration for `rtsim describe` (which finds
// socket bindings itself): a BIC listening on a broadcast bus, a node on a ring. A machine's
// blocks call connect() where they wire such a connection. Used by gaudet-pert's buses, and for
// the token ring and the ray array to come.
#include <string>
#include <vector>

namespace rtsim::modules {

struct Connection {
  std::string from, to;  ///< hierarchical names
  std::string what;      ///< "broadcast", ...
};

/// Every connection recorded in this process (one simulation per process).
std::vector<Connection>& wiring();

inline void connect(std::string from, std::string to, std::string what) {
  wiring().push_back({std::move(from), std::move(to), std::move(what)});
}

}  // namespace rtsim::modules
