// Scene file parsing throughput (bytes per second): the largest shared SPD scenes, the teapot
// .bpt, and a large generated NFF text (100,000 Ullner squares written by write_nff), parsed
// from memory so the figures show the reader alone, not the disk.
// Run: build/bench/scene_parse_bench --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <string>

#include "scenes/bpt_reader.hpp"
#include "scenes/generators/ullner_random.hpp"
#include "scenes/nff_reader.hpp"
#include "scenes/scene_text.hpp"
#include "scenes/scene_writer.hpp"

namespace {

using namespace rtsim;

void parse_text(benchmark::State& state, const std::string& text, bool bpt) {
  for (auto _ : state) {
    const scenes::Scene s =
        bpt ? scenes::parse_bpt(text, "bench.bpt") : scenes::parse_nff(text, "bench.nff");
    benchmark::DoNotOptimize(s.primitives.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(text.size()));
}

void parse_file(benchmark::State& state, const std::string& path, bool bpt) {
  parse_text(state, scenes::read_scene_file(path), bpt);
}

void parse_generated(benchmark::State& state) {
  static const std::string text = scenes::write_nff(scenes::make_ullner_random(100'000));
  parse_text(state, text, false);
}

const std::string kShared = RTSIM_SHARED_DIR;

}  // namespace

BENCHMARK_CAPTURE(parse_file, balls_s3_nff, kShared + "/scenes/balls-s3.nff", false)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(parse_file, teapot_s2_nff, kShared + "/scenes/teapot-s2.nff", false)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(parse_file, teapot_bpt, kShared + "/scenes/teapot.bpt", true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(parse_generated)->Unit(benchmark::kMillisecond);
