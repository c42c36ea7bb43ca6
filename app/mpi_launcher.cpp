#include "app/mpi_launcher.hpp"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdlib>

namespace rtsim::app {

namespace {

/// A non-negative decimal count, whole; nothing if unset or not one.
std::optional<int> count_of(const EnvLookup& env, const char* name) {
  const char* value = env(name);
  if (!value || !*value) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const long n = std::strtol(value, &end, 10);
  if (*end != '\0' || errno != 0 || n < 0 || n > INT_MAX) return std::nullopt;
  return static_cast<int>(n);
}

/// One launcher's answer: its rank, its size, and the ranks on this host (or the hosts).
std::optional<OneHostRanks> one_host(const EnvLookup& env, const char* rank_name,
                                     const char* size_name, const char* local_size_name) {
  const auto rank = count_of(env, rank_name);
  const auto size = count_of(env, size_name);
  const auto local = count_of(env, local_size_name);
  if (!rank || !size || !local || *size < 1 || *rank >= *size || *local != *size)
    return std::nullopt;
  return OneHostRanks{*rank, *size};
}

}  // namespace

const char* process_env(const char* name) { return std::getenv(name); }

int launcher_rank(const EnvLookup& env) {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK", "SLURM_PROCID"})
    if (const auto rank = count_of(env, name)) return *rank;
  return -1;
}

std::optional<OneHostRanks> one_host_ranks(const EnvLookup& env) {
  // The first launcher whose variables are there answers: they never set another's.
  if (env("OMPI_COMM_WORLD_SIZE"))
    return one_host(env, "OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE",
                    "OMPI_COMM_WORLD_LOCAL_SIZE");
  if (env("PMI_SIZE")) return one_host(env, "PMI_RANK", "PMI_SIZE", "MPI_LOCALNRANKS");
  if (env("SLURM_STEP_NUM_NODES")) {
    // Slurm names the nodes, not the tasks on this one: one node holds them all.
    const auto nodes = count_of(env, "SLURM_STEP_NUM_NODES");
    if (nodes != 1) return std::nullopt;
    return one_host(env, "SLURM_PROCID", "SLURM_STEP_NUM_TASKS", "SLURM_STEP_NUM_TASKS");
  }
  return std::nullopt;
}

int take_launcher_cpus() {
  cpu_set_t own, parent;
  CPU_ZERO(&own);
  CPU_ZERO(&parent);
  if (::sched_getaffinity(0, sizeof own, &own) != 0) return 0;
  if (::sched_getaffinity(::getppid(), sizeof parent, &parent) == 0) {
    cpu_set_t both;
    CPU_OR(&both, &own, &parent);
    // The kernel keeps within what the process's cgroup allows; a refusal leaves it as it was.
    if (CPU_COUNT(&both) > CPU_COUNT(&own) && ::sched_setaffinity(0, sizeof both, &both) == 0)
      own = both;
  }
  return CPU_COUNT(&own);
}

int one_host_jobs(const OneHostRanks& host, int jobs_per_rank) {
  constexpr long long kMostJobs = 65536;
  return static_cast<int>(std::min<long long>(
      kMostJobs, static_cast<long long>(host.size) * std::max(jobs_per_rank, 1)));
}

std::string one_host_note(const char* command, const char* work, const OneHostRanks& host, int jobs,
                          int cpus) {
  return std::string("rtsim ") + command + ": all " + std::to_string(host.size) +
         " MPI ranks are on this host: rank 0 runs the " + work + " as " + std::to_string(jobs) +
         " local jobs on " + std::to_string(cpus) + (cpus == 1 ? " CPU" : " CPUs") +
         " without starting MPI (--one-host mpi hands them out over MPI)\n";
}

}  // namespace rtsim::app
