#include "platform/functional/every_core.hpp"

#include <algorithm>
#include <system_error>
#include <thread>
#include <vector>

namespace rtsim::functional {

int every_core() {
  return static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 256u));
}

int run_on_threads(int threads, const std::function<void(int)>& worker) {
  std::vector<std::thread> pool;
  for (int t = 1; t < std::max(1, threads); ++t) {
    try {
      pool.emplace_back(worker, t);
    } catch (const std::system_error&) {
      break;  // out of threads or memory for their stacks: those that started share the work
    }
  }
  worker(0);
  for (auto& th : pool) th.join();
  return 1 + static_cast<int>(pool.size());
}

}  // namespace rtsim::functional
