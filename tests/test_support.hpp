#pragma once
// Helpers shared by the end-to-end tests: run the real `rtsim` binary, read files, compare
// images with OpenImageIO.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imagecache.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace rtsim::test {

struct CommandResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// Run `command` through /bin/sh, stdout and stderr together.
inline CommandResult run_shell(const std::string& command) {
  const std::string cmd = command + " 2>&1";
  CommandResult r;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// Run the rtsim binary with `args` (shell-quoted by the caller where needed).
inline CommandResult run_rtsim(const std::string& args) {
  return run_shell(std::string(RTSIM_BINARY) + " " + args);
}

/// Run `rtsim-kit`, the rtsim program with the kit's minimal machine registered beside the
/// others (tests/kit_machine/): what the generic tests run every machine with.
inline CommandResult run_kit(const std::string& args) {
  return run_shell(std::string(RTSIM_KIT_BINARY) + " " + args);
}

/// A machine as `rtsim list machines --format json` gives it (its registration).
struct MachineInfo {
  std::string name;
  std::string sample_scene;  ///< the machine's own (`rtsim describe` builds it on this)
  /// Scene and parameters of the runs the generic tests make (no size); the first is the small
  /// run every generic test uses.
  std::vector<std::string> test_runs;
  /// It takes --sample (a machine that does not refuses it, saying why).
  bool samples = true;
  /// The first test run: `--scene SCENE -p ...`.
  const std::string& small_run() const { return test_runs.front(); }
};

/// gtest's name for a parameter in its output: the machine's.
inline void PrintTo(const MachineInfo& m, std::ostream* os) { *os << m.name; }

/// The machines `program` (RTSIM_BINARY or RTSIM_KIT_BINARY) registers, so a test covers a new
/// machine with no edit. A machine with no test run is given its sample scene.
inline std::vector<MachineInfo> machines_of(const std::string& program) {
  const auto r = run_shell(program + " list machines --format json");
  std::vector<MachineInfo> out;
  for (const auto& m : nlohmann::json::parse(r.output, nullptr, false)) {
    MachineInfo info{m.value("name", std::string()), m.value("sample_scene", std::string()),
                     m.value("test_runs", std::vector<std::string>()), m.value("samples", true)};
    if (info.test_runs.empty()) info.test_runs.push_back("--scene " + info.sample_scene);
    out.push_back(std::move(info));
  }
  return out;
}

/// Every machine the rtsim program registers.
inline std::vector<MachineInfo> registered_machines() { return machines_of(RTSIM_BINARY); }

/// Every machine rtsim-kit registers: rtsim's and the minimal machine. The generic tests
/// (describe, trace agreement, processor accounts, quantum, sampled simulation, unused
/// parameters) are instantiated over these.
inline std::vector<MachineInfo> kit_machines() { return machines_of(RTSIM_KIT_BINARY); }

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// A JSON file (stats.json, validation.json), keys in file order.
inline nlohmann::ordered_json read_json(const std::filesystem::path& p) {
  return nlohmann::ordered_json::parse(read_file(p));
}

/// A JSON-lines file (a sweep's results.jsonl): one object per non-empty line.
/// Calls `f(path, value)` for every number of a stats.json document, by its dotted path
/// ("modules.host.busy_s"; an array's numbers under the array's path), but those of the run's
/// parameters and units (top-level `params` and `units`, which hold text).
template <class Json, class F>
void each_number(const Json& j, const F& f, const std::string& path = "") {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items())
      if (!(path.empty() && (k == "params" || k == "units")))
        each_number(v, f, path.empty() ? k : path + "." + k);
  } else if (j.is_array()) {
    for (const auto& v : j) each_number(v, f, path);
  } else if (j.is_number()) {
    f(path, j.template get<double>());
  }
}

inline std::vector<nlohmann::ordered_json> read_jsonl(const std::filesystem::path& p) {
  std::vector<nlohmann::ordered_json> rows;
  std::istringstream in(read_file(p));
  std::string line;
  while (std::getline(in, line))
    if (!line.empty()) rows.push_back(nlohmann::ordered_json::parse(line));
  return rows;
}

inline std::string shared_path(const std::string& rel) {
  return std::string(RTSIM_SHARED_DIR) + "/" + rel;
}

/// A name (a machine's, a scene's) as a GoogleTest parameter name: "npp-412" -> "npp_412".
inline std::string gtest_param_name(std::string name) {
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

/// A GoogleTest parameter name for a machine.
inline std::string machine_param_name(const testing::TestParamInfo<MachineInfo>& i) {
  return gtest_param_name(i.param.name);
}

/// A fresh, empty folder under the build tree for one test's outputs.
/// The process id keeps tests that CTest runs in parallel out of each other's way.
inline std::filesystem::path scratch_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() /
             ("rtsim-test-" + std::to_string(::getpid()) + "-" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

/// `rtsim ARGS -q` into a scratch folder named after `tag`: the folder, and a failed expectation
/// if the run did not exit 0.
inline std::filesystem::path run_ok(const std::string& tag, const std::string& args) {
  const auto dir = scratch_dir(tag);
  const auto r = run_rtsim(args + " -q --out " + dir.string());
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.output;
  return dir;
}

/// `rtsim-kit run --machine MACHINE ARGS -q` (any machine of rtsim, or the minimal one) into a
/// scratch folder named after `tag`: its stats.json
/// with "image_png" (the image's path) added; an empty object, and a failed expectation, if the
/// run did not exit 0.
inline nlohmann::ordered_json run_machine(const std::string& machine, const std::string& tag,
                                          const std::string& args) {
  const auto dir = scratch_dir(machine + "-" + tag);
  const auto r = run_kit("run --machine " + machine + " " + args + " -q --out " + dir.string());
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.output;
  if (r.exit_code != 0) return {};
  auto stats = read_json(dir / "stats.json");
  stats["image_png"] = (dir / "image.png").string();
  return stats;
}

/// An ImageBuf made from a file name reads it through OpenImageIO's shared ImageCache, which
/// keeps a file it has seen and re-reads it only when its modification time changed: a test that
/// writes the same path twice within one second (a scratch folder reused in a loop) would get the
/// first image again. Call this before reading a path that may have been rewritten.
inline void forget_cached_image(const std::string& path) {
  OIIO::ImageCache::create(/*shared=*/true)->invalidate(OIIO::ustring(path), /*force=*/true);
}

/// OpenImageIO's comparison of two images; fails if either cannot be read.
inline OIIO::ImageBufAlgo::CompareResults compare_images(const std::string& a, const std::string& b,
                                                         float fail_threshold) {
  forget_cached_image(a);
  forget_cached_image(b);
  OIIO::ImageBuf A(a), B(b);
  OIIO::ImageBufAlgo::CompareResults cr;
  cr.error = true;
  if (!A.read() || !B.read()) return cr;
  return OIIO::ImageBufAlgo::compare(A, B, fail_threshold, fail_threshold);
}

}  // namespace rtsim::test
