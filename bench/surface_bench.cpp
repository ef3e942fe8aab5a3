// One-frame surface (issue 3): time of reconstruct_frame for one frame of each phantom and of the
// real bivme data; the counter `vertices/s` is output vertices per second (target ≥ 100,000 on one
// core at the default edge length). `_nocheck` variants leave out the CGAL self-intersection test;
// `_cgal_remesher` variants remesh with CGAL's isotropic remeshing instead of ours (SurfaceOptions::rows_remesher);
// `_bands` variants are `--no-rows` (SurfaceOptions::rows = false: every band remeshed, the previous default).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <optional>
#include <string>

#include "contour4d/pipeline/input.h"
#include "contour4d/phantoms/phantom.h"
#include "contour4d/surface/reconstruct.h"

#include "bench_main.h"

namespace {

// engine: both remeshers set to it (std::nullopt: the defaults, ours with rows and CGAL's without).
using Engine = std::optional<c4d::RemeshEngine>;

void run(benchmark::State& state, const c4d::Sequence& seq, bool check, Engine engine = std::nullopt, bool rows = true) {
  // One core: the target is per core, and the self-intersection test lists its pairs in parallel on large meshes.
  const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  c4d::SurfaceOptions o;
  o.check_self_intersections = check;
  if (engine) o.remesher = o.rows_remesher = *engine;
  o.rows = rows;
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

void phantom(benchmark::State& state, const std::string& name, bool oblique, bool check, Engine engine = std::nullopt,
             bool rows = true) {
  c4d::PhantomOptions po;
  po.oblique = oblique;
  const c4d::Phantom ph = c4d::make_phantom(name, po);
  run(state, ph.contours, check, engine, rows);
}

void bivme(benchmark::State& state, bool check, Engine engine = std::nullopt, bool rows = true) {
  const std::string dir = std::string(C4D_DATA_DIR) + "/bivme-patient1/guidepoints";
  c4d::Sequence seq;
  try {
    seq = c4d::read_contours(dir).sequence;
  } catch (const std::exception& e) {
    state.SkipWithError(("cannot read " + dir + ": " + e.what()).c_str());
    return;
  }
  run(state, seq, check, engine, rows);
}

}  // namespace

BENCHMARK_CAPTURE(phantom, ellipsoid, std::string("ellipsoid"), false, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, ellipsoid_nocheck, std::string("ellipsoid"), false, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, ellipsoid_oblique, std::string("ellipsoid"), true, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, left_heart_ed, std::string("left-heart-ed"), false, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, left_heart_ed_nocheck, std::string("left-heart-ed"), false, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, left_heart_es, std::string("left-heart-es"), false, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, torus, std::string("torus"), false, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, bifurcation, std::string("bifurcation"), false, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(bivme, frame0, true)->Unit(benchmark::kMillisecond);
// The same with CGAL's remeshing (SurfaceOptions::rows_remesher = Cgal, the rows' remesher before): the ratio of
// the default rows above to these.
BENCHMARK_CAPTURE(phantom, left_heart_ed_cgal_remesher, std::string("left-heart-ed"), false, true, c4d::RemeshEngine::Cgal)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, torus_cgal_remesher, std::string("torus"), false, true, c4d::RemeshEngine::Cgal)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(bivme, frame0_cgal_remesher, true, c4d::RemeshEngine::Cgal)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(bivme, frame0_nocheck, false)->Unit(benchmark::kMillisecond);
// `--no-rows` (SurfaceOptions::rows = false: every band remeshed, then the faired surface): the ratio of the
// default rows above to these.
BENCHMARK_CAPTURE(phantom, left_heart_ed_bands, std::string("left-heart-ed"), false, true, std::nullopt, false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, left_heart_es_bands, std::string("left-heart-es"), false, true, std::nullopt, false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(phantom, torus_bands, std::string("torus"), false, true, std::nullopt, false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(bivme, frame0_bands, true, std::nullopt, false)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) { return c4d::bench::run_benchmarks(argc, argv); }
