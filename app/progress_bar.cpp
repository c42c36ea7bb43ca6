#include "app/progress_bar.hpp"

#include <unistd.h>

#include <cstdio>
#include <string>

namespace rtsim::app {
namespace {

/// The bar itself, `frac` of it filled.
std::string bar_text(double frac) {
  constexpr int kWidth = 30;
  std::string bar(static_cast<std::size_t>(frac * kWidth), '=');
  bar.resize(kWidth, ' ');
  return bar;
}

}  // namespace

ProgressBar::ProgressBar(std::string label, bool lines_when_not_a_terminal)
    : label_(std::move(label)),
      enabled_(::isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {
  if (!enabled_ && lines_when_not_a_terminal) enabled_ = lines_ = true;
  if (label_.empty()) enabled_ = false;
}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::note(const std::string& line) {
  // "\033[K": clear what the bar drew on the line.
  std::fprintf(stderr, "%s%s\n", drawn_ && !lines_ ? "\r\033[K" : "", line.c_str());
  std::fflush(stderr);
  in_phase_ = false;
}

void ProgressBar::finish() {
  if (drawn_ && !lines_) std::fputs(in_phase_ ? " done\n" : "\n", stderr);
  std::fflush(stderr);
  drawn_ = false;
  enabled_ = false;
}

void ProgressBar::phase(const std::string& what) {
  if (!enabled_ || lines_ || !drawn_ || total_ <= 0) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double frac = static_cast<double>(done_) / static_cast<double>(total_);
  // "\033[K": clear the rest of the line (the ETA it replaces).
  std::fprintf(stderr, "\r%s [%s] %3d%%  %ld/%ld  elapsed %.1fs  %s ...\033[K", label_.c_str(),
               bar_text(frac).c_str(), static_cast<int>(frac * 100.0), done_, total_, elapsed,
               what.c_str());
  std::fflush(stderr);
  in_phase_ = true;
}

void ProgressBar::update(long done, long total) {
  if (!enabled_ || total <= 0) return;
  done_ = done;
  total_ = total;
  const auto now = std::chrono::steady_clock::now();
  const double frac = static_cast<double>(done) / static_cast<double>(total);
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double eta = done > 0 ? elapsed * (1.0 - frac) / frac : 0.0;
  if (lines_) {
    // A line every kLineInterval; the last one only if earlier ones were printed.
    if (now - last_ < kLineInterval && !(done == total && drawn_)) return;
    last_ = now;
    drawn_ = true;
    std::fprintf(stderr, "%s: %ld/%ld (%d%%)  elapsed %.0fs  ETA %.0fs\n", label_.c_str(), done,
                 total, static_cast<int>(frac * 100.0), elapsed, eta);
    std::fflush(stderr);
    return;
  }
  if (done < total && drawn_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  drawn_ = true;
  std::fprintf(stderr, "\r%s [%s] %3d%%  %ld/%ld  elapsed %.1fs  ETA %.1fs ", label_.c_str(),
               bar_text(frac).c_str(), static_cast<int>(frac * 100.0), done, total, elapsed, eta);
  std::fflush(stderr);
}

}  // namespace rtsim::app
