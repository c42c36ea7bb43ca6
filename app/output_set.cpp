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

namespace {

/// The checks of any --out: a path that is or can become a folder of the user's, not the root.
void check_output_path(const fs::path& dir) {
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
}

/// The outermost folder of `dir` that does not exist yet (dir itself, or an ancestor).
fs::path first_missing(const fs::path& dir) {
  std::error_code ec;
  fs::path missing;
  for (fs::path p = fs::absolute(dir, ec); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    missing = p;
    if (p == p.parent_path()) break;
  }
  return missing;
}

}  // namespace

void check_output_folder(const fs::path& dir) {
  check_output_path(dir);
  const std::string arg = "--out " + dir.string();
  std::error_code ec;
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
  static constexpr std::array<std::string_view, 15> kNames = {
      "image.png",     "image.exr", "id.exr",     "depth.exr",     "stats.json",
      "drawing.svg",   "trace.vcd", "trace.json", "report.html",   "results.csv",
      "results.jsonl", "points",    "run.log",    ".report-plots", ".rtsim-sweep.lock"};
  if (std::find(kNames.begin(), kNames.end(), name) != kNames.end()) return true;
  // A staging folder (this run's or a killed one's), or a sweep table being written.
  return name.starts_with(".rtsim-partial-") || name.find(".partial-") != std::string_view::npos;
}

OutputSet::OutputSet(fs::path dir, Folder folder) : dir_(std::move(dir)) {
  // Every problem with the output folder is bad input (exit 2), found before any work.
  if (folder == Folder::RunsOwn)
    check_output_folder(dir_);
  else
    check_output_path(dir_);
  const std::string arg = "--out " + dir_.string();
  std::error_code ec;
  // Each folder is made and registered for removal on an interrupt in one step (see
  // make_and_remove_on_interrupt): an interrupt at any moment leaves neither behind.
  if (!fs::exists(dir_, ec)) {
    created_root_ = first_missing(dir_);
    interrupt_ids_.push_back(
        make_and_remove_on_interrupt(created_root_, [&] { fs::create_directories(dir_, ec); }));
    if (ec) {
      forget_interrupt_paths();
      remove_created_folders();
      throw InputError(arg, 0, "cannot create the output folder: " + ec.message());
    }
  }
  staging_ = dir_ / (".rtsim-partial-" + std::to_string(::getpid()));
  interrupt_ids_.push_back(make_and_remove_on_interrupt(staging_, [&] {
    fs::remove_all(staging_, ec);
    fs::create_directories(staging_, ec);
  }));
  if (ec) {
    forget_interrupt_paths();
    remove_created_folders();
    throw InputError(arg, 0, "cannot write in the output folder: " + ec.message());
  }
}

void OutputSet::forget_interrupt_paths() {
  for (const std::uint64_t id : interrupt_ids_) forget_on_interrupt(id);
  interrupt_ids_.clear();
}

void OutputSet::remove_created_folders() {
  if (created_root_.empty()) return;
  std::error_code ec;
  const fs::path root = created_root_.lexically_normal();
  for (fs::path p = fs::absolute(dir_, ec).lexically_normal();; p = p.parent_path()) {
    if (!fs::is_directory(p, ec) || !fs::is_empty(p, ec) || !fs::remove(p, ec)) break;
    if (p == root || p == p.parent_path()) break;
  }
}

OutputSet::~OutputSet() {
  // Removed before they are forgotten: an interrupt in between still finds them registered.
  std::error_code ec;
  fs::remove_all(staging_, ec);
  if (!committed_) remove_created_folders();
  forget_interrupt_paths();
}

fs::path OutputSet::stage(const std::string& name) {
  if (std::find(names_.begin(), names_.end(), name) == names_.end()) names_.push_back(name);
  return staging_ / name;
}

namespace {

/// A staged file's name in the staging folder while the file it replaces waits there.
std::string aside_name(std::string_view name) { return ".replaced-" + std::string(name); }

}  // namespace

void OutputSet::commit() {
  const std::string arg = "--out " + dir_.string();
  // Every destination is checked before the first file moves: a run that cannot put one file in
  // place replaces none (a folder where stats.json should go, say).
  for (const auto& name : names_) {
    std::error_code ec;
    const fs::path to = dir_ / name;
    if (fs::exists(to, ec) && !fs::is_regular_file(to, ec))
      throw InputError(arg, 0, to.string() + " exists and is not a file; nothing was replaced");
    if (!fs::is_regular_file(staging_ / name, ec))
      throw std::logic_error("output " + name + " was staged but never written");
  }
  // What goes away: the files this set replaces, and an earlier run's outputs that this one does
  // not write (a trace from a run with --trace beside the stats of one without).
  std::vector<std::string> old = names_;
  for (const std::string_view s : superseded_)
    if (std::find(names_.begin(), names_.end(), s) == names_.end()) old.emplace_back(s);
  // Moves are undone newest first if one fails.
  std::vector<std::pair<fs::path, fs::path>> done;  // from, to
  const auto undo = [&done] {
    std::error_code ec;
    for (auto it = done.rbegin(); it != done.rend(); ++it) fs::rename(it->second, it->first, ec);
  };
  const auto move = [&](const fs::path& from, const fs::path& to, const std::string& name) {
    std::error_code ec;
    fs::rename(from, to, ec);
    if (!ec) {
      done.emplace_back(from, to);
      return;
    }
    undo();
    throw InputError(arg, 0,
                     "cannot replace " + name + " in " + dir_.string() + ": " + ec.message() +
                         "; nothing was replaced");
  };
  for (const auto& name : old) {
    std::error_code ec;
    if (fs::is_regular_file(dir_ / name, ec)) move(dir_ / name, staging_ / aside_name(name), name);
  }
  for (const auto& name : names_) move(staging_ / name, dir_ / name, name);
  // From here the files in DIR are the run's answer: an interrupt no longer removes DIR (the
  // staging folder, with the files moved aside, still goes).
  if (!created_root_.empty()) forget_on_interrupt(interrupt_ids_.front());
  committed_ = true;
}

}  // namespace rtsim::app
