#include "platform/runs/run_request.hpp"

namespace rtsim::runs {

std::string shell_quote(const std::string& s) {
  if (!s.empty() && s.find_first_of(" \t\"'\\$`|&;<>()*?[]{}~#!") == std::string::npos) return s;
  std::string out = "'";
  for (char c : s) {
    if (c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  return out + "'";
}

std::string RunRequest::command_line() const {
  std::string s = "rtsim";
  for (const auto& a : args) {
    s += ' ';  // not `" " + shell_quote(a)`: GCC 12's -Wrestrict, bug 105651
    s += shell_quote(a);
  }
  return s;
}

}  // namespace rtsim::runs
