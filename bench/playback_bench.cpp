// Miara et al. Tables I and II on a synthetic cardiac-like sequence: storage of model.c4d and
// model.glb against per-frame meshes, and headless playback time and bytes per frame, classical
// (each frame's mesh uploaded) against compact (data once, a uniform per frame), in one run.
// Usage: playback_bench [subdivisions=6] [frames=20] [draws=40]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "contour4d/io/gltf.h"
#include "contour4d/io/model_c4d.h"
#include "contour4d/render/renderer.h"
#include "contour4d/temporal/compact.h"
#include "contour4d/temporal/sequence.h"

int main(int argc, char** argv) {
  using namespace c4d;
  using clock = std::chrono::steady_clock;
  const int subdiv = argc > 1 ? std::atoi(argv[1]) : 6;
  const std::size_t frames = argc > 2 ? static_cast<std::size_t>(std::atoi(argv[2])) : 20;
  const int draws = argc > 3 ? std::atoi(argv[3]) : 40;
  const MeshSequence seq = synthetic_beating_mesh(subdiv, frames);
  const std::size_t nv = seq.positions[0].size(), nt = seq.triangles.size();
  auto t0 = clock::now();
  CompactStats st;
  const CompactModel model = compact_encode(seq, {}, nullptr, &st);
  const double enc_s = std::chrono::duration<double>(clock::now() - t0).count();
  const std::size_t c4d = serialize_model_c4d(model).size();
  const std::size_t glb = gltf_glb_bytes(seq).size();
  const double vtp = static_cast<double>(nv * 24 + nt * 32) * frames, ply = static_cast<double>(nv * 12 + nt * 13) * frames;
  std::printf("Table I  %zu vertices, %zu triangles, %zu frames (encode %.2f s)\n", nv, nt, frames, enc_s);
  std::printf("  per-frame VTP  %12.0f B  (%.0fx model.c4d)\n", vtp, vtp / c4d);
  std::printf("  per-frame PLY  %12.0f B  (%.0fx model.c4d)\n", ply, ply / c4d);
  std::printf("  model.c4d      %12zu B  (index %zu, positions %zu, motion %zu, corrections %zu [%zu])\n", c4d,
              st.index_bytes, st.position_bytes, st.motion_bytes, st.correction_bytes, st.corrected_vertices);
  std::printf("  model.glb      %12zu B\n", glb);
  std::printf("  error max %.4f mm, RMS %.4f mm\n", st.max_error, st.rms_error);

  RenderOptions o;
  o.width = 800;
  o.height = 600;
  OffscreenRenderer r(o);
  std::printf("Table II  %s, %zu triangles drawn per frame, %dx%d\n", r.description().c_str(), nt, o.width, o.height);
  r.load_classical(seq);
  r.draw_classical(0);
  r.finish();
  std::size_t bc = 0;
  t0 = clock::now();
  for (int i = 0; i < draws; ++i) bc += r.draw_classical(static_cast<std::size_t>(i) % frames);
  r.finish();
  const double mc = std::chrono::duration<double, std::milli>(clock::now() - t0).count() / draws;
  r.load_compact(model);
  r.draw_compact(0);
  r.finish();
  std::size_t bk = 0;
  t0 = clock::now();
  for (int i = 0; i < draws; ++i) bk += r.draw_compact(seq.times_ms[static_cast<std::size_t>(i) % frames] + 10.0);
  r.finish();
  const double mk = std::chrono::duration<double, std::milli>(clock::now() - t0).count() / draws;
  std::printf("  classical  %8.2f ms/frame  %10zu B/frame\n", mc, bc / draws);
  std::printf("  compact    %8.2f ms/frame  %10zu B/frame\n", mk, bk / draws);
  std::printf("  speed-up %.2fx, %.0fx fewer bytes per frame\n", mc / mk, static_cast<double>(bc) / bk);
  return 0;
}
