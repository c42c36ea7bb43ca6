// libFuzzer target: sweep files (platform/sweep/sweep_file.hpp) through what `rtsim sweep` does
// with one before any point runs: parse_sweep, then for sweeps of a few points expand_points and
// check_sweep against the machines' registries (without loading scenes). docs/fuzzing.md.
//
// Bad input may only be refused with rtsim::InputError. Any other exception, a crash, a sanitizer
// report, a leak or a timeout is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "common/input_error.hpp"
#include "platform/sweep/sweep_check.hpp"
#include "platform/sweep/sweep_file.hpp"
#include "platform/sweep/sweep_points.hpp"

namespace {

/// Relative paths in the file (configs, scenes) resolve here: a folder that does not exist, so
/// a run reads no file. (An absolute `configs` path is only looked up, and then check_sweep is
/// skipped.)
constexpr const char* kBaseDir = "/nonexistent/rtsim-fuzz";

/// Larger sweeps are parsed and counted only: expanding and checking 100000 points is slow
/// without finding more.
constexpr std::size_t kMaxExpandedPoints = 1000;

[[noreturn]] void sweep_defect(const char* what) {
  std::fprintf(stderr, "fuzz: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace sweep = rtsim::sweep;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const sweep::SweepFile file = sweep::parse_sweep(text, "fuzz-sweep.toml", kBaseDir);
    const std::size_t n = file.point_count();
    if (n == 0 || n > sweep::kMaxPoints)
      sweep_defect("a sweep was accepted with 0 or too many points");
    if (n > kMaxExpandedPoints) return 0;
    const std::vector<sweep::Point> points = sweep::expand_points(file);
    if (points.size() != n) sweep_defect("expand_points gave another count than point_count()");
    if (!file.configs.empty()) return 0;  // check_sweep would read those files
    sweep::check_sweep(file, points, {.load_scenes = false});
  } catch (const rtsim::InputError&) {
    // Refused with a message naming file and line: the expected outcome for bad input.
  }
  return 0;
}
