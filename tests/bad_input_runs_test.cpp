// Issue 11's defects, each reproduced first: crashes, hangs and dishonest exit statuses on input
// a hostile user can give. Each test names the defect it guards.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using rtsim::test::read_file;
using rtsim::test::run_rtsim;
using rtsim::test::scratch_dir;

/// Runs `shell` (a /bin/sh command line) and returns its exit status and output.
rtsim::test::CommandResult run_shell(const std::string& shell) {
  rtsim::test::CommandResult r;
  FILE* pipe = ::popen((shell + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) r.output.append(buf, n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// Defect 1: when threads cannot be created (here: too little address space for their stacks),
// the render aborted with "terminate called without an active exception". It now renders with
// the threads it could start, says so, and the image is the one a single thread renders.
TEST(BadInputRuns, ThreadsTheSystemRefusesDoNotAbortTheRender) {
  const fs::path dir = scratch_dir("threads");
  const std::string args = "render --scene builtin:default --width 16 --height 16 -q --out ";
  const auto one = run_rtsim(args + (dir / "one").string() + " --threads 1");
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const auto many = run_shell("ulimit -v 1500000; " + std::string(RTSIM_BINARY) + " " + args +
                              (dir / "many").string() + " --threads 256");
  std::cout << many.output;
  ASSERT_EQ(many.exit_code, 0) << many.output;
  EXPECT_NE(many.output.find("would start only"), std::string::npos) << many.output;
  EXPECT_EQ(read_file(dir / "one" / "image.exr"), read_file(dir / "many" / "image.exr"));
  // More than the cap is a usage error.
  const auto capped = run_rtsim(args + (dir / "cap").string() + " --threads 1024");
  EXPECT_EQ(capped.exit_code, 2) << capped.output;
  fs::remove_all(dir);
}

// Defect 3: gaudet-pert on a scene whose primitives are all degenerate exited 1 with "internal
// error: the twin's tracer is not a shell search". It is bad input for the PERT (its data sets
// would be empty): exit 2 with the reason and no output; vax-750 renders the empty scene.
TEST(BadInputRuns, AllDegenerateScenesAreRejectedByThePertWithTheReason) {
  const fs::path dir = scratch_dir("degenerate");
  fs::create_directories(dir);
  const std::string head =
      "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 8 8\n"
      "l 1 1 1\nf 1 0 0 1 0 0 0 0\n";
  const std::string bodies[] = {"s 0 0 0 1e-300\n",
                                "p 3\n0 0 0\n1 0 0\n2 0 0\np 4\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n"};
  int k = 0;
  for (const auto& body : bodies) {
    const fs::path scene = dir / ("degenerate" + std::to_string(k++) + ".nff");
    { std::ofstream(scene) << head << body; }
    for (const char* command : {"run", "render"}) {
      const fs::path out = dir / "out";
      const auto r = run_rtsim(std::string(command) + " --machine gaudet-pert --scene " +
                               scene.string() + " -q --out " + out.string());
      EXPECT_EQ(r.exit_code, 2) << command << " " << scene << "\n" << r.output;
      EXPECT_NE(r.output.find("no primitive of this scene survives"), std::string::npos)
          << r.output;
      EXPECT_FALSE(fs::exists(out)) << "no output for bad input";
    }
    const auto vax = run_rtsim("run --machine vax-750 --scene " + scene.string() + " -q --out " +
                               (dir / "vax").string());
    EXPECT_EQ(vax.exit_code, 0) << vax.output;
  }
  fs::remove_all(dir);
}

}  // namespace
