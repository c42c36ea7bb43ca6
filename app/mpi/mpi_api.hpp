#pragma once
// The interface between `rtsim sweep --mpi` (app/mpi/sweep_mpi.cpp) and its MPI module
// (librtsim_mpi.so, app/mpi/mpi_module.cpp, built when CMake finds MPI). Open MPI and the
// libraries it brings are loaded only by `--mpi`, not by every rtsim start.
//
// Plain C types only. Every function returns 0 on success, else an error code of MPI's.
#include <cstddef>

extern "C" {

struct rtsim_mpi_api {
  /// MPI_Init_thread (the main thread calls MPI), then this process's rank and the size.
  int (*init)(int* rank, int* size);
  /// MPI_Abort(1) when `abort`, else MPI_Finalize.
  void (*finish)(int abort);
  /// MPI_Send of `size` chars to `dest` with `tag`.
  int (*send_text)(const char* data, int size, int dest, int tag);
  /// MPI_Iprobe from `source` (-1: any) with any tag; if a message has arrived, receives it into
  /// a buffer from malloc (*data, *size chars; the caller frees it) and sets *arrived, *from
  /// and *tag.
  int (*poll_text)(int source, int* arrived, int* from, int* tag, char** data, int* size);
  /// MPI_Bcast of one int from rank 0.
  int (*bcast_int)(int* value);
};

/// The module's entry point, looked up by this name: returns its table.
typedef const rtsim_mpi_api* (*rtsim_mpi_api_fn)();
inline constexpr const char* kRtsimMpiApiSymbol = "rtsim_mpi_api";
}
