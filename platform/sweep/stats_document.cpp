#include "platform/sweep/stats_document.hpp"

#include "common/input_error.hpp"

namespace rtsim::sweep {
namespace {

/// The deepest nesting of arrays and objects in a JSON text, counted without parsing it
/// (strings skipped, escapes honoured); it stops counting past `limit`.
std::size_t json_depth(std::string_view text, std::size_t limit) {
  std::size_t depth = 0, deepest = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      if (++depth > deepest) deepest = depth;
      if (deepest > limit) return deepest;
    } else if ((c == '}' || c == ']') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

std::string shape_problem(const nlohmann::ordered_json& j) {
  if (!j.is_object()) return std::string("it is a JSON ") + j.type_name() + ", not an object";
  const auto command = j.find("command");
  if (command == j.end() || !command->is_string() || (*command != "run" && *command != "render"))
    return "its \"command\" is not \"run\" or \"render\"";
  for (const char* key : {"machine", "scene"})
    if (const auto it = j.find(key); it == j.end() || !it->is_string())
      return std::string("its \"") + key + "\" is not a string";
  for (const char* key : {"width", "height"})
    if (const auto it = j.find(key);
        it == j.end() || !it->is_number_unsigned() || it->get<std::uint64_t>() == 0)
      return std::string("its \"") + key + "\" is not a whole number from 1";
  return "";
}

/// Parses `text` after the depth check; `problem` says why not when it returns a null.
nlohmann::ordered_json parse_checked(std::string_view text, std::string& problem) {
  if (json_depth(text, kMaxStatsDepth) > kMaxStatsDepth) {
    problem = "it nests more than " + std::to_string(kMaxStatsDepth) + " levels deep";
    return nullptr;
  }
  auto j = nlohmann::ordered_json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) {
    problem = "it is not valid JSON";
    return nullptr;
  }
  problem = shape_problem(j);
  return j;
}

}  // namespace

std::string stats_json_problem(std::string_view text) {
  std::string problem;
  (void)parse_checked(text, problem);
  return problem;
}

nlohmann::ordered_json read_stats_json(std::string_view text, const std::string& origin) {
  std::string problem;
  auto j = parse_checked(text, problem);
  if (!problem.empty()) throw InputError(origin, 0, "not a stats.json: " + problem);
  return j;
}

}  // namespace rtsim::sweep
