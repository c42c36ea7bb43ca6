#pragma once
// A set of output files that appears all at once or not at all (DESIGN.md "Outputs": files are
// written to a temporary name and renamed, so a failed run leaves no half-written output).
// Files are staged in DIR/.rtsim-partial-PID/ and renamed into DIR by commit(); without a
// commit the destructor removes the staging folder, and DIR itself if this set created it; so
// does Ctrl-C or SIGTERM (app/interrupt_cleanup.hpp).
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rtsim::app {

/// The checks `render`, `run` and `sweep` make of their --out before any work: not empty, not the
/// filesystem root, not an existing non-folder, and an existing folder holds nothing but what
/// rtsim writes (is_rtsim_output_name). InputError ("--out DIR: why", exit 2) otherwise.
void check_output_folder(const std::filesystem::path& dir);

/// A file or folder name that `render`, `run` or `sweep` writes into its --out folder.
bool is_rtsim_output_name(std::string_view name);

class OutputSet {
 public:
  /// Who else may keep files in DIR: `render`, `run` and `sweep` own their folder (it may hold
  /// only what rtsim writes: check_output_folder); `describe` writes MACHINE.dot and .svg into
  /// any folder the user names (docs/, say), so other files there are left alone.
  enum class Folder : std::uint8_t { RunsOwn, Shared };
  explicit OutputSet(std::filesystem::path dir, Folder folder = Folder::RunsOwn);
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// Where to write the file `name` now; it becomes DIR/name on commit(). Staging a name twice
  /// gives the same path (one file, moved once).
  std::filesystem::path stage(const std::string& name);
  /// Where a file staged as `name` is before commit() (for readers of staged files, such as
  /// the report); also a place for scratch files that must not be committed.
  std::filesystem::path staged_path(const std::string& name) const { return staging_ / name; }
  /// The files of a single frame's outputs (image, AOVs, stats, traces, report): what a run
  /// or a render writes, any of which an earlier one in the same folder may have written.
  static constexpr std::string_view kFrameOutputs[] = {"image.png",  "image.exr",   "id.exr",
                                                       "depth.exr",  "stats.json",  "trace.vcd",
                                                       "trace.json", "report.html", "drawing.svg"};
  /// On commit(), the files of `names` that this set did not stage are removed from DIR: they
  /// are an earlier run's, and would otherwise sit beside this run's outputs as if its own.
  void supersede(std::span<const std::string_view> names) {
    superseded_.assign(names.begin(), names.end());
  }
  /// Move every staged file into place, all or none: the files it replaces (and those it
  /// supersedes) are first moved aside into the staging folder, then the new ones in; if any
  /// move fails (an immutable or undeletable file, say), what was moved is moved back and an
  /// InputError names the file ("--out DIR", exit 2). The files moved aside are removed last.
  void commit();
  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
  std::filesystem::path staging_;
  std::vector<std::string> names_;
  std::vector<std::string_view> superseded_;
  /// The outermost folder this set created (DIR or an ancestor of it, `--out a/b/c` in an empty
  /// place creates a); empty when DIR existed. Without a commit, it goes again.
  std::filesystem::path created_root_;
  bool committed_ = false;
  std::vector<std::uint64_t> interrupt_ids_;  ///< app/interrupt_cleanup.hpp registrations
  void forget_interrupt_paths();
  /// Removes DIR and the ancestors up to created_root_ that this set created, if empty.
  void remove_created_folders();
};

}  // namespace rtsim::app
