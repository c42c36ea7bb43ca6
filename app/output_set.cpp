#include "app/output_set.hpp"

#include <unistd.h>

#include <stdexcept>
#include <system_error>

#include "common/input_error.hpp"

namespace rtsim::app {

namespace fs = std::filesystem;

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
  fs::remove_all(staging_, ec);
  fs::create_directories(staging_, ec);
  if (ec) {
    if (created_dir_) fs::remove(dir_, ec);
    throw InputError(arg, 0, "cannot write in the output folder: " + ec.message());
  }
}

OutputSet::~OutputSet() {
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
