// A parameter the chosen machine does not read is an error, not a silent no-op (issue 10 item 2):
//  * each machine declares exactly what it reads: after a whole run every declared parameter
//    has been read (ParamRegistry::unread() is empty), so "declared" can stand for "used";
//  * a name that another machine or the functional renderer reads, set from -p, a config file or
//    a sweep file, stops the run before anything is written: exit 2, "not used by", and the
//    closest names the machine does read.
// The machines are called directly, each simulation in a forked child (one per process); the
// test program has the kit's minimal machine too (tests/kit_machine/), which is covered with them.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/scene_input.hpp"
#include "platform/machine.hpp"
#include "platform/machine_registry.hpp"
#include "tests/machine_test_support.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using rtsim::test::run_rtsim;

namespace {

/// Runs `machine` on `scene` at 8x8 in a child; the child writes the parameters it declared but
/// never read, one per line, to `out`. Returns the child's exit code.
int unread_after_run(const std::string& machine_name, const std::string& scene_name,
                     const fs::path& out) {
  return rtsim::test::run_in_child([&] {
    auto m = rtsim::test::prepare_machine(machine_name, scene_name);
    rtsim::platform::RunOptions opts;
    opts.width = 8;
    opts.height = 8;
    (void)m->machine->run(m->scene, m->twin, m->registry, opts);
    std::ofstream f(out);
    for (const auto& name : m->registry.unread()) f << name << "\n";
    return f ? 0 : 4;
  });
}

TEST(UnusedParams, EveryMachineReadsEveryParameterItDeclares) {
  const fs::path dir = rtsim::test::scratch_dir("unread");
  fs::create_directories(dir);
  // A scene with lights, so the shading parameters are read too; polygons only, so every
  // machine holds it.
  for (const auto* machine : rtsim::platform::machines()) {
    const fs::path out = dir / (machine->name() + ".txt");
    ASSERT_EQ(unread_after_run(machine->name(), "builtin:ullner-cubes", out), 0) << machine->name();
    const std::string unread = rtsim::test::read_file(out);
    EXPECT_EQ(unread, "") << machine->name() << " declares parameters it never read:\n" << unread;
  }
  fs::remove_all(dir);
}

TEST(UnusedParams, DeclaredSetsDiffer) {
  // The check above is not vacuous: a name one machine reads is missing from another's set
  // (render.grid.divisions: the twins that choose their search structure read it; those with a
  // structure of their own do not declare it).
  std::size_t with = 0, without = 0;
  for (const auto* machine : rtsim::platform::machines()) {
    rtsim::params::ParamRegistry r;
    rtsim::platform::declare_params_of(machine, r);
    ++(r.contains("render.grid.divisions") ? with : without);
  }
  EXPECT_GT(with, 0u);
  EXPECT_GT(without, 0u);
}

TEST(UnusedParams, CommandLineOverrideStopsTheRun) {
  const fs::path out = rtsim::test::scratch_dir("unused-p");
  const auto r = run_rtsim(
      "run --machine ullner-peripheral --scene builtin:ullner-cubes --width 8 --height 8 -q "
      "-p render.grid.divisions=11 --out " +
      out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("'render.grid.divisions' is not used by ullner-peripheral"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("did you mean 'peripheral.grid.divisions'?"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out)) << "a rejected run wrote " << out;
}

TEST(UnusedParams, ConfigFileNamesFileAndLine) {
  const fs::path dir = rtsim::test::scratch_dir("unused-config");
  fs::create_directories(dir);
  {
    std::ofstream f(dir / "grid.toml");
    f << "# meant for the peripheral\n[render.grid]\ndivisions = 11\n";
  }
  const auto r = run_rtsim(
      "run --machine ullner-peripheral --scene builtin:ullner-cubes -q "
      "--config " +
      (dir / "grid.toml").string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("grid.toml:3"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("is not used by ullner-peripheral"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

TEST(UnusedParams, SweepFileIsRejectedBeforeAnyPoint) {
  const fs::path dir = rtsim::test::scratch_dir("unused-sweep");
  fs::create_directories(dir);
  {
    std::ofstream f(dir / "s.toml");
    f << "machine = \"ullner-peripheral\"\nscene = \"builtin:ullner-cubes\"\n"
         "[[axes]]\nparam = \"render.grid.divisions\"\nvalues = [4, 8]\n";
  }
  const auto r = run_rtsim("sweep " + (dir / "s.toml").string() + " --list");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("'render.grid.divisions' is not used by ullner-peripheral"),
            std::string::npos)
      << r.output;
  fs::remove_all(dir);
}

TEST(UnusedParams, FunctionalRendererHasNoQuantum) {
  const fs::path out = rtsim::test::scratch_dir("unused-render");
  const auto r = run_rtsim(
      "render --scene builtin:ullner-cubes --width 8 --height 8 -q "
      "-p 'quantum=1 us' --out " +
      out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("'quantum' is not used by the functional renderer"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST(UnusedParams, AMisspeltNameIsStillUnknown) {
  const auto r = run_rtsim("list params --machine ullner-peripheral -p peripheral.grid.divsions=3");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("unknown parameter 'peripheral.grid.divsions'"), std::string::npos)
      << r.output;
}

}  // namespace
