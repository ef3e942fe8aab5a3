// One-frame surface (issue 3): time of reconstruct_frame for one frame of each phantom and of the
// real bivme data; the counter `vertices/s` is output vertices per second (target ≥ 100,000 on one
// core at the default edge length). `_nocheck` variants leave out the CGAL self-intersection test;
// `_bands` variants remesh every band (SurfaceOptions::rows = false, our remesher: the 4D run's frame 0).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <string>

#include "contour4d/pipeline/input.h"
#include "contour4d/phantoms/phantom.h"
#include "contour4d/surface/reconstruct.h"

#include "bench_main.h"

namespace {

void run(benchmark::State& state, const c4d::Sequence& seq, bool check, bool rows = true) {
  // One core: the target is per core, and the self-intersection test lists its pairs in parallel on large meshes.
  const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  c4d::SurfaceOptions o;
  o.check_self_intersections = check;
  o.rows = rows;
  o.remesher = c4d::RemeshEngine::Fast;  // with rows = false, as the 4D run's frame 0
  std::size_t vertices = 0;
  for (auto _ : state) {
    const c4d::TriangleMesh m = c4d::reconstruct_frame(seq, 0, o);
    vertices = m.positions.size();
    benchmark::DoNotOptimize(m.positions.data());
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["vertices/s"] =
      benchmark::Counter(static_cast<double>(vertices), benchmark::Counter::kIsIterationInvariantRate);
}

void phantom(benchmark::State& state, const std::string& name, bool oblique, bool check, bool rows = true) {
  c4d::PhantomOptions po;
  po.oblique = oblique;
  const c4d::Phantom ph = c4d::make_phantom(name, po);
  run(state, ph.contours, check, rows);
}

void bivme(benchmark::State& state, bool check, bool rows = true) {
  const std::string dir = std::string(C4D_DATA_DIR) + "/bivme-patient1/guidepoints";
  c4d::Sequence seq;
  try {
    seq = c4d::read_contours(dir).sequence;
  } catch (const std::exception& e) {
    state.SkipWithError(("cannot read " + dir + ": " + e.what()).c_str());
    return;
  }
  run(state, seq, check, rows);
}

}  // namespace

BENCHMARK_CAPTURE(phantom, ellipsoid, std::string("ellipsoid"), false, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, ellipsoid_nocheck, std::string("ellipsoid"), false, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, ellipsoid_oblique, std::string("ellipsoid"), true, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, left_heart_ed, std::string("left-heart-ed"), false, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, left_heart_ed_nocheck, std::string("left-heart-ed"), false, false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, left_heart_es, std::string("left-heart-es"), false, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, torus, std::string("torus"), false, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, bifurcation, std::string("bifurcation"), false, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(bivme, frame0, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(bivme, frame0_nocheck, false)->Unit(benchmark::kMillisecond);
// Every band remeshed (SurfaceOptions::rows = false): the ratio of the default rows above to these.
BENCHMARK_CAPTURE(phantom, left_heart_ed_bands, std::string("left-heart-ed"), false, true, false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, left_heart_es_bands, std::string("left-heart-es"), false, true, false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, torus_bands, std::string("torus"), false, true, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(bivme, frame0_bands, true, false)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) { return c4d::bench::run_benchmarks(argc, argv); }
