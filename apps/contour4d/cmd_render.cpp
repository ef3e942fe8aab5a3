// `contour4d render`: headless PNG frames of a 4D mesh, and the classical-vs-compact playback
// benchmark (Miara et al. Table II). Needs the contour4d_render library (EGL + OpenGL).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include <fmt/core.h>

#include "cli.h"
#include "contour4d/core/errors.h"
#include "contour4d/temporal/model_c4d.h"
#include "contour4d/io/output_dir.h"
#include "contour4d/temporal/compact.h"
#include "contour4d/temporal/displacement_map.h"
#include "contour4d/temporal/interpolate.h"
#include "contour4d/temporal/sequence.h"
#ifdef C4D_HAVE_RENDER
#include "contour4d/render/renderer.h"
#endif

namespace c4d::cli {
namespace {

struct RenderArgs {
  std::string input;
  std::string output;
  std::size_t frames = 0;
  std::string size = "640x480";
  std::string interp = "linear";
  bool classical = false;
  bool perspective = false;
  int bench = 0;
  bool tessellated = false;
  int level = 6;
  int grid = 8;
  std::size_t base_triangles = 2000;
  bool wireframe = false;
};

int run_render(const RenderArgs& a) {
#ifndef C4D_HAVE_RENDER
  (void)a;
  throw Error(ErrorCode::NotImplemented, {}, "this contour4d was built without EGL/OpenGL",
              "install libegl-dev and libgl-dev (scripts/setup.sh) and rebuild");
#else
  const std::filesystem::path in(a.input);
  CompactModel model;
  MeshSequence seq;
  if (std::filesystem::is_regular_file(in)) {
    model = read_model_c4d(in);
    seq = decode_model_c4d(model, in.string());
  } else {
    seq = load_mesh_sequence(in);
    if (!a.tessellated || a.bench > 0) model = compact_encode(seq);
  }
  RenderOptions opt;
  if (std::sscanf(a.size.c_str(), "%dx%d", &opt.width, &opt.height) != 2)
    throw InvalidInput(ErrorCode::Usage, {}, "bad --size '" + a.size + "'", "use WIDTHxHEIGHT, e.g. 800x600");
  opt.perspective = a.perspective;
  opt.interpolation = a.interp == "catmull-rom"
                          ? TimeInterpolation::CatmullRomPeriodic
                          : (a.interp == "step" ? TimeInterpolation::Step : TimeInterpolation::Linear);
  OffscreenRenderer r(opt);
  std::cout << "renderer: " << r.description() << "\n";
  const std::size_t nf = seq.positions.size();
  if (a.bench > 0) {
    using clock = std::chrono::steady_clock;
    r.load_classical(seq);
    r.draw_classical(0);
    r.finish();
    std::size_t bytes_c = 0;
    auto t0 = clock::now();
    for (int i = 0; i < a.bench; ++i) bytes_c += r.draw_classical(static_cast<std::size_t>(i) % nf);
    r.finish();
    const double ms_c = std::chrono::duration<double, std::milli>(clock::now() - t0).count() / a.bench;
    r.load_compact(model);
    r.draw_compact(0);
    r.finish();
    std::size_t bytes_k = 0;
    t0 = clock::now();
    for (int i = 0; i < a.bench; ++i) bytes_k += r.draw_compact(seq.times_ms[static_cast<std::size_t>(i) % nf]);
    r.finish();
    const double ms_k = std::chrono::duration<double, std::milli>(clock::now() - t0).count() / a.bench;
    std::cout << fmt::format("{} triangles, {} frames drawn per path\n", seq.triangles.size(), a.bench)
              << fmt::format("  classical: {:.2f} ms/frame, {} bytes uploaded/frame\n", ms_c, bytes_c / a.bench)
              << fmt::format("  compact:   {:.2f} ms/frame, {} bytes uploaded/frame\n", ms_k, bytes_k / a.bench)
              << fmt::format("  speed-up {:.2f}x, {:.0f}x fewer bytes per frame\n", ms_c / ms_k,
                             static_cast<double>(bytes_c) / static_cast<double>(std::max<std::size_t>(bytes_k, 1)));
    return 0;
  }
  if (a.output.empty()) throw InvalidInput(ErrorCode::Usage, {}, "no output folder", "pass -o DIR");
  const std::size_t count = a.frames > 0 ? a.frames : nf;
  if (a.tessellated) {  // the viewer's pipeline: base mesh + displacement maps, tessellation shaders
    PatchOptions po;
    po.grid = a.grid;
    po.base_triangles = a.base_triangles;
    const PatchMesh pm = build_patch_mesh(seq, po);
    if (a.classical) {  // the same displaced patches tessellated on the CPU, drawn as plain meshes
      r.load_classical(tessellate_patches(pm, a.level));
    } else {
      r.patches().load(pm);
    }
    PatchDrawState st;
    st.level = a.level;
    st.wireframe = a.wireframe;
    st.interpolation = opt.interpolation;
    OutputDir out(a.output);
    const double period = cycle_period(seq.times_ms);
    for (std::size_t i = 0; i < count; ++i) {
      st.t_ms = a.frames > 0 ? seq.times_ms.front() + period * static_cast<double>(i) / static_cast<double>(count)
                             : seq.times_ms[i];
      if (a.classical)
        r.draw_classical(i % nf);
      else
        r.draw_patches(st);
      write_png(out.path(fmt::format("frame_{:03d}.png", i)), r.read_image());
    }
    out.commit();
    std::cout << fmt::format("wrote {} tessellated frames ({}x{}, base {} triangles, level {}) to {}\n", count,
                             opt.width, opt.height, pm.triangles.size(), a.level, a.output);
    return 0;
  }
  // Both paths draw the same times: the stored frames, or `count` times evenly over the cycle, which the
  // classical path interpolates on the CPU (the compact path on the GPU, with the same weights).
  const double period = cycle_period(seq.times_ms);
  std::vector<double> times;
  for (std::size_t i = 0; i < count; ++i)
    times.push_back(a.frames > 0 ? seq.times_ms.front() + period * static_cast<double>(i) / static_cast<double>(count)
                                 : seq.times_ms[i]);
  if (a.classical && a.frames > 0) {
    MeshSequence drawn;
    drawn.triangles = seq.triangles;
    drawn.times_ms = times;
    for (double t : times) drawn.positions.push_back(interpolate_positions(seq, t, opt.interpolation));
    r.load_classical(drawn, seq);
  } else if (a.classical) {
    r.load_classical(seq);
  } else {
    r.load_compact(model);
  }
  OutputDir out(a.output);
  for (std::size_t i = 0; i < count; ++i) {
    if (a.classical)
      r.draw_classical(i);
    else
      r.draw_compact(times[i]);
    write_png(out.path(fmt::format("frame_{:03d}.png", i)), r.read_image());
  }
  out.commit();
  std::cout << fmt::format("wrote {} frames ({}x{}) to {}\n", count, opt.width, opt.height, a.output);
  return 0;
#endif
}

}  // namespace

void add_render_command(CLI::App& root, std::vector<Command>& commands) {
  CLI::App* app = root.add_subcommand(
      "render",
      "Draw a 4D mesh offscreen (EGL, no window; Mesa's llvmpipe without a GPU) to DIR/frame_000.png...\n"
      "By default the compact path animates on the GPU (data uploaded once, per frame one uniform).\n"
      "--bench N compares it with the classical path (each frame's full mesh uploaded) on the same scene.");
  app->footer(
      "Examples:\n"
      "  contour4d render out -o pngs                      # one PNG per frame\n"
      "  contour4d render out/model.c4d -o movie --frames 100 --interp catmull-rom\n"
      "  contour4d render out -o tess --tessellated --level 6 --wireframe   # what `contour4d view` shows\n"
      "  LIBGL_ALWAYS_SOFTWARE=1 contour4d render out --bench 50   # Table II: ms and bytes per frame\n");
  auto args = std::make_shared<RenderArgs>();
  app->add_option("INPUT", args->input, "output folder of a reconstruction or a model.c4d")->required();
  app->add_option("-o,--output", args->output, "folder for the PNG frames");
  app->add_option("--frames", args->frames, "number of images evenly over the cycle (0: one per frame)")
      ->default_val(0);
  app->add_option("--size", args->size, "image size WIDTHxHEIGHT")->default_val("640x480");
  app->add_option("--interp", args->interp, "interpolation between frames")
      ->check(CLI::IsMember({"linear", "catmull-rom", "step"}))
      ->default_val("linear");
  app->add_flag("--classical", args->classical,
                "upload each frame's mesh instead of the compact GPU path (with --tessellated: the patches "
                "tessellated on the CPU)");
  app->add_flag("--perspective", args->perspective, "perspective camera (default orthographic)");
  app->add_flag("--tessellated", args->tessellated,
                "draw through the viewer's tessellation shaders (base mesh + displacement maps, PN patches)");
  app->add_option("--level", args->level, "tessellation level with --tessellated (1..64)")
      ->default_val(6)
      ->check(CLI::Range(1, 64));
  app->add_option("--grid", args->grid, "displacement map lattice steps per base edge")
      ->default_val(8)
      ->check(CLI::Range(1, 64));
  app->add_option("--base-triangles", args->base_triangles, "triangles of the coarse base mesh")->default_val(2000);
  app->add_flag("--wireframe", args->wireframe, "with --tessellated: draw the tessellated edges");
  app->add_option("--bench", args->bench, "draw N frames with each path and report ms and bytes per frame")
      ->default_val(0);
  commands.push_back({app, [args] { return run_render(*args); }});
}

}  // namespace c4d::cli
