#pragma once
// A progress bar with an ETA on stderr, drawn only when stderr is a terminal. On request, when
// stderr is not a terminal (a batch job, mpirun's forwarded output), a plain progress line
// every kLineInterval instead.
#include <chrono>
#include <string>

namespace rtsim::app {

class ProgressBar {
 public:
  /// An empty label draws nothing.
  explicit ProgressBar(std::string label, bool lines_when_not_a_terminal = false);
  ~ProgressBar();
  /// Redraws at most ten times a second, and always at completion.
  void update(long done, long total);
  /// What the command does after the counted work (a terminal's bar says it, in place of the
  /// ETA: "writing outputs"), so a full bar does not sit silent.
  void phase(const std::string& what);
  /// Prints `line` on stderr on a line of its own (over the bar, which the next update redraws
  /// below it), whether or not the bar is drawn.
  void note(const std::string& line);
  /// Ends the bar's line, so what is printed next starts on a line of its own; draws nothing
  /// after. The destructor calls it.
  void finish();

  /// Time between two progress lines when stderr is not a terminal.
  static constexpr std::chrono::seconds kLineInterval{10};

 private:
  std::string label_;
  bool enabled_;
  bool lines_ = false;  ///< plain lines, not a redrawn bar
  bool drawn_ = false;
  bool in_phase_ = false;  ///< phase() drew last
  long done_ = 0, total_ = 0;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace rtsim::app
