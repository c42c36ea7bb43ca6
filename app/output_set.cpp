#include "app/output_set.hpp"

#include <unistd.h>

#include <stdexcept>
#include <system_error>

namespace rtsim::app {

namespace fs = std::filesystem;

OutputSet::OutputSet(fs::path dir) : dir_(std::move(dir)) {
  std::error_code ec;
  if (!fs::exists(dir_, ec)) {
    fs::create_directories(dir_, ec);
    if (ec)
      throw std::runtime_error("cannot create output folder " + dir_.string() + ": " +
                               ec.message());
    created_dir_ = true;
  } else if (!fs::is_directory(dir_, ec)) {
    throw std::runtime_error("output path " + dir_.string() + " exists and is not a folder");
  }
  staging_ = dir_ / (".rtsim-partial-" + std::to_string(::getpid()));
  fs::remove_all(staging_, ec);
  fs::create_directories(staging_, ec);
  if (ec) throw std::runtime_error("cannot write in " + dir_.string() + ": " + ec.message());
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
