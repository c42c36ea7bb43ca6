#pragma once
// Helpers shared by the end-to-end tests: run the real `rtsim` binary, read files, compare
// images with OpenImageIO.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rtsim::test {

struct CommandResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// Run the rtsim binary with `args` (shell-quoted by the caller where needed).
inline CommandResult run_rtsim(const std::string& args) {
  const std::string cmd = std::string(RTSIM_BINARY) + " " + args + " 2>&1";
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

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline std::string shared_path(const std::string& rel) {
  return std::string(RTSIM_SHARED_DIR) + "/" + rel;
}

/// A fresh, empty folder under the build tree for one test's outputs.
/// The process id keeps tests that CTest runs in parallel out of each other's way.
inline std::filesystem::path scratch_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() /
             ("rtsim-test-" + std::to_string(::getpid()) + "-" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

/// OpenImageIO's comparison of two images; fails if either cannot be read.
inline OIIO::ImageBufAlgo::CompareResults compare_images(const std::string& a,
                                                         const std::string& b,
                                                         float fail_threshold) {
  OIIO::ImageBuf A(a), B(b);
  OIIO::ImageBufAlgo::CompareResults cr;
  cr.error = true;
  if (!A.read() || !B.read()) return cr;
  return OIIO::ImageBufAlgo::compare(A, B, fail_threshold, fail_threshold);
}

}  // namespace rtsim::test
