#pragma once
// One field of a CSV line (RFC 4180): as it is, or in double quotes when it holds a comma, a
// quote or a line break (a quote inside doubled). The sweep's results.csv and validation.csv.
#include <string>

namespace rtsim {

inline std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace rtsim
