// librtsim_mpi.so: the MPI calls of `rtsim sweep --mpi`, loaded by --mpi only
// (app/mpi/mpi_api.hpp). The only file that includes mpi.h.
#include <mpi.h>

#include <cstdlib>

#include "app/mpi/mpi_api.hpp"

namespace {

int init(int* rank, int* size) {
  // Our messages are a few hundred bytes of JSON a run: OpenMPI's ob1 messaging with its own
  // transports starts in 0.13 s where the default's probing of UCX takes 0.35 s, a fifth of a
  // small sweep on one box (docs/sweeps.md). A user's own choice (mpirun --mca pml, or the
  // environment) wins.
  setenv("OMPI_MCA_pml", "ob1", /*overwrite=*/0);
  int provided = 0;
  if (int rc = MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided); rc != MPI_SUCCESS)
    return rc;
  if (int rc = MPI_Comm_rank(MPI_COMM_WORLD, rank); rc != MPI_SUCCESS) return rc;
  return MPI_Comm_size(MPI_COMM_WORLD, size);
}

void finish(int abort) {
  if (abort) MPI_Abort(MPI_COMM_WORLD, 1);
  MPI_Finalize();
}

int send_text(const char* data, int size, int dest, int tag) {
  // MPI_Send takes a non-const buffer in older MPI headers.
  return MPI_Send(const_cast<char*>(data), size, MPI_CHAR, dest, tag, MPI_COMM_WORLD);
}

int poll_text(int source, int* arrived, int* from, int* tag, char** data, int* size) {
  MPI_Status status;
  *arrived = 0;
  if (int rc = MPI_Iprobe(source < 0 ? MPI_ANY_SOURCE : source, MPI_ANY_TAG, MPI_COMM_WORLD,
                          arrived, &status);
      rc != MPI_SUCCESS || !*arrived)
    return rc;
  int count = 0;
  if (int rc = MPI_Get_count(&status, MPI_CHAR, &count); rc != MPI_SUCCESS) return rc;
  *data = static_cast<char*>(std::malloc(static_cast<std::size_t>(count > 0 ? count : 1)));
  *size = count;
  *from = status.MPI_SOURCE;
  *tag = status.MPI_TAG;
  return MPI_Recv(*data, count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
                  MPI_STATUS_IGNORE);
}

int bcast_int(int* value) { return MPI_Bcast(value, 1, MPI_INT, 0, MPI_COMM_WORLD); }

const rtsim_mpi_api kApi = {init, finish, send_text, poll_text, bcast_int};

}  // namespace

extern "C" __attribute__((visibility("default"))) const rtsim_mpi_api* rtsim_mpi_api() {
  return &kApi;
}
