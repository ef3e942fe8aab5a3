// The all-frames stage's speed, as ratios in one run: against the paper (Lim et al. 2014, "CPU time": 4.5 ms
// per vertex per frame), against the paper's own method (RBF) and against the sum of the frames' one-frame
// surfaces built one after another on one thread (`ratio_to_one_frame_sum`, measured once per benchmark
// outside the timing). Inputs: the 20-frame idealized left-heart cycle (a branching: the default falls back
// to the morph), the 20-frame ellipsoid cycle (apex and base cross planes: frames rebuilt on one mesh, the rest
// carried) and biv-me patient 1's 25 LV frames when ../shared/data is there. Counters: vertices, µs per vertex
// per frame, speed-up over the paper's figure, peak resident memory. Run: bench/morph_bench
#include <sys/resource.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <string>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "contour4d/motion/reconstruct4d.h"
#include "contour4d/phantoms/phantom.h"
#include "contour4d/pipeline/input.h"
#include "contour4d/surface/reconstruct.h"

#include "bench_main.h"

namespace {

const c4d::Sequence& phantom_cycle(const char* name) {
  static std::map<std::string, c4d::Sequence> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    c4d::PhantomOptions o;
    o.frames = 20;
    o.truth_edge = 2.0;  // the truth mesh is not used here
    it = cache.emplace(name, c4d::make_phantom(name, o).contours).first;
  }
  return it->second;
}

const c4d::Sequence& left_heart_cycle() { return phantom_cycle("left-heart-cycle"); }

// biv-me patient 1, LV endocardium (empty when ../shared/data is missing).
const c4d::Sequence& bivme() {
  static const c4d::Sequence seq = [] {
    const std::filesystem::path dir = std::filesystem::path(C4D_DATA_DIR) / "bivme-patient1";
    if (!std::filesystem::exists(dir)) return c4d::Sequence{};
    return c4d::read_contours(dir).sequence;
  }();
  return seq;
}

// The frames' one-frame surfaces built one after another on one thread (seconds).
double one_frame_sum(const c4d::Sequence& seq) {
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t f = 0; f < seq.frames.size(); ++f) c4d::reconstruct_frame(seq, static_cast<int>(f));
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

void run_on(benchmark::State& state, const c4d::Sequence& seq, c4d::MorphMethod method,
            c4d::AllFramesMethod all_frames) {
  if (seq.frames.empty()) {
    state.SkipWithError("input missing (../shared/data)");
    return;
  }
  const double sum = one_frame_sum(seq);
  const int threads = static_cast<int>(state.range(0));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  c4d::Reconstruct4DOptions opt;
  opt.morph.method = method;
  opt.all_frames = all_frames;
  std::size_t vertices = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const c4d::MeshSequence m = c4d::reconstruct_4d(seq, opt);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
  state.counters["one_frame_sum_s"] = sum;
  state.counters["ratio_to_one_frame_sum"] = seconds / static_cast<double>(state.iterations()) / sum;
  state.counters["peak_rss_MB"] = peak_rss_mb();
}

void run(benchmark::State& state, c4d::MorphMethod method,
         c4d::AllFramesMethod all_frames = c4d::AllFramesMethod::Morph) {
  run_on(state, left_heart_cycle(), method, all_frames);
}

// The default (AllFramesMethod::Auto), the frame-after-frame morph and the paper's RBF on each input.
void BM_LeftHeartCycle_Auto(benchmark::State& s) { run(s, c4d::MorphMethod::RbfProject, c4d::AllFramesMethod::Auto); }
void BM_LeftHeartCycle_RbfProject(benchmark::State& s) { run(s, c4d::MorphMethod::RbfProject); }
void BM_LeftHeartCycle_PaperRbf(benchmark::State& s) { run(s, c4d::MorphMethod::Rbf); }
// --method carry: every frame on its own from frame 0's mesh (carry.h), frames in parallel.
void BM_LeftHeartCycle_Carry(benchmark::State& s) { run(s, c4d::MorphMethod::RbfProject, c4d::AllFramesMethod::Carry); }
void BM_EllipsoidCycle_Auto(benchmark::State& s) {
  run_on(s, phantom_cycle("ellipsoid"), c4d::MorphMethod::RbfProject, c4d::AllFramesMethod::Auto);
}
void BM_EllipsoidCycle_RbfProject(benchmark::State& s) {
  run_on(s, phantom_cycle("ellipsoid"), c4d::MorphMethod::RbfProject, c4d::AllFramesMethod::Morph);
}
void BM_Bivme_Auto(benchmark::State& s) {
  run_on(s, bivme(), c4d::MorphMethod::RbfProject, c4d::AllFramesMethod::Auto);
}
void BM_Bivme_RbfProject(benchmark::State& s) {
  run_on(s, bivme(), c4d::MorphMethod::RbfProject, c4d::AllFramesMethod::Morph);
}

BENCHMARK(BM_LeftHeartCycle_Auto)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_LeftHeartCycle_RbfProject)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_LeftHeartCycle_Carry)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_LeftHeartCycle_PaperRbf)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_EllipsoidCycle_Auto)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_EllipsoidCycle_RbfProject)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_Bivme_Auto)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_Bivme_RbfProject)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace

int main(int argc, char** argv) { return c4d::bench::run_benchmarks(argc, argv); }
