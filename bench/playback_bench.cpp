// Miara et al. Tables I and II on a synthetic cardiac-like sequence, in one run.
//  Table I: storage of model.c4d (vertex and surface error bounds) and model.glb against per-frame
//    meshes of the same sequence (bench/storage_table.sh does it against marching cubes meshes).
//  Table II: headless playback, ms and bytes uploaded per frame, on the same scene at the same
//    displayed triangle count:
//    - classical: each frame's full mesh (the displaced patches tessellated on the CPU, positions
//      and triangles) uploaded with glBufferSubData and drawn;
//    - compact: the base mesh and all displacement maps uploaded once, per frame two uniform vectors;
//      the tessellation shaders rebuild the surface (the pipeline of `contour4d view`).
//    Scenes: a large viewport, and a small one where the rasteriser's share is small and the
//    upload dominates, as with Miara et al.'s discrete GPU behind a bus.
//  Then the default path of `contour4d render` on the fine mesh itself: classical (each frame's mesh
//  uploaded) against compact (model.c4d decoded, frame 0 and every frame's displacement uploaded once,
//  blended in the vertex shader), ms per frame and frames per second (bench/gpu_check.sh runs this part).
// Usage: playback_bench [subdivisions=6] [frames=20] [draws=30] [base_triangles=2000] [level=6] [tables=all|vertex]
//  (subdivisions 7: 327,680 triangles; 8: 1,310,720.)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "contour4d/io/gltf.h"
#include "contour4d/temporal/model_c4d.h"
#include "contour4d/render/renderer.h"
#include "contour4d/temporal/compact.h"
#include "contour4d/temporal/displacement_map.h"
#include "contour4d/temporal/sequence.h"

namespace {

using clock_type = std::chrono::steady_clock;

double coverage(const c4d::Image& im) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < im.rgba.size(); i += 4)
    n += !(im.rgba[i] == 255 && im.rgba[i + 1] == 255 && im.rgba[i + 2] == 255);
  return static_cast<double>(n) / (static_cast<double>(im.width) * im.height);
}

void table2(const c4d::MeshSequence& classical, const c4d::PatchMesh& pm, int level, int width, int height, int draws) {
  using namespace c4d;
  RenderOptions o;
  o.width = width;
  o.height = height;
  o.perspective = true;
  OffscreenRenderer r(o);
  const std::size_t frames = classical.positions.size();
  r.load_classical(classical);
  r.draw_classical(0);
  r.finish();
  const double cov_c = coverage(r.read_image());
  std::size_t bc = 0;
  auto t0 = clock_type::now();
  for (int i = 0; i < draws; ++i) bc += r.draw_classical(static_cast<std::size_t>(i) % frames);
  r.finish();
  const double mc = std::chrono::duration<double, std::milli>(clock_type::now() - t0).count() / draws;

  r.patches().load(pm);
  PatchDrawState st;
  st.level = level;
  st.width = width;
  st.height = height;
  // Match the classical camera's image coverage (coverage ~ 1 / zoom²), so both rasterise alike.
  r.draw_patches(st);
  st.camera.zoom *= std::sqrt(coverage(r.read_image()) / std::max(cov_c, 1e-3));
  const std::uint64_t shown = r.patches().count_triangles(st);
  r.draw_patches(st);
  r.finish();
  const double cov_k = coverage(r.read_image());
  std::size_t bk = 0;
  t0 = clock_type::now();
  for (int i = 0; i < draws; ++i) {
    st.t_ms = pm.times_ms[static_cast<std::size_t>(i) % frames] + 10.0;  // between frames: GPU interpolation
    bk += r.draw_patches(st);
  }
  r.finish();
  const double mk = std::chrono::duration<double, std::milli>(clock_type::now() - t0).count() / draws;
  std::printf("  %dx%d  classical %zu triangles: %8.2f ms/frame %10zu B/frame (covers %.0f%% of the image)\n", width,
              height, classical.triangles.size(), mc, bc / draws, 100 * cov_c);
  std::printf(
      "  %dx%d  compact   %llu triangles (base %zu, level %d): %8.2f ms/frame %10zu B/frame (covers %.0f%%), "
      "%zu B once\n",
      width, height, static_cast<unsigned long long>(shown), pm.triangles.size(), level, mk, bk / draws, 100 * cov_k,
      r.patches().static_bytes());
  std::printf("  %dx%d  speed-up %.2fx, %.0fx fewer bytes per frame\n", width, height, mc / mk,
              static_cast<double>(bc) / static_cast<double>(bk));
}

// The fine mesh through `contour4d render`'s two paths at 800 x 600: classical against compact.
void vertex_path(const c4d::MeshSequence& seq, const c4d::CompactModel& model, int draws) {
  using namespace c4d;
  RenderOptions o;
  o.width = 800;
  o.height = 600;
  OffscreenRenderer r(o);
  const std::size_t frames = seq.positions.size();
  r.load_classical(seq);
  r.draw_classical(0);
  r.finish();
  auto t0 = clock_type::now();
  for (int i = 0; i < draws; ++i) r.draw_classical(static_cast<std::size_t>(i) % frames);
  r.finish();
  const double mc = std::chrono::duration<double, std::milli>(clock_type::now() - t0).count() / draws;
  r.load_compact(model);
  r.draw_compact(0.0);
  r.finish();
  t0 = clock_type::now();
  for (int i = 0; i < draws; ++i) r.draw_compact(seq.times_ms[static_cast<std::size_t>(i) % frames] + 10.0);
  r.finish();
  const double mk = std::chrono::duration<double, std::milli>(clock_type::now() - t0).count() / draws;
  std::printf("Render paths  %s, %zu triangles, %d draws each, 800x600\n", r.description().c_str(),
              seq.triangles.size(), draws);
  std::printf("  classical %8.3f ms/frame (%6.0f frames/s)\n", mc, 1000.0 / mc);
  std::printf("  compact   %8.3f ms/frame (%6.0f frames/s), speed-up %.2fx\n", mk, 1000.0 / mk, mc / mk);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace c4d;
  const int subdiv = argc > 1 ? std::atoi(argv[1]) : 6;
  const std::size_t frames = argc > 2 ? static_cast<std::size_t>(std::atoi(argv[2])) : 20;
  const int draws = argc > 3 ? std::atoi(argv[3]) : 30;
  const std::size_t base = argc > 4 ? static_cast<std::size_t>(std::atoi(argv[4])) : 2000;
  const int level = argc > 5 ? std::atoi(argv[5]) : 6;
  const MeshSequence seq = synthetic_beating_mesh(subdiv, frames);
  const std::size_t nv = seq.positions[0].size(), nt = seq.triangles.size();
  auto t0 = clock_type::now();
  CompactStats st;
  const CompactModel model = compact_encode(seq, {}, nullptr, &st);
  const double enc_s = std::chrono::duration<double>(clock_type::now() - t0).count();
  const std::size_t c4d = serialize_model_c4d(model).size();
  const std::size_t glb = argc > 6 && std::string(argv[6]) == "vertex" ? 0 : gltf_glb_bytes(seq).size();
  const double vtp = static_cast<double>(nv * 24 + nt * 32) * frames,
               ply = static_cast<double>(nv * 12 + nt * 13) * frames;
  std::printf("Table I  %zu vertices, %zu triangles, %zu frames (encode %.2f s)\n", nv, nt, frames, enc_s);
  std::printf("  per-frame VTP  %12.0f B  (%.0fx model.c4d)\n", vtp, vtp / c4d);
  std::printf("  per-frame PLY  %12.0f B  (%.0fx model.c4d)\n", ply, ply / c4d);
  std::printf(
      "  model.c4d      %12zu B  (before zstd: index %zu, positions %zu, motion %zu) vertex max %.4f mm, normals p99 "
      "%.2f deg\n",
      c4d, st.index_bytes, st.position_bytes, st.motion_bytes, st.max_error, st.normal_p99);
  std::printf("  model.glb      %12zu B\n", glb);
  vertex_path(seq, model, draws);
  if (argc > 6 && std::string(argv[6]) == "vertex") return 0;

  t0 = clock_type::now();
  PatchOptions po;
  po.base_triangles = base;
  const PatchMesh pm = build_patch_mesh(seq, po);
  const double bake_s = std::chrono::duration<double>(clock_type::now() - t0).count();
  // The classical scene: the same displaced patches, tessellated on the CPU to about the number of
  // triangles the GPU tessellator generates at `level` (GL's nested rings give more than level²).
  RenderOptions probe_o;
  probe_o.width = probe_o.height = 64;
  std::uint64_t shown = 0;
  {
    OffscreenRenderer probe(probe_o);
    std::printf("Table II  %s\n", probe.description().c_str());
    probe.patches().load(pm);
    PatchDrawState s;
    s.level = level;
    s.width = s.height = 64;
    shown = probe.patches().count_triangles(s);
  }
  const int cpu_level =
      std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(shown) / pm.triangles.size()))));
  const MeshSequence classical = tessellate_patches(pm, cpu_level);
  std::printf(
      "  base %zu triangles, maps %d steps/edge (bake %.2f s, %zu samples missed); classical = CPU lattice level %d\n",
      pm.triangles.size(), po.grid, bake_s, pm.missed, cpu_level);
  table2(classical, pm, level, 800, 600, draws);
  table2(classical, pm, level, 64, 64, draws);
  return 0;
}
