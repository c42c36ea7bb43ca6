// `rtsim run --fault MEMORY:WORD:MASK` on every registered machine: a memory the machine does
// not have is bad input (exit 2) that names the memories it has, and writes nothing. Each
// machine's own data-path test (a word corrupted in flight changes its image) is in its test
// file (tests/data_path_support.hpp holds what they share).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/test_support.hpp"

namespace fs = std::filesystem;

namespace {

using rtsim::test::MachineInfo;

class DataPath : public ::testing::TestWithParam<MachineInfo> {};

TEST_P(DataPath, AFaultOnNoMemoryIsRefusedAndWritesNothing) {
  const MachineInfo& m = GetParam();
  const fs::path dir = rtsim::test::scratch_dir("fault-no-memory-" + m.name);
  fs::remove_all(dir);
  const auto r = rtsim::test::run_kit(
      "run --machine " + m.name + " " + m.small_run() +
      " --width 8 --height 8 -q --fault no_such.memory:0:0x1 --out " + dir.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no_such.memory"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir));
}

INSTANTIATE_TEST_SUITE_P(Machines, DataPath, ::testing::ValuesIn(rtsim::test::kit_machines()),
                         rtsim::test::machine_param_name);

}  // namespace
