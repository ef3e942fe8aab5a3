// Issue 4's speed target, as a ratio to the paper (Lim et al. 2014, "CPU time": 4.5 ms per vertex
// per frame) and to the paper's own method in the same run: the whole 4D reconstruction of the
// 20-frame idealized left-heart cycle. Counters: vertices, µs per vertex per frame, speed-up over
// the paper's published figure, peak resident memory. Run: bench/morph_bench
#include <sys/resource.h>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "contour4d/motion/reconstruct4d.h"
#include "contour4d/phantoms/phantom.h"

#include "bench_main.h"

namespace {

const c4d::Phantom& left_heart_cycle() {
  static const c4d::Phantom p = [] {
    c4d::PhantomOptions o;
    o.frames = 20;
    o.truth_edge = 2.0;  // the truth mesh is not used here
    return c4d::make_phantom("left-heart-cycle", o);
  }();
  return p;
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

void run(benchmark::State& state, c4d::MorphMethod method,
         c4d::AllFramesMethod all_frames = c4d::AllFramesMethod::Morph) {
  const int threads = static_cast<int>(state.range(0));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  const c4d::Sequence& seq = left_heart_cycle().contours;
  c4d::Reconstruct4DOptions opt;
  opt.morph.method = method;
  opt.all_frames = all_frames;
  std::size_t vertices = 0;
  for (auto _ : state) {
    const c4d::MeshSequence m = c4d::reconstruct_4d(seq, opt);
    vertices = m.positions.front().size();
    benchmark::DoNotOptimize(m.positions.back().data());
  }
  const double frames = static_cast<double>(seq.frames.size());
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["frames"] = frames;
  state.counters["us_per_vertex_frame"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(vertices) * frames / 1e6,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  // Lim et al. report 4.5 ms per vertex per frame; speed-up = 4500 µs / ours.
  state.counters["speedup_vs_paper"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(vertices) * frames * 4.5e-3,
                         benchmark::Counter::kIsRate);
  state.counters["peak_rss_MB"] = peak_rss_mb();
}

void BM_LeftHeartCycle_RbfProject(benchmark::State& s) { run(s, c4d::MorphMethod::RbfProject); }
void BM_LeftHeartCycle_PaperRbf(benchmark::State& s) { run(s, c4d::MorphMethod::Rbf); }
// --method carry: every frame on its own from frame 0's mesh (carry.h), frames in parallel.
void BM_LeftHeartCycle_Carry(benchmark::State& s) { run(s, c4d::MorphMethod::RbfProject, c4d::AllFramesMethod::Carry); }

BENCHMARK(BM_LeftHeartCycle_RbfProject)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_LeftHeartCycle_Carry)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_LeftHeartCycle_PaperRbf)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace

int main(int argc, char** argv) { return c4d::bench::run_benchmarks(argc, argv); }
