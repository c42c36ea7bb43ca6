#pragma once
// A progress bar with an ETA on stderr, drawn only when stderr is a terminal.
#include <chrono>
#include <string>

namespace rtsim::app {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();
  /// Redraws at most ten times a second, and always at completion.
  void update(long done, long total);

 private:
  std::string label_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace rtsim::app
