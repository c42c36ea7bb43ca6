#include "modules/stat_classes.hpp"

#include <algorithm>
#include <cctype>
#include <limits>
#include <map>

namespace rtsim::modules {

std::string instance_class(std::string_view name) {
  std::string out;
  std::size_t begin = 0;
  while (begin <= name.size()) {
    const std::size_t dot = std::min(name.find('.', begin), name.size());
    std::string_view part = name.substr(begin, dot - begin);
    std::size_t digits = part.size();
    while (digits > 0 && std::isdigit(static_cast<unsigned char>(part[digits - 1]))) --digits;
    // A part that is all digits stays what it is: it names no instance of anything.
    if (digits > 0 && digits < part.size()) {
      out.append(part.substr(0, digits));
      out += '*';
    } else {
      out.append(part);
    }
    if (dot == name.size()) break;
    out += '.';
    begin = dot + 1;
  }
  return out;
}

namespace {
void leaves(const nlohmann::ordered_json& j, const std::string& prefix,
            std::vector<std::pair<std::string, double>>& out) {
  for (const auto& [key, value] : j.items()) {
    if (key == "utilization_windows") continue;  // a series over time, not a figure
    const std::string path = prefix.empty() ? key : prefix + "." + key;
    if (value.is_object())
      leaves(value, path, out);
    else if (value.is_number())
      out.emplace_back(path, value.get<double>());
  }
}

struct Aggregate {
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();
  double sum = 0.0;
  std::size_t count = 0;
  std::string max_instance;
};
}  // namespace

std::vector<std::pair<std::string, double>> numeric_leaves(const nlohmann::ordered_json& module) {
  std::vector<std::pair<std::string, double>> out;
  if (module.is_object()) leaves(module, "", out);
  return out;
}

nlohmann::ordered_json class_aggregates(const nlohmann::ordered_json& modules) {
  struct Class {
    std::size_t instances = 0;
    std::vector<std::string> order;  ///< keys in the order the instances report them
    std::map<std::string, Aggregate> keys;
  };
  std::map<std::string, Class> classes;
  for (const auto& [name, module] : modules.items()) {
    Class& c = classes[instance_class(name)];
    ++c.instances;
    for (const auto& [key, v] : numeric_leaves(module)) {
      auto [it, added] = c.keys.try_emplace(key);
      if (added) c.order.push_back(key);
      Aggregate& a = it->second;
      a.min = std::min(a.min, v);
      if (v > a.max) {  // ties: the first in name order
        a.max = v;
        a.max_instance = name;
      }
      a.sum += v;
      ++a.count;
    }
  }
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  auto& by_name = out.get_ref<nlohmann::ordered_json::object_t&>();  // unique names, appended
  for (const auto& [name, c] : classes) {
    if (c.instances < 2) continue;
    nlohmann::ordered_json j;
    j["instances"] = c.instances;
    for (const auto& key : c.order) {
      const Aggregate& a = c.keys.at(key);
      nlohmann::ordered_json k = {{"min", a.min},
                                  {"mean", a.sum / static_cast<double>(a.count)},
                                  {"max", a.max},
                                  {"sum", a.sum},
                                  {"max_instance", a.max_instance}};
      if (a.count < c.instances) k["instances_reporting"] = a.count;
      j[key] = std::move(k);
    }
    by_name.emplace_back(name, std::move(j));
  }
  return out;
}

}  // namespace rtsim::modules
