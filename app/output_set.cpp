#include "app/output_set.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <vector>

#include "app/interrupt_cleanup.hpp"
#include "common/input_error.hpp"

namespace rtsim::app {

namespace fs = std::filesystem;

namespace {
/// Names of files in the way that one --out message lists.
constexpr std::size_t kForeignNamesShown = 3;
}  // namespace

void check_output_folder(const fs::path& dir) {
  const std::string arg = "--out " + dir.string();
  std::error_code ec;
  if (dir.empty()) throw InputError(arg, 0, "the output folder is empty");
  const fs::path absolute = fs::weakly_canonical(fs::absolute(dir, ec), ec);
  if (!ec && absolute == absolute.root_path())
    throw InputError(arg, 0,
                     "refusing to write the run's files into the filesystem root; name a "
                     "folder for them");
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw InputError(arg, 0, "exists and is not a folder");
  if (!fs::is_directory(dir, ec)) return;
  // An existing folder must be the runs' own: empty, or holding only what rtsim writes.
  std::vector<std::string> foreign;
  std::size_t count = 0;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (is_rtsim_output_name(name)) continue;
    if (foreign.size() < kForeignNamesShown) foreign.push_back("'" + name + "'");
    ++count;
  }
  if (ec) throw InputError(arg, 0, "cannot read the output folder: " + ec.message());
  if (count > 0) {
    std::string names;
    for (const auto& n : foreign) names += (names.empty() ? "" : ", ") + n;
    if (count > foreign.size()) names += ", ... (" + std::to_string(count) + " in all)";
    throw InputError(arg, 0,
                     "the folder holds files rtsim did not write (" + names +
                         "); name a new or empty folder, or one an earlier run filled");
  }
}

bool is_rtsim_output_name(std::string_view name) {
  static constexpr std::array<std::string_view, 14> kNames = {
      "image.png", "image.exr",  "id.exr",        "depth.exr",        "stats.json",
      "trace.vcd", "trace.json", "report.html",   "results.csv",      "results.jsonl",
      "points",    "run.log",    ".report-plots", ".rtsim-sweep.lock"};
  if (std::find(kNames.begin(), kNames.end(), name) != kNames.end()) return true;
  // A staging folder (this run's or a killed one's), or a sweep table being written.
  return name.starts_with(".rtsim-partial-") || name.find(".partial-") != std::string_view::npos;
}

OutputSet::OutputSet(fs::path dir) : dir_(std::move(dir)) {
  // Every problem with the output folder is bad input (exit 2), found before any work.
  check_output_folder(dir_);
  const std::string arg = "--out " + dir_.string();
  std::error_code ec;
  if (!fs::exists(dir_, ec)) {
    fs::create_directories(dir_, ec);
    if (ec) throw InputError(arg, 0, "cannot create the output folder: " + ec.message());
    created_dir_ = true;
  }
  staging_ = dir_ / (".rtsim-partial-" + std::to_string(::getpid()));
  // Interrupted before commit(): the staging folder goes, and the output folder if this set made
  // it (newest first).
  if (created_dir_) interrupt_ids_.push_back(remove_on_interrupt(dir_));
  interrupt_ids_.push_back(remove_on_interrupt(staging_));
  fs::remove_all(staging_, ec);
  fs::create_directories(staging_, ec);
  if (ec) {
    forget_interrupt_paths();
    if (created_dir_) fs::remove(dir_, ec);
    throw InputError(arg, 0, "cannot write in the output folder: " + ec.message());
  }
}

void OutputSet::forget_interrupt_paths() {
  for (const std::uint64_t id : interrupt_ids_) forget_on_interrupt(id);
  interrupt_ids_.clear();
}

OutputSet::~OutputSet() {
  forget_interrupt_paths();
  std::error_code ec;
  fs::remove_all(staging_, ec);
  if (!committed_ && created_dir_ && fs::is_empty(dir_, ec)) fs::remove(dir_, ec);
}

fs::path OutputSet::stage(const std::string& name) {
  names_.push_back(name);
  return staging_ / name;
}

void OutputSet::commit() {
  // Every destination is checked before the first file moves: a run that cannot put one file in
  // place replaces none (a folder where stats.json should go, say).
  for (const auto& name : names_) {
    std::error_code ec;
    const fs::path to = dir_ / name;
    if (fs::exists(to, ec) && !fs::is_regular_file(to, ec))
      throw InputError("--out " + dir_.string(), 0,
                       to.string() + " exists and is not a file; nothing was replaced");
  }
  // From the first rename on, the files in DIR are the run's answer: an interrupt no longer
  // removes DIR (the staging folder, now emptying, still goes).
  if (created_dir_) forget_on_interrupt(interrupt_ids_.front());
  // An earlier run's outputs that this one does not write would read as this run's (a trace
  // from a run with --trace beside the stats of one without): they go.
  for (const std::string_view old : superseded_) {
    if (std::find(names_.begin(), names_.end(), old) != names_.end()) continue;
    std::error_code ec;
    if (fs::is_regular_file(dir_ / old, ec)) fs::remove(dir_ / old, ec);
  }
  for (const auto& name : names_) {
    std::error_code ec;
    fs::rename(staging_ / name, dir_ / name, ec);
    if (ec)
      throw std::runtime_error("cannot move " + name + " into " + dir_.string() + ": " +
                               ec.message());
  }
  committed_ = true;
}

}  // namespace rtsim::app
