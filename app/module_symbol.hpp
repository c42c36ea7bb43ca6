#pragma once
// rtsim's modules (librtsim_image_io.so, librtsim_mpi.so: libraries too heavy to load at every
// start, app/image_io/image_io_api.hpp, app/mpi/mpi_api.hpp) are found beside the program.
#include <string>

namespace rtsim::app {

/// `symbol` of `module`, dlopen'ed from the program's folder (build/rtsim beside build/lib*.so),
/// its parent (the test programs in build/tests/) or the build folder this rtsim was configured
/// with; `global` loads it RTLD_GLOBAL. nullptr if none has it, with the paths tried in `tried`.
void* find_module_symbol(const char* module, const char* symbol, bool global, std::string& tried);

}  // namespace rtsim::app
