// `rtsim sweep --mpi` in a build without MPI (CMake found no MPI): says so.
#include <stdexcept>

#include "app/sweep_mpi.hpp"

namespace rtsim::app::mpi {

bool built_with_mpi() { return false; }

Session::Session() {
  throw std::runtime_error(
      "this rtsim was built without MPI: install Debian's libopenmpi-dev and openmpi-bin "
      "(scripts/quickstart.sh does) and re-run cmake");
}

Session::~Session() = default;

int Session::share_status(int status) { return status; }

void Session::dispatch(const std::vector<validation::RunRequest>&,
                       const validation::RunQueueOptions&,
                       const std::function<void(std::size_t, const sweep::PointOutcome&)>&) {}

void Session::work(const validation::RunQueueOptions&) {}

}  // namespace rtsim::app::mpi
