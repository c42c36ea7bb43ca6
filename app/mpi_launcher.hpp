#pragma once
// What an MPI launcher (OpenMPI's mpirun, MPICH's Hydra, Slurm's srun) tells each process it
// starts, read before MPI_Init: the process's rank, and whether every rank runs on this host.
//
// `rtsim sweep --mpi` uses it twice: to load the image library in the fork servers of the ranks
// whose first points write images, and, when every rank is on this host, to run the sweep as
// local jobs in rank 0 without starting MPI at all (`--one-host jobs`, the default; docs/sweeps.md
// "MPI"). `rtsim validate --mpi` does the latter too. On one host MPI adds only its start-up and
// shutdown (about 0.2 s here, 10-20% of a sweep of two seconds) and nothing the local run queue
// lacks.
#include <functional>
#include <optional>
#include <string>

namespace rtsim::app {

/// Looks up an environment variable (std::getenv; tests pass their own).
using EnvLookup = std::function<const char*(const char*)>;
const char* process_env(const char* name);

/// This process's rank as its launcher tells it before MPI_Init (OMPI_COMM_WORLD_RANK,
/// PMIX_RANK, PMI_RANK or SLURM_PROCID, the first set); -1 if none does.
int launcher_rank(const EnvLookup& env = process_env);

/// The ranks of a launch whose every rank is on this host, as one launcher tells it.
struct OneHostRanks {
  int rank = 0;  ///< this process's
  int size = 1;  ///< every rank's, all on this host
};

/// Whether one launcher's variables say that every rank of the launch runs on this host:
/// OpenMPI (OMPI_COMM_WORLD_SIZE equal to OMPI_COMM_WORLD_LOCAL_SIZE), MPICH's Hydra (PMI_SIZE
/// equal to MPI_LOCALNRANKS) or Slurm (SLURM_STEP_NUM_NODES = 1, SLURM_STEP_NUM_TASKS). Nothing
/// when no launcher says so plainly (none set, several hosts, a value that is not a count, a
/// rank out of range): the caller then starts MPI, which is right everywhere.
std::optional<OneHostRanks> one_host_ranks(const EnvLookup& env = process_env);

/// Adds to this process's CPU affinity the CPUs its parent (the launcher) may run on. A launcher
/// binds each rank to its own core (OpenMPI does with two ranks or fewer); a rank 0 that runs
/// every rank's points must not keep them all on its one core. Returns the CPUs it may run on
/// after (0 if they cannot be read).
int take_launcher_cpus();

/// The local jobs that stand for `host`'s ranks with `jobs_per_rank` each (at most 65536, however
/// many ranks a launcher claims).
int one_host_jobs(const OneHostRanks& host, int jobs_per_rank);

/// What rank 0 says when it runs a launch's work as local jobs (`command`: "sweep", its `work`:
/// "points"): the ranks, the jobs, the CPUs, and how to have MPI instead.
std::string one_host_note(const char* command, const char* work, const OneHostRanks& host, int jobs,
                          int cpus);

}  // namespace rtsim::app
