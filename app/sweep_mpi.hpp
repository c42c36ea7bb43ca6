#pragma once
// `rtsim sweep --mpi`: the points of a sweep spread over MPI ranks. Rank 0 reads and checks the
// sweep, then hands out points one at a time as ranks ask for work (dynamic load balancing) and
// runs `--jobs` points itself meanwhile; every other rank runs what it is given (each point is
// still its own `rtsim run` process) and sends back the outcome with the run's stats.json, so
// rank 0 writes the one results table.
//
// This header has no MPI in it: app/mpi/sweep_mpi.cpp implements it with the MPI C API, and
// app/mpi/sweep_no_mpi.cpp (a build without MPI) makes Session's constructor throw.
#include <cstddef>
#include <functional>
#include <vector>

#include "platform/runs/run_queue.hpp"
#include "platform/sweep/point_outcome.hpp"

namespace rtsim::app::mpi {

/// Whether this rtsim was built with MPI.
bool built_with_mpi();

/// One MPI session: MPI_Init_thread (main thread calls MPI) to MPI_Finalize.
class Session {
 public:
  Session();   ///< std::runtime_error when built without MPI
  ~Session();  ///< MPI_Finalize; MPI_Abort instead when an exception is unwinding (no rank hangs)
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }

  /// Rank 0 passes `status` (0: go on; else every rank exits with it); the others get it.
  int share_status(int status);

  /// Rank 0: runs every request somewhere, `local.jobs` at a time on this rank and one per slot
  /// on the others, handing out the next request to whoever finishes first. `on_done(i, o)` is
  /// called on this thread for request i as results arrive. Returns when all requests are done
  /// and every other rank has been told to stop.
  void dispatch(const std::vector<runs::RunRequest>& requests, const runs::RunQueueOptions& local,
                const std::function<void(std::size_t, const sweep::PointOutcome&)>& on_done);

  /// Every other rank: asks rank 0 for work (`options.jobs` requests at once), runs each in its
  /// own process under options.executable, sends the outcomes, until told to stop. The
  /// folders are the ones rank 0 names.
  void work(const runs::RunQueueOptions& options);

 private:
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace rtsim::app::mpi
