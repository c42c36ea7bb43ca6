#pragma once
// A sweep file (TOML, docs/sweeps.md): the machine(s), scene(s), image size, fixed parameters and
// the axes to vary, read into a SweepFile. Reading checks the file's own structure (keys, types,
// ranges, zipped lengths, duplicates); whether the parameters exist and their values fit is checked
// against the machines' registries by check_sweep (sweep_check.hpp).
//
//   machine = "NAME"                          # or a list: an axis
//   scene = "builtin:ullner-sheets-1000"      # or a list: an axis
//   width = 64
//   height = 64
//   [params]
//   "shade.max_depth" = 0
//   [[axes]]
//   param = "peripheral.grid.divisions"
//   range = { start = 1, stop = 30, step = 1 }
//
// Every error is an rtsim::InputError naming the file, the line and what was expected.
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rtsim::sweep {

/// Most points a sweep may have: a guard against a mistyped step (1e-9 for 1).
inline constexpr std::size_t kMaxPoints = 100000;

/// Names that are options of `rtsim run` rather than parameters. They may be set at the top level
/// or varied by an axis like a parameter.
inline constexpr std::string_view kMachine = "machine";
inline constexpr std::string_view kScene = "scene";
inline constexpr std::string_view kWidth = "width";
inline constexpr std::string_view kHeight = "height";
/// The other options of `rtsim run` a sweep may set or vary, named as the flags are: the sampled
/// simulation's, the image files written, the latency probe and traces (docs/sweeps.md). A
/// timing sweep sets `image = "none"` and `sample = K`.
inline constexpr std::string_view kRunFlags[] = {
    "sample", "sample-error",  "sample-window", "sample-warmup",   "sample-work-stride",
    "image",  "latency-probe", "trace",         "trace-max-events"};
/// A sweep's traces are capped: at most this many events a trace file, unless
/// `trace-max-events` says otherwise (each point writes its own).
inline constexpr std::int64_t kSweepTraceMaxEvents = 1000000;
bool is_run_option(std::string_view name);
/// One of kRunFlags.
bool is_run_flag(std::string_view name);

/// One value from the file: the text given to `rtsim run` (`-p NAME=TEXT`, `--width TEXT`), the
/// typed value for results.jsonl, and the line it came from (for errors).
struct Value {
  std::string text{};
  nlohmann::ordered_json json{};
  std::size_t line = 0;
};

/// A parameter (or run option) of an axis and its values.
struct AxisMember {
  std::string name{};
  std::size_t line = 0;  ///< where the name is given
  std::vector<Value> values{};
};

/// One axis of the product. Several members are zipped: they advance together, so they all
/// have the same number of values.
struct Axis {
  std::vector<AxisMember> members{};
  std::size_t line = 0;
  std::size_t size() const { return members.front().values.size(); }
};

/// A name set to one value for every point.
struct Fixed {
  std::string name{};
  Value value{};
};

struct SweepFile {
  std::string origin{};              ///< the file as named on the command line (in errors)
  std::filesystem::path base_dir{};  ///< relative scene and config paths are resolved against it
  std::string name{};                ///< optional label (`name = "..."`)
  /// Outermost first: the machine list, the scene list, then [[axes]] in file order.
  std::vector<Axis> axes{};
  /// Fixed run options (machine, scene, width, height) and [params], in file order.
  std::vector<Fixed> fixed{};
  /// `configs = [...]`: --config files of every point, resolved, with the line naming each.
  std::vector<std::pair<std::filesystem::path, std::size_t>> configs{};
  /// `share-images` (default true): points that would render the same image render it once
  /// (image_sharing.hpp); false: every point renders its own.
  bool share_images = true;

  /// Product of the axes' sizes (1 with no axes).
  std::size_t point_count() const;
  /// The parameters varied by the axes, in axis order (run options excluded).
  std::vector<std::string> swept_params() const;
  /// What the axes vary besides machine, scene, width and height: the parameters and the run
  /// flags (kRunFlags), in axis order. The results table's columns after width and height.
  std::vector<std::string> swept_columns() const;
};

/// Reads a sweep file; relative paths in it are resolved against its folder.
SweepFile read_sweep_file(const std::string& path);
/// The same for text in memory: `origin` names it in errors, `base_dir` resolves relative paths.
SweepFile parse_sweep(std::string_view text, const std::string& origin,
                      const std::filesystem::path& base_dir);

}  // namespace rtsim::sweep
