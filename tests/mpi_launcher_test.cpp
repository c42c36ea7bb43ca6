// What a launcher's environment says before MPI_Init (app/mpi_launcher.hpp): the rank, and
// whether every rank is on this host, for OpenMPI, MPICH's Hydra and Slurm; anything unclear
// (several hosts, a value that is not a count, a rank past the size) says "start MPI".
#include "app/mpi_launcher.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>

using rtsim::app::launcher_rank;
using rtsim::app::one_host_ranks;

namespace {

/// An environment of exactly these variables.
rtsim::app::EnvLookup env_of(const std::map<std::string, std::string>& vars) {
  return [vars](const char* name) -> const char* {
    const auto it = vars.find(name);
    return it == vars.end() ? nullptr : it->second.c_str();
  };
}

}  // namespace

TEST(MpiLauncher, OpenMpiRanksOnOneHost) {
  const auto host = one_host_ranks(env_of({{"OMPI_COMM_WORLD_RANK", "1"},
                                           {"OMPI_COMM_WORLD_SIZE", "4"},
                                           {"OMPI_COMM_WORLD_LOCAL_SIZE", "4"}}));
  ASSERT_TRUE(host);
  EXPECT_EQ(host->rank, 1);
  EXPECT_EQ(host->size, 4);
  // Two of the four elsewhere: MPI.
  EXPECT_FALSE(one_host_ranks(env_of({{"OMPI_COMM_WORLD_RANK", "1"},
                                      {"OMPI_COMM_WORLD_SIZE", "4"},
                                      {"OMPI_COMM_WORLD_LOCAL_SIZE", "2"}})));
}

TEST(MpiLauncher, MpichAndSlurm) {
  const auto hydra =
      one_host_ranks(env_of({{"PMI_RANK", "0"}, {"PMI_SIZE", "3"}, {"MPI_LOCALNRANKS", "3"}}));
  ASSERT_TRUE(hydra);
  EXPECT_EQ(hydra->size, 3);
  EXPECT_FALSE(
      one_host_ranks(env_of({{"PMI_RANK", "0"}, {"PMI_SIZE", "3"}, {"MPI_LOCALNRANKS", "1"}})));
  const auto slurm = one_host_ranks(env_of(
      {{"SLURM_PROCID", "5"}, {"SLURM_STEP_NUM_TASKS", "8"}, {"SLURM_STEP_NUM_NODES", "1"}}));
  ASSERT_TRUE(slurm);
  EXPECT_EQ(slurm->rank, 5);
  EXPECT_EQ(slurm->size, 8);
  EXPECT_FALSE(one_host_ranks(env_of(
      {{"SLURM_PROCID", "5"}, {"SLURM_STEP_NUM_TASKS", "8"}, {"SLURM_STEP_NUM_NODES", "2"}})));
}

TEST(MpiLauncher, AnythingUnclearStartsMpi) {
  EXPECT_FALSE(one_host_ranks(env_of({})));
  for (const char* bad : {"", "two", "2x", "-1", "99999999999"})
    EXPECT_FALSE(one_host_ranks(env_of({{"OMPI_COMM_WORLD_RANK", "0"},
                                        {"OMPI_COMM_WORLD_SIZE", bad},
                                        {"OMPI_COMM_WORLD_LOCAL_SIZE", bad}})))
        << bad;
  // A rank past the size, a launch of no ranks, a size without the local count.
  EXPECT_FALSE(one_host_ranks(env_of({{"OMPI_COMM_WORLD_RANK", "2"},
                                      {"OMPI_COMM_WORLD_SIZE", "2"},
                                      {"OMPI_COMM_WORLD_LOCAL_SIZE", "2"}})));
  EXPECT_FALSE(one_host_ranks(env_of({{"OMPI_COMM_WORLD_RANK", "0"},
                                      {"OMPI_COMM_WORLD_SIZE", "0"},
                                      {"OMPI_COMM_WORLD_LOCAL_SIZE", "0"}})));
  EXPECT_FALSE(
      one_host_ranks(env_of({{"OMPI_COMM_WORLD_RANK", "0"}, {"OMPI_COMM_WORLD_SIZE", "2"}})));
}

TEST(MpiLauncher, LocalJobsStandForEveryRanksSlotsWithinBounds) {
  EXPECT_EQ(rtsim::app::one_host_jobs({0, 2}, 1), 2);
  EXPECT_EQ(rtsim::app::one_host_jobs({0, 4}, 3), 12);
  // A launcher that claims two billion ranks gets a bound, not an overflow.
  EXPECT_EQ(rtsim::app::one_host_jobs({0, 2'000'000'000}, 1024), 65536);
}

TEST(MpiLauncher, RankFromTheFirstLauncherVariableSet) {
  EXPECT_EQ(launcher_rank(env_of({})), -1);
  EXPECT_EQ(launcher_rank(env_of({{"PMIX_RANK", "3"}})), 3);
  EXPECT_EQ(launcher_rank(env_of({{"OMPI_COMM_WORLD_RANK", "1"}, {"SLURM_PROCID", "7"}})), 1);
  EXPECT_EQ(launcher_rank(env_of({{"PMI_RANK", "x"}, {"SLURM_PROCID", "2"}})), 2);
}
