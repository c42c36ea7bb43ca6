#include "platform/machines/wang_bezier/job_fault.hpp"

#include <algorithm>
#include <bit>
#include <cctype>

#include "common/input_error.hpp"
#include "platform/machines/machine_support.hpp"

namespace rtsim::platform::wang_bezier {

namespace {
/// Words of a job on the wire into stage 0.
constexpr std::uint64_t kJobWords = PatchJob::kWireBits / 32;
/// Words of a job between stages that a fault may change: O, D, the planes, buffer1's patches.
constexpr std::uint64_t kStageWords = 6 + 8 + kernels::Culler::kSurvivors * 48;

/// A word on the wire (a single), its bits XORed: a wide arithmetic's word as it travels.
template <typename T>
void flip(T& x, std::uint32_t mask) {
  x = static_cast<T>(
      std::bit_cast<float>(std::bit_cast<std::uint32_t>(static_cast<float>(x)) ^ mask));
}

template <typename T>
void flip_net(kernels::ControlNet<T>& net, std::uint64_t w, std::uint32_t mask) {
  const std::uint64_t point = w / 3;
  flip(net.p[point / 4][point % 4][static_cast<int>(w % 3)], mask);
}
}  // namespace

std::string JobFault::at(const std::string& pipeline) const {
  return stage == 0 ? pipeline + ".input" : pipeline + ".loop" + std::to_string(stage) + ".in";
}

void JobFault::apply(PatchJob& job) {
  ++applied;
  if (word < 3) return flip(job.o[static_cast<int>(word)], xor_mask);
  if (word < 6) return flip(job.d[static_cast<int>(word - 3)], xor_mask);
  flip_net(job.net, word - 6, xor_mask);
}

template <typename T>
void JobFault::apply(kernels::WangJob<T>& job) {
  ++applied;
  if (word < 3) return flip(job.o[static_cast<int>(word)], xor_mask);
  if (word < 6) return flip(job.d[static_cast<int>(word - 3)], xor_mask);
  if (word < 14) {
    kernels::RayPlanes<T>& p = job.planes;
    T* plane_words[8] = {&p.n_u.x, &p.n_u.y, &p.n_u.z, &p.e_u,
                         &p.n_v.x, &p.n_v.y, &p.n_v.z, &p.e_v};
    return flip(*plane_words[word - 6], xor_mask);
  }
  const std::uint64_t w = word - 14;
  flip_net(job.buffer1[w / 48].net, w % 48, xor_mask);
}

template void JobFault::apply(kernels::WangJob<float>&);
template void JobFault::apply(kernels::WangJob<double>&);

std::vector<JobFault> job_faults(const std::string& pipeline, int loop_stages,
                                 std::vector<MemoryFault>& faults) {
  const std::string input = pipeline + ".input";
  const std::string loop = pipeline + ".loop";
  std::vector<JobFault> out;
  for (const MemoryFault& f : take_faults(faults, [&](const std::string& name) {
         return name == input || (name.starts_with(loop) && name.ends_with(".in"));
       })) {
    const std::string arg = "--fault " + f.memory + ":" + std::to_string(f.word);
    if (f.memory == input) {
      if (f.word >= kJobWords)
        throw InputError(arg, 0,
                         "a ray/patch job has " + std::to_string(kJobWords) +
                             " words (0-2 O, 3-5 D, 6-53 the 16 control points, 3 words each)");
      out.push_back({.stage = 0, .word = f.word, .xor_mask = f.xor_mask});
      continue;
    }
    const std::string digits = f.memory.substr(loop.size(), f.memory.size() - loop.size() - 3);
    const bool number = !digits.empty() && digits.size() <= 4 &&
                        std::all_of(digits.begin(), digits.end(), [](char c) {
                          return std::isdigit(static_cast<unsigned char>(c));
                        });
    const int stage = number ? std::stoi(digits) : 0;
    if (stage < 1 || stage > loop_stages)
      throw InputError(arg, 0,
                       "the pipeline's loop stages are " + loop + "1.in to " + loop +
                           std::to_string(loop_stages) + ".in (bezier.iterations), and " + input +
                           " enters stage 0");
    if (f.word >= kStageWords)
      throw InputError(arg, 0,
                       "a job between stages has " + std::to_string(kStageWords) +
                           " words a fault may change (0-2 O, 3-5 D, 6-13 the planes N_U, E_U, "
                           "N_V, E_V, 14-205 buffer1's four patches, 48 words each)");
    out.push_back({.stage = stage, .word = f.word, .xor_mask = f.xor_mask});
  }
  return out;
}

}  // namespace rtsim::platform::wang_bezier
