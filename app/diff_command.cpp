// `rtsim diff A B`: two runs compared (app/run_diff.hpp).
#include <filesystem>
#include <iostream>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/run_diff.hpp"
#include "common/input_error.hpp"
#include "common/input_file.hpp"
#include "platform/sweep/stats_document.hpp"

namespace rtsim::app {
namespace {

namespace fs = std::filesystem;

/// A run folder's stats.json, or a stats.json file itself, checked before use.
nlohmann::ordered_json read_stats(const std::string& given) {
  fs::path path = given;
  std::error_code ec;
  if (fs::is_directory(path, ec)) path /= "stats.json";
  if (!fs::exists(path, ec))
    throw InputError(given, 0,
                     fs::exists(given, ec) ? "not a run folder: it has no stats.json"
                                           : "no such file or folder (give a run's --out folder "
                                             "or its stats.json)");
  return sweep::read_stats_json(
      read_input_file(path.string(), "stats.json", sweep::kMaxStatsFileBytes, "kMaxStatsFileBytes"),
      path.string());
}

std::string label(const std::string& given, const nlohmann::ordered_json& s) {
  return given + " (" + s.value("machine", std::string("?")) + " on " +
         s.value("scene", std::string("?")) + ", " + std::to_string(s.value("width", 0)) + "x" +
         std::to_string(s.value("height", 0)) + ")";
}

}  // namespace

int run_diff(const DiffArgs& args) {
  const auto a = read_stats(args.a);
  const auto b = read_stats(args.b);
  const RunDiff d = diff_runs(a, b, args.tolerance);
  std::cout << format_run_diff(d, label(args.a, a), label(args.b, b),
                               args.all ? 0 : DiffArgs::kStatsShown);
  return kExitOk;
}

}  // namespace rtsim::app
