#pragma once
// A number may be written with a leading '+' ("+1", "+1 us") in scene files and parameter values
// alike; std::from_chars does not take it. Used by the scene readers and the parameter registry.
#include <string_view>

namespace rtsim {

/// `text` without one leading '+' before a digit or point ("+1" -> "1"); "+-1", "++1" and "+"
/// are left as they are, to be rejected as numbers.
inline std::string_view strip_leading_plus(std::string_view text) {
  if (text.size() >= 2 && text[0] == '+' && text[1] != '-' && text[1] != '+') return text.substr(1);
  return text;
}

}  // namespace rtsim
