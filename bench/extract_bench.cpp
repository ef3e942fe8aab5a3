// Contour extraction from a cine label image: 256×256×20 voxels, 25 frames, three labels
// (ACDC numbering: RV = 1, MYO = 2, LV = 3), on one core. Target: >= 50 frames per second.
//
//   extract_bench                                  run the benchmarks
//   extract_bench --c4d-write=cine.nii.gz          also write the label image and cine.nii.gz.json
//                                                  (LV ellipsoid per frame) for
//                                                  bench/marching_cubes_baseline.py
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <numbers>
#include <string>

#include "contour4d/extract/mask_contours.h"
#include "contour4d/io/images.h"

namespace {

using namespace c4d;

constexpr int kFrames = 25;
constexpr double kSpacing[3] = {1.25, 1.25, 8.0};

struct Ellipsoid {
  Vec3 c, a;
  double radial(Vec3 p) const {  // |q| (r - 1)/r: distance from the surface along the ray from the centre
    const Vec3 q = p - c;
    const double r = std::sqrt(q.x * q.x / (a.x * a.x) + q.y * q.y / (a.y * a.y) + q.z * q.z / (a.z * a.z));
    return r > 0 ? norm(q) * (r - 1) / r : -a.x;
  }
};

Ellipsoid lv_of(int t) {
  const double s = 1.0 - 0.25 * std::pow(std::sin(std::numbers::pi * t / kFrames), 2);
  return {{160, 150, 76}, {26 * s, 24 * s, 60 * std::sqrt(s)}};
}

const LabelSeries& cine() {
  static const LabelSeries series = [] {
    LabelSeries s;
    s.source = "bench-cine";
    for (int t = 0; t < kFrames; ++t) {
      LabelVolume v;
      v.dims = {256, 256, 20};
      v.spacing = {kSpacing[0], kSpacing[1], kSpacing[2]};
      v.labels.assign(256 * 256 * 20, 0);
      const Ellipsoid lv = lv_of(t);
      const Ellipsoid myo{lv.c, lv.a + Vec3{9, 9, 9}};
      const Ellipsoid rv{{lv.c.x - 38, lv.c.y + 4, lv.c.z - 6}, {30, 42, 55 * std::sqrt(lv.a.x / 26)}};
      for (int k = 0; k < 20; ++k)
        for (int j = 0; j < 256; ++j)
          for (int i = 0; i < 256; ++i) {
            const Vec3 p{i * kSpacing[0], j * kSpacing[1], k * kSpacing[2]};
            int32_t l = 0;
            if (lv.radial(p) < 0)
              l = 3;
            else if (myo.radial(p) < 0)
              l = 2;
            else if (rv.radial(p) < 0)
              l = 1;
            v.labels[static_cast<std::size_t>(i + 256 * (j + 256 * k))] = l;
          }
      s.frames.push_back(std::move(v));
      s.times_ms.push_back(t * 40.0);
    }
    return s;
  }();
  return series;
}

void report_shape(benchmark::State& state, const Sequence& seq) {
  double pts = 0, contours = 0, worst = 0, sum = 0, lv_pts = 0;
  for (std::size_t f = 0; f < seq.frames.size(); ++f)
    for (const Slice& sl : seq.frames[f].slices)
      for (const Contour& c : sl.contours) {
        contours += 1;
        pts += static_cast<double>(c.points.size());
        if (c.label != "lv") continue;
        for (const Vec3& p : c.points) {
          const double e = std::abs(lv_of(static_cast<int>(f)).radial(p));
          worst = std::max(worst, e);
          sum += e;
          lv_pts += 1;
        }
      }
  state.counters["contours_per_frame"] = contours / kFrames;
  state.counters["points_per_frame"] = pts / kFrames;
  if (lv_pts > 0) {
    state.counters["lv_err_max_mm"] = worst;
    state.counters["lv_err_mean_mm"] = sum / lv_pts;
  }
}

void run(benchmark::State& state, const MaskExtractOptions& o) {
  const LabelSeries& s = cine();
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  Sequence seq;
  for (auto _ : state) {
    seq = extract_mask_contours(s, o);
    benchmark::DoNotOptimize(seq.frames.data());
  }
  state.counters["frames_per_s"] = benchmark::Counter(kFrames, benchmark::Counter::kIsIterationInvariantRate);
  report_shape(state, seq);
}

MaskExtractOptions preset(std::vector<std::string> labels) {
  MaskExtractOptions o;
  o.preset = "acdc";
  o.labels = std::move(labels);
  return o;
}

void BM_ExtractAllLabels(benchmark::State& state) { run(state, preset({})); }
void BM_ExtractLV(benchmark::State& state) { run(state, preset({"lv"})); }
void BM_ExtractLVRawStaircase(benchmark::State& state) {
  MaskExtractOptions o = preset({"lv"});
  o.staircase = c4d::StaircaseSmoothing::None;
  o.resample_mm = 0;
  run(state, o);
}
void BM_ExtractLVGaussian(benchmark::State& state) {
  MaskExtractOptions o = preset({"lv"});
  o.presmooth_sigma_px = 0.7;
  o.taubin_passes = 0;
  run(state, o);
}

BENCHMARK(BM_ExtractAllLabels)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ExtractLV)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ExtractLVRawStaircase)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ExtractLVGaussian)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  int n = 0;
  for (int i = 0; i < argc; ++i) {
    if (std::strncmp(argv[i], "--c4d-write=", 12) == 0) {
      const std::string path = argv[i] + 12;
      write_label_volume(path, cine().frames, {ImagePixel::Int16, 1.0});
      std::ofstream js(path + ".json");
      js << "{\"label\": 3, \"frames\": [";
      for (int t = 0; t < kFrames; ++t) {
        const Ellipsoid e = lv_of(t);
        js << (t ? ", " : "") << "{\"center\": [" << e.c.x << ", " << e.c.y << ", " << e.c.z << "], \"axes\": ["
           << e.a.x << ", " << e.a.y << ", " << e.a.z << "]}";
      }
      js << "]}\n";
      std::printf("wrote %s and %s.json\n", path.c_str(), path.c_str());
      continue;
    }
    argv[n++] = argv[i];
  }
  argc = n;
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
