// `contour4d view`: the interactive playback window (GLFW), or with --snapshot the same pipeline
// offscreen through EGL. All drawing is in the contour4d_render library.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include <fmt/core.h>

#include "cli.h"
#include "contour4d/core/errors.h"
#include "contour4d/pipeline/input.h"
#include "contour4d/temporal/displacement_map.h"
#include "contour4d/temporal/sequence.h"
#ifdef C4D_HAVE_RENDER
#include "contour4d/render/renderer.h"
#include "contour4d/render/viewer.h"
#endif

namespace c4d::cli {
namespace {

struct ViewArgs {
  std::string input;
  std::string contours;
  std::string snapshot;
  std::string size = "1280x800";
  std::string interp = "linear";
  int level = 6;
  int grid = 8;
  std::size_t base_triangles = 2000;
  bool wireframe = false;
  bool section = false;
  bool no_maps = false;
  bool tessellated = false;
  bool no_hud = false;
  int section_slice = -1;
  double time_ms = 0.0;
  double yaw = -65.0;
  double pitch = 20.0;
  double zoom = 1.0;
  int seconds = 0;
};

int run_view(const ViewArgs& a) {
#ifndef C4D_HAVE_RENDER
  (void)a;
  throw Error(ErrorCode::NotImplemented, {}, "this contour4d was built without OpenGL",
              "install libegl-dev, libgl-dev and libglfw3-dev (scripts/setup.sh) and rebuild");
#else
  const std::filesystem::path in(a.input);
  const MeshSequence seq = load_mesh_sequence(in);
  PatchOptions po;
  po.grid = a.grid;
  po.base_triangles = a.base_triangles;
  // Input contours for the section view: --contours, else contours.json beside or above the input.
  std::unique_ptr<Sequence> contours;
  std::filesystem::path cpath = a.contours;
  if (cpath.empty()) {
    const std::filesystem::path dir = std::filesystem::is_directory(in) ? in : in.parent_path();
    for (const auto& c : {dir / "contours.json", dir.parent_path() / "contours.json"})
      if (std::filesystem::is_regular_file(c)) {
        cpath = c;
        break;
      }
  }
  if (!cpath.empty()) {
    contours = std::make_unique<Sequence>(read_contours(cpath).sequence);
    std::cout << "contours: " << cpath.string() << "\n";
  }
  PatchDrawState st;
  st.level = a.level;
  st.wireframe = a.wireframe;
  st.section = a.section;
  st.section_slice = a.section_slice;
  st.displaced = !a.no_maps;
  st.camera.yaw_deg = a.yaw;
  st.camera.pitch_deg = a.pitch;
  st.camera.zoom = a.zoom;
  st.interpolation = a.interp == "catmull-rom" ? TimeInterpolation::CatmullRomPeriodic : TimeInterpolation::Linear;
  st.t_ms = seq.times_ms.front() + a.time_ms;
  st.mesh = !a.tessellated;
  st.hud = !a.no_hud;
  st.hud_footer = kViewerKeys;
  int w = 0, h = 0;
  if (std::sscanf(a.size.c_str(), "%dx%d", &w, &h) != 2 || w <= 0 || h <= 0)
    throw InvalidInput(ErrorCode::Usage, {}, "bad --size '" + a.size + "'", "use WIDTHxHEIGHT, e.g. 1280x800");
  if (!a.snapshot.empty()) {
    RenderOptions ro;
    ro.width = w;
    ro.height = h;
    OffscreenRenderer r(ro);
    r.patches().load_mesh(seq);
    if (a.tessellated) {
      const PatchMesh pm = build_patch_mesh(seq, po);
      std::cout << fmt::format(
          "base mesh {} triangles ({} fine), {} frames, displacement maps {}x{} lattice, max |d| {:.2f} mm, {} "
          "samples missed the surface\n",
          pm.triangles.size(), seq.triangles.size(), pm.positions.size(), a.grid, a.grid, pm.max_abs_displacement,
          pm.missed);
      r.patches().load(pm);
    }
    if (contours) r.patches().set_contours(*contours);
    const std::uint64_t tris = r.patches().count_triangles([&] {
      PatchDrawState s = st;
      s.width = w;
      s.height = h;
      return s;
    }());
    r.draw_patches(st);
    write_png(a.snapshot, r.read_image());
    std::cout << fmt::format("wrote {} ({}x{}, {} triangles{}; {})\n", a.snapshot, w, h, tris,
                             a.tessellated ? fmt::format(" at level {}", a.level) : std::string(), r.description());
    return 0;
  }
  ViewerOptions vo;
  vo.width = w;
  vo.height = h;
  vo.initial = st;
  vo.max_seconds = a.seconds;
  vo.title = "contour4d view " + in.filename().string();
  vo.patches = po;
  run_viewer(seq, contours.get(), vo);
  return 0;
#endif
}

}  // namespace

void add_view_command(CLI::App& root, std::vector<Command>& commands) {
  CLI::App* app = root.add_subcommand(
      "view",
      "Play a 4D mesh in a window (OpenGL 4.3, GLFW), as `contour4d render` draws it: frame 0 and every\n"
      "frame's displacement are uploaded once and blended on the GPU; per frame only the time is sent.\n"
      "On screen: time, frame, volume, the volume curve of the cycle and the keys. Keys: space\n"
      "play/pause, left/right one frame, +/- speed, T tessellated patches (Miara et al.: base mesh +\n"
      "displacement maps; [ ] level, D maps on/off), H overlay, W wireframe, S section plane with the\n"
      "input contours (, . move it by one slice), I linear/Catmull-Rom, R reset view, Q quit; drag\n"
      "orbits, wheel zooms. --snapshot draws one image headless (EGL).");
  app->footer(
      "Examples:\n"
      "  contour4d view out                         # OUTDIR of `contour4d reconstruct`\n"
      "  contour4d view out/model.c4d --contours lv.json --section\n"
      "  contour4d view out --snapshot view.png --time 300   # no display needed\n"
      "  contour4d view out --snapshot tess.png --tessellated --wireframe --level 4\n");
  auto args = std::make_shared<ViewArgs>();
  app->add_option("INPUT", args->input, "output folder of a reconstruction or a model.c4d")->required();
  app->add_option("--contours", args->contours,
                  "input contours for the section view (default: contours.json beside INPUT)");
  app->add_option("--snapshot", args->snapshot, "draw one image offscreen to this PNG and exit (no window)");
  app->add_option("--size", args->size, "window or image size WIDTHxHEIGHT")->default_val("1280x800");
  app->add_option("--level", args->level, "tessellation level (1..64; about 1.5·level² triangles per base triangle)")
      ->default_val(6)
      ->check(CLI::Range(1, 64));
  app->add_option("--grid", args->grid, "displacement map lattice steps per base edge")
      ->default_val(8)
      ->check(CLI::Range(1, 64));
  app->add_option("--base-triangles", args->base_triangles, "triangles of the coarse base mesh")->default_val(2000);
  app->add_option("--interp", args->interp, "interpolation between frames")
      ->check(CLI::IsMember({"linear", "catmull-rom"}))
      ->default_val("linear");
  app->add_flag("--wireframe", args->wireframe, "start with the tessellated edges drawn");
  app->add_flag("--section", args->section, "start with the section plane on");
  app->add_option("--section-slice", args->section_slice, "slice (0-based, sorted) of the section plane; -1: middle")
      ->default_val(-1);
  app->add_flag("--tessellated", args->tessellated, "start with the tessellated patches (key T)");
  app->add_flag("--no-maps", args->no_maps, "with the patches: start without the displacement maps (PN patches)");
  app->add_flag("--no-hud", args->no_hud, "start without the on-screen information (key H)");
  app->add_option("--time", args->time_ms, "start time after the first frame (ms)")->default_val(0.0);
  app->add_option("--yaw", args->yaw, "camera azimuth about +z (degrees)")->default_val(-65.0);
  app->add_option("--pitch", args->pitch, "camera elevation (degrees)")->default_val(20.0);
  app->add_option("--zoom", args->zoom, "camera distance factor (< 1: closer)")
      ->default_val(1.0)
      ->check(CLI::PositiveNumber);
  app->add_option("--seconds", args->seconds, "close the window after N seconds (0: never)")->default_val(0);
  commands.push_back({app, [args] { return run_view(*args); }});
}

}  // namespace c4d::cli
