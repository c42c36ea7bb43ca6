#pragma once
// Wang, Lewis & Hung's ray/bicubic-Bezier-patch intersection by subdivision: the implemented loop
// of §2.9 (seed 002 L251-L262) built from the functional blocks of bezier_wang_blocks.hpp.
//
//   Step 1: subdivide the input patch into 4 -> buffer1 (capacity 4); generate planes U and V.
//   Step 2: if the iteration count is reached go to step 5; else subdivide each buffer1 patch
//           into 4 -> buffer2 (capacity 16).
//   Step 3: HullClassification, PatchCenter and PatchDistance for every buffer2 patch.
//   Step 4: Culler: the (at most) 4 nearest that pass and are not behind -> buffer1; go to step 2.
//   Step 5: output the centre of the closest of the four.
//
// Termination is a fixed iteration count, not a flatness test (L256); the hardware unrolls it into
// 10 identical loop stages after stage 0 (L284). Resolution: stage 0 splits once and each loop
// stage once more, so after n iterations a surviving subpatch spans 2^-(n+1) of the original
// parameter range in u and in v; the default n = 10 gives 1/2048 (about 1/2048 of the patch's
// linear size). The paper's "after n iterations ... 1/2^n" (L262) counts the loop stages only.
#include <array>
#include <cstdint>

#include "firmware/cost.hpp"
#include "firmware/kernels/bezier_patch_math.hpp"
#include "firmware/kernels/bezier_wang_blocks.hpp"
#include "firmware/kernels/culler_network.hpp"
#include "firmware/kernels/wang_arithmetic.hpp"
#include "firmware/math.hpp"

namespace rtsim::kernels {

/// Loop stages of the hardware pipeline (stages 1-10 after stage 0, seed 002 L284). The paper
/// chose the number "based on observations of the algorithm's convergence rate" (L286) and gives
/// no data; tests/bezier_wang_test.cpp measures it.
inline constexpr int kWangLoopStages = 10;
/// At least one loop stage: with none, the four stage-0 subpatches are never hull-tested and
/// every ray would "hit".
inline constexpr int kWangMinIterations = 1;
/// Subpatch parameter indices are 32-bit: level = iterations + 1 <= 31.
inline constexpr int kWangMaxIterations = 30;

/// What one call did (accumulated, so one object can count many calls).
struct WangCounters {
  std::uint64_t calls = 0;         ///< wang_intersect calls (= PlaneGenerator runs)
  std::uint64_t iterations = 0;    ///< loop stages executed (step 2-4 passes)
  std::uint64_t subdivisions = 0;  ///< PatchSubdivider runs (one patch into four)
  std::uint64_t hull_tests = 0;    ///< subpatches classified (against both planes); each also
                                   ///< gets PatchCenter and PatchDistance
  std::uint64_t culls = 0;         ///< Culler runs
  std::uint64_t hits = 0;

  WangCounters& operator+=(const WangCounters& o) {
    calls += o.calls;
    iterations += o.iterations;
    subdivisions += o.subdivisions;
    hull_tests += o.hull_tests;
    culls += o.culls;
    hits += o.hits;
    return *this;
  }
};

/// Cost of the work the counters record (the software loop stops early once buffer1 is empty).
constexpr Cost wang_cost(const WangCounters& c) {
  return PlaneGenerator::kCost * c.calls + PatchSubdivider::kCost * c.subdivisions +
         (HullClassification::kCost + PatchCenter::kCost + PatchDistance::kCost) * c.hull_tests +
         Culler::kCost * c.culls;
}

/// Stage 0 of the pipeline (L284): PlaneGenerator and the first four-way split.
inline constexpr Cost kWangStage0Cost = PlaneGenerator::kCost + PatchSubdivider::kCost;
/// One full loop stage (Table 4's substages, L437-L441): 4 PatchSubdivider, 16 x
/// (HullClassification + PatchCenter + PatchDistance), 1 Culler.
inline constexpr Cost kWangLoopStageCost =
    PatchSubdivider::kCost * 4 +
    (HullClassification::kCost + PatchCenter::kCost + PatchDistance::kCost) * 16 + Culler::kCost;

/// Data-independent cost of one job through a pipeline of `iterations` loop stages: what the
/// hardware spends whether or not the ray hits (every stage runs on full buffers).
constexpr Cost wang_pipeline_cost(int iterations) {
  return kWangStage0Cost + kWangLoopStageCost * static_cast<std::uint64_t>(iterations);
}

/// How the Culler sorts (step 4): its keys' bits (Culler::kKeyBits: exact) and whether by the
/// ASIC's bitonic network or by the software's selection sort (the same outputs: a test shows it).
struct CullerConfig {
  int key_bits = Culler::kKeyBits;
  bool network = false;
};

/// Result of the pipeline: the centre of the closest surviving subpatch (step 5), or no hit.
template <typename T>
struct WangResult {
  bool hit = false;
  Vec3T<T> point{T(0)};  ///< centre Q(1/2,1/2) of the closest final subpatch
  double u = 0.0;        ///< that centre in the ORIGINAL patch's parameters
  double v = 0.0;
  std::uint32_t level = 0;  ///< subdivision depth of the final subpatch (iterations + 1)
  int survivors = 0;        ///< final buffer1 occupancy (1..4 on a hit)
};

/// A (ray, patch) job as it travels between the pipeline's stages (Fig. 10, L280-L288): the
/// ray, its planes U and V, and buffer1 (the at most four surviving subpatches and their
/// centres). Stage 0 makes it; every loop stage turns it into the next; the last stage's output
/// is the result.
template <typename T>
struct WangJob {
  Vec3T<T> o{T(0)};
  Vec3T<T> d{T(0)};
  RayPlanes<T> planes;
  std::array<Subpatch<T>, Culler::kSurvivors> buffer1;
  std::array<Vec3T<T>, Culler::kSurvivors> centers1;
  int n1 = 0;  ///< buffer1's occupancy
};

/// A loop stage's working sets as they pass between its substages (Table 4, L437-L441): the
/// halves SplitInHalf in u made of buffer1's patches, buffer2 (their halves in v), each buffer2
/// patch's hull verdict, centre and sort key. Stage 0 uses the first two on the input patch.
template <typename T>
struct WangStageWork {
  /// 2 i and 2 i + 1: buffer1[i]'s left and right halves in u. Each keeps its parent's parameter
  /// indices and level (split_v gives the quadrants theirs).
  std::array<Subpatch<T>, 2 * Culler::kSurvivors> halves;
  std::array<Subpatch<T>, Culler::kCandidates> buffer2;
  std::array<bool, Culler::kCandidates> may_hit{};
  std::array<Vec3T<T>, Culler::kCandidates> centers;
  std::array<T, Culler::kCandidates> keys;
  int n2 = 0;  ///< buffer2's occupancy: 4 n1
};

// The substages of a stage, each on the job and the working sets it received. A job whose
// buffer1 is empty (every candidate culled) passes every substage unchanged. Run in order they
// are one loop stage (wang_loop_stage) and give the same bits. `words`: the fixed-point word
// format every word a block writes is stored in (wang_arithmetic.hpp); none for float and
// double.

/// Stage 0's PlaneGenerator (step 1): planes U and V; the input patch as the job's only patch.
template <typename T>
WangJob<T> wang_planes(const ControlNet<T>& net, const Vec3T<T>& o, const Vec3T<T>& d,
                       WangCounters& counters, const FixedWords* words = nullptr) {
  ++counters.calls;
  WangJob<T> job;
  job.o = o;
  job.d = d;
  job.buffer1[0].net = net;
  store_words(words, job.o);  // the job's words, as stage 0 takes them in
  store_words(words, job.d);
  store_words(words, job.buffer1[0].net);
  job.planes = PlaneGenerator::generate(job.o, job.d);
  store_words(words, job.planes.n_u);
  store_words(words, job.planes.e_u);
  store_words(words, job.planes.n_v);
  store_words(words, job.planes.e_v);
  job.n1 = 1;
  return job;
}

/// Substage 1 (L437): SplitInHalf in u of every buffer1 patch (one DSP each).
template <typename T>
void wang_split_u(const WangJob<T>& job, WangStageWork<T>& work,
                  const FixedWords* words = nullptr) {
  for (int i = 0; i < job.n1; ++i) {
    const Subpatch<T>& parent = job.buffer1[i];
    for (Subpatch<T>* half : {&work.halves[2 * i], &work.halves[2 * i + 1]}) {
      half->iu = parent.iu;
      half->iv = parent.iv;
      half->level = parent.level;
    }
    split_u(parent.net, work.halves[2 * i].net, work.halves[2 * i + 1].net);
    store_words(words, work.halves[2 * i].net);
    store_words(words, work.halves[2 * i + 1].net);
  }
}

/// Substage 2 (L438): SplitInHalf in v of every half -> buffer2, four quadrants a buffer1 patch
/// in eq. 11's order (PatchSubdivider::subdivide's, bit for bit).
template <typename T>
void wang_split_v(const WangJob<T>& job, WangStageWork<T>& work, WangCounters& counters,
                  const FixedWords* words = nullptr) {
  for (int i = 0; i < job.n1; ++i) {
    Subpatch<T>* out = &work.buffer2[4 * i];
    split_v(work.halves[2 * i].net, out[kTL].net, out[kBL].net);
    split_v(work.halves[2 * i + 1].net, out[kTR].net, out[kBR].net);
    const Subpatch<T>& parent = work.halves[2 * i];
    for (int q = 0; q < 4; ++q) {
      out[q].iu = 2 * parent.iu + static_cast<std::uint32_t>(quadrant_u_half(q));
      out[q].iv = 2 * parent.iv + static_cast<std::uint32_t>(quadrant_v_half(q));
      out[q].level = parent.level + 1;
      store_words(words, out[q].net);
    }
  }
  work.n2 = 4 * job.n1;
  counters.subdivisions += static_cast<std::uint64_t>(job.n1);
}

/// Stage 0's output: its four quadrants are buffer1 (no hull test or cull in stage 0).
template <typename T>
void wang_stage0_output(WangJob<T>& job, const WangStageWork<T>& work) {
  for (int q = 0; q < Culler::kSurvivors; ++q) job.buffer1[q] = work.buffer2[q];
  job.n1 = Culler::kSurvivors;
}

/// Substage 3 (L439): HullClassification of every buffer2 patch against both planes.
template <typename T>
void wang_hull(const WangJob<T>& job, WangStageWork<T>& work, WangCounters& counters) {
  if (job.n1 == 0) return;
  for (int i = 0; i < work.n2; ++i)
    work.may_hit[i] = HullClassification::classify(job.planes, work.buffer2[i].net).may_hit;
  counters.hull_tests += static_cast<std::uint64_t>(work.n2);
}

/// Substage 4 (L440): PatchCenter and PatchDistance -> the sort keys. Empty slots and hull
/// failures get the "behind" flag (see Culler::select).
template <typename T>
void wang_center_distance(const WangJob<T>& job, WangStageWork<T>& work,
                          const FixedWords* words = nullptr) {
  if (job.n1 == 0) return;
  work.keys.fill(T(PatchDistance::kBehind));
  for (int i = 0; i < work.n2; ++i) {
    work.centers[i] = PatchCenter::center(work.buffer2[i].net);
    store_words(words, work.centers[i]);
    T dist = PatchDistance::distance(job.o, job.d, work.centers[i]);
    store_words(words, dist);
    work.keys[i] = work.may_hit[i] ? dist : T(PatchDistance::kBehind);
  }
}

/// Substage 5 (L441, L302-L318): the Culler's four nearest -> buffer1.
template <typename T>
void wang_cull(WangJob<T>& job, const WangStageWork<T>& work, WangCounters& counters,
               const CullerConfig& culler) {
  if (job.n1 == 0) return;
  std::array<int, Culler::kSurvivors> keep;
  job.n1 = culler.network ? CullerNetwork::select(work.keys, keep, culler.key_bits)
                          : Culler::select(work.keys, keep, culler.key_bits);
  ++counters.culls;
  for (int k = 0; k < job.n1; ++k) {
    job.buffer1[k] = work.buffer2[keep[k]];
    job.centers1[k] = work.centers[keep[k]];
  }
}

/// Stage 0 (step 1): planes U and V; the input patch into four -> buffer1.
template <typename T>
WangJob<T> wang_stage0(const ControlNet<T>& net, const Vec3T<T>& o, const Vec3T<T>& d,
                       WangCounters& counters, const FixedWords* words = nullptr) {
  WangJob<T> job = wang_planes(net, o, d, counters, words);
  WangStageWork<T> work;
  wang_split_u(job, work, words);
  wang_split_v(job, work, counters, words);
  wang_stage0_output(job, work);
  return job;
}

/// One loop stage (steps 2-4): every buffer1 patch into four, hull classification, centre and
/// distance of each, and the Culler's four nearest -> buffer1. An empty job passes unchanged.
template <typename T>
void wang_loop_stage(WangJob<T>& job, WangCounters& counters, const CullerConfig& culler = {},
                     const FixedWords* words = nullptr) {
  if (job.n1 == 0) return;
  ++counters.iterations;
  WangStageWork<T> work;
  wang_split_u(job, work, words);
  wang_split_v(job, work, counters, words);
  wang_hull(job, work, counters);
  wang_center_distance(job, work, words);
  wang_cull(job, work, counters, culler);
}

/// Step 5, the last stage's output: the centre of the closest (the Culler put it first). An
/// empty buffer1 is the null result of the outline's step 3 (L92).
template <typename T>
WangResult<T> wang_output(const WangJob<T>& job, int iterations, WangCounters& counters) {
  WangResult<T> result;
  if (job.n1 > 0 && iterations >= kWangMinIterations) {
    result.hit = true;
    result.point = job.centers1[0];
    result.u = job.buffer1[0].u_center();
    result.v = job.buffer1[0].v_center();
    result.level = job.buffer1[0].level;
    result.survivors = job.n1;
    ++counters.hits;
  }
  return result;
}

/// The loop of §2.9 on one (ray, patch) job. `o`, `d` are the ray in the pipeline's precision;
/// d should be unit length (L100) but only its direction matters here. `iterations` must be in
/// [kWangMinIterations, kWangMaxIterations] (not checked here; the kernel adapter checks it).
/// The software loop stops once buffer1 is empty; the hardware's stages pass the empty job on.
template <typename T>
WangResult<T> wang_intersect(const ControlNet<T>& net, const Vec3T<T>& o, const Vec3T<T>& d,
                             int iterations, WangCounters* counters = nullptr,
                             const CullerConfig& culler = {}, const FixedWords* words = nullptr) {
  WangCounters local;
  WangJob<T> job = wang_stage0(net, o, d, local, words);
  for (int it = 0; it < iterations && job.n1 > 0; ++it) wang_loop_stage(job, local, culler, words);
  const WangResult<T> result = wang_output(job, iterations, local);
  if (counters) *counters += local;
  return result;
}

extern template WangResult<float> wang_intersect<float>(const ControlNet<float>&,
                                                        const Vec3T<float>&, const Vec3T<float>&,
                                                        int, WangCounters*, const CullerConfig&,
                                                        const FixedWords*);
extern template WangResult<double> wang_intersect<double>(const ControlNet<double>&,
                                                          const Vec3T<double>&,
                                                          const Vec3T<double>&, int, WangCounters*,
                                                          const CullerConfig&, const FixedWords*);

}  // namespace rtsim::kernels
