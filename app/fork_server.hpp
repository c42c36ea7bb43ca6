#pragma once
// The runs of an MPI rank (`rtsim sweep --mpi`, `rtsim validate --mpi`) as forks of a process
// started before MPI. A rank must not fork its runs itself: OpenMPI's threads and network state
// would be copied half-way. Starting a new rtsim for each run costs a program start and, for a
// run that writes an image, loading the image library (about half a second, where a point of
// the fig2-18 sweep takes a tenth: MPI sweeps on one box were 5x slower than local jobs).
//
// So each slot of a rank gets a fork server: a process forked from the main thread before
// MPI_Init, which loads the image module once (at once, when its rank knows that runs will write
// images: the load then overlaps MPI's start-up) and then, for each request, forks a child that
// runs the command line in-process (run_cli_in_forked_child), with its output in the run's log. The
// server tells the child's pid at once (so stop_runs can signal it) and its wait status when it
// ends. A server ends when its rank closes its socket, or dies with its rank.
#include <sys/types.h>

#include <condition_variable>
#include <filesystem>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace rtsim::app {

class ForkServers {
 public:
  /// Forks `count` servers now (call before MPI_Init, from the main thread); each runs its
  /// requests one at a time with `run` in a forked child and returns its exit status. With
  /// `load_image_module`, each server loads the image library as soon as it starts, while its
  /// rank is still in MPI_Init, rather than when the first run that writes an image comes.
  ForkServers(int count, std::function<int(const std::vector<std::string>&)> run,
              bool load_image_module = false);
  /// Closes the sockets (the servers end) and waits for them.
  ~ForkServers();
  ForkServers(const ForkServers&) = delete;
  ForkServers& operator=(const ForkServers&) = delete;

  /// runs::RunQueueOptions::run_and_wait: runs `args` (argv[0] the program's path) on a free
  /// server with stdout and stderr to `log`, calls `started` with the child's pid, and returns
  /// its wait status; -1 with `error` if it could not run. Thread-safe; waits for a free server.
  int run_and_wait(const std::vector<std::string>& args, const std::filesystem::path& log,
                   const std::function<void(pid_t)>& started, std::string& error);

 private:
  struct Server {
    pid_t pid = -1;
    int socket = -1;
    bool busy = false;
  };
  std::vector<Server> servers_;
  std::mutex mutex_;
  std::condition_variable free_;
};

/// RunQueueOptions::run_and_wait through `servers` (which must outlive the queue).
std::function<int(const std::vector<std::string>&, const std::filesystem::path&,
                  const std::function<void(pid_t)>&, std::string&)>
fork_server_runner(ForkServers& servers);

}  // namespace rtsim::app
