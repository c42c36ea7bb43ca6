#pragma once
// A table of hostile inputs: each row is the arguments of one rtsim command (passed without a
// shell), the exit statuses allowed (0: it ran; 2: refused as bad input; never 1, a signal or a
// hang), and what must or must not be on disk afterwards. The generic rows are
// hostile_input_test.cpp's; a machine's own rows (its parameters, its memories) are in its test
// file, run by the same runner.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "tests/limited_run.hpp"
#include "tests/test_support.hpp"

namespace rtsim::test {

struct HostileCase {
  std::string name;
  std::vector<std::string> args;
  std::vector<int> allowed;
  /// After the run, in the table's folder: "" if all is well, else what is wrong.
  std::function<std::string(const std::filesystem::path&, const LimitedRun&)> check = nullptr;
};

inline std::string present(const std::filesystem::path& p) {
  return std::filesystem::exists(p) ? "" : p.string() + " is missing";
}
inline std::string absent(const std::filesystem::path& p) {
  return std::filesystem::exists(p) ? p.string() + " exists" : "";
}
inline std::string says(const LimitedRun& r, const std::string& text) {
  return r.output.find(text) != std::string::npos ? "" : "output lacks '" + text + "'";
}

/// `rtsim run` of `machine` on `scene` at 8 x 8, quietly, into out/MACHINE, then `more`.
inline std::vector<std::string> hostile_run(const std::string& machine, const std::string& scene,
                                            const std::vector<std::string>& more = {}) {
  std::vector<std::string> a = {"run", "--machine", machine, "--scene", scene,   "--width",
                                "8",   "--height",  "8",     "-q",      "--out", "out/" + machine};
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

/// Runs every row in `dir` (made empty first; `prepare` writes the inputs the rows use), each
/// within `timeout_s`, an 8 GiB address space and 2 GiB of resident memory, and expects each
/// to exit as it allows and pass its check.
inline void run_hostile_table(const std::filesystem::path& dir,
                              const std::vector<HostileCase>& table,
                              const std::function<void(const std::filesystem::path&)>& prepare = {},
                              double timeout_s = 60.0) {
  constexpr std::uint64_t kAddressSpace = std::uint64_t{8} << 30;
  constexpr long kMaxRssKib = 2L << 20;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  if (prepare) prepare(dir);
  std::size_t failures = 0;
  for (const HostileCase& c : table) {
    const LimitedRun r = run_limited(c.args, dir, timeout_s, kAddressSpace);
    const bool status_ok =
        std::find(c.allowed.begin(), c.allowed.end(), r.exit_code) != c.allowed.end();
    std::string problem = status_ok ? "" : "status " + r.status();
    if (problem.empty() && r.max_rss_kib >= kMaxRssKib)
      problem = "peak memory " + std::to_string(r.max_rss_kib / 1024) + " MiB";
    if (problem.empty() && c.check) problem = c.check(dir, r);
    if (!problem.empty()) ++failures;
    EXPECT_TRUE(problem.empty()) << c.name << ": " << problem << "\n" << r.output;
  }
  std::printf("%zu rows, %zu failed\n", table.size(), failures);
  std::filesystem::remove_all(dir);
}

}  // namespace rtsim::test
