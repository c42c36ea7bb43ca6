#include "app/module_symbol.hpp"

#include <dlfcn.h>

#include <filesystem>

namespace rtsim::app {

void* find_module_symbol(const char* module, const char* symbol, bool global, std::string& tried) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  const fs::path dir = ec ? fs::path() : exe.parent_path();
  for (const fs::path& candidate :
       {dir / module, dir.parent_path() / module, fs::path(RTSIM_MODULE_DIR) / module}) {
    tried += (tried.empty() ? "" : ", ") + candidate.string();
    void* handle = ::dlopen(candidate.c_str(), RTLD_NOW | (global ? RTLD_GLOBAL : RTLD_LOCAL));
    if (!handle) continue;
    if (void* found = ::dlsym(handle, symbol)) return found;
  }
  return nullptr;
}

}  // namespace rtsim::app
