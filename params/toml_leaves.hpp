#pragma once
// Every value of a TOML table with its dotted name, in file order: `[a.b] c = 1`, `a.b.c = 1`
// and `"a.b.c" = 1` all give "a.b.c". Tables (including inline ones) are walked; anything else
// is a leaf. toml++ keeps keys sorted, so the leaves are put back in the order they appear in
// the file (the first problem reported is the first in the file). Config files (registry.cpp)
// and a sweep file's [params] (sweep_file.cpp) read parameters this way.
#include <toml++/toml.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace rtsim::params {

using TomlLeaves = std::vector<std::pair<std::string, const toml::node*>>;

namespace detail {
inline void collect_toml_leaves(const toml::table& table, const std::string& prefix,
                                TomlLeaves& out) {
  for (const auto& [key, node] : table) {
    std::string name =
        prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
    if (const auto* sub = node.as_table()) {
      collect_toml_leaves(*sub, name, out);
    } else {
      out.emplace_back(std::move(name), &node);
    }
  }
}
}  // namespace detail

inline TomlLeaves toml_leaves_in_file_order(const toml::table& table) {
  TomlLeaves leaves;
  detail::collect_toml_leaves(table, "", leaves);
  std::stable_sort(leaves.begin(), leaves.end(), [](const auto& a, const auto& b) {
    return a.second->source().begin < b.second->source().begin;
  });
  return leaves;
}

}  // namespace rtsim::params
