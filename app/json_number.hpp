#pragma once
// A number of a stats.json object, 0 when the key is absent or not a number: what the console's
// summary lines read (a machine without a figure prints none of it, never "null").
#include <nlohmann/json.hpp>

namespace rtsim::app {

inline double json_number(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : 0.0;
}

}  // namespace rtsim::app
