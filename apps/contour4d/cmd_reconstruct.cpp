// `contour4d reconstruct`: contours in, 4D mesh out (the main job).
#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "cli.h"
#include "input_options.h"
#include "contour4d/core/errors.h"
#include "contour4d/io/input.h"
#include "contour4d/io/mesh_output.h"
#include "contour4d/io/output_dir.h"
#include "contour4d/metrics/result_check.h"
#include "contour4d/motion/reconstruct4d.h"
#include "progress.h"

namespace c4d::cli {
namespace {

struct ReconstructArgs {
  std::string input;
  std::string output;
  int frame = -1;
  InputOptions in;
  double edge = SurfaceOptions{}.edge;
  std::string cap = "rounded";
  double cap_fill = SurfaceOptions{}.cap_max_fill;
  std::string method = "rbf-project";
  int threads = 0;
  double pin_spacing = MorphOptions{}.pin_spacing;
  bool vertical = false;
  bool biharmonic = false;
  bool fast = false;
  bool no_rows = false;
  std::string tiling = "bands";
  std::string remesher = "auto";
  std::string keep_failed;
  double volume_tolerance = ResultCheckOptions{}.volume_tolerance;
};

nlohmann::json connections_json(const std::vector<Connection>& cs) {
  nlohmann::json a = nlohmann::json::array();
  for (const Connection& c : cs)
    a.push_back({{"frame_a", c.frame_a}, {"slice_a", c.slice_a}, {"contour_a", c.contour_a}, {"frame_b", c.frame_b},
                 {"slice_b", c.slice_b}, {"contour_b", c.contour_b}, {"similarity", c.similarity},
                 {"kept_by_threshold", c.kept_by_threshold}});
  return a;
}

nlohmann::json repairs_json(const std::vector<ContourRepair>& repairs) {
  nlohmann::json a = nlohmann::json::array();
  for (const ContourRepair& r : repairs)
    a.push_back({{"frame", r.frame}, {"slice", r.slice}, {"contour", r.contour}, {"kind", r.kind}, {"detail", r.detail},
                 {"moved_mm", r.moved_mm}});
  return a;
}

nlohmann::json surface_json(const SurfaceReport& r) {
  return {{"contours", r.contours},   {"caps", r.caps},         {"branchings", r.branchings},
          {"vertices", r.vertices},   {"triangles", r.triangles}, {"closed", r.closed},
          {"self_intersects", r.self_intersections_checked ? nlohmann::json(r.self_intersects) : nlohmann::json()}, {"euler", r.euler}, {"components", r.components},
          {"volume_mm3", r.volume},   {"warnings", r.warnings},  {"connections", connections_json(r.connections)}};
}

// The contours each output frame was built from (one structure; --frame: that frame only), for the
// volume comparison of the output gate.
Sequence checked_contours(const Sequence& seq, const std::string& label, int frame) {
  Sequence sub = label.empty() ? seq : select_label(seq, label);
  if (frame >= 0) sub.frames = {sub.frames[static_cast<std::size_t>(frame)]};
  return sub;
}

nlohmann::json checks_json(const ResultCheck& check) {
  nlohmann::json a = nlohmann::json::array();
  for (const FrameCheck& c : check.frames)
    a.push_back({{"frame", c.frame}, {"ok", c.ok()}, {"volume_mm3", c.volume}, {"simpson_volume_mm3", c.simpson_volume},
                 {"crossing_triangle_pairs", c.self_intersections}, {"faults", c.faults}});
  return a;
}

// Every frame's output checks (the contours of --frame's frame only).
ResultCheck run_checks(const ReconstructArgs& a, const Sequence& seq, const std::string& label, bool closed,
                       const MeshSequence& result) {
  ResultCheckOptions opt;
  opt.closed = closed;
  opt.volume_tolerance = a.volume_tolerance;
  ResultCheck check = check_result(result, checked_contours(seq, label, a.frame), opt);
  if (a.frame >= 0)
    for (FrameCheck& c : check.frames) c.frame = a.frame;
  return check;
}

// The output gate: every frame checked before anything is written. A failing result is written only
// where --keep-failed asks, marked FAILED, and the run ends with ErrorCode::InvalidResult.
void check_before_writing(const ReconstructArgs& a, const ResultCheck& check, const MeshSequence& result,
                          nlohmann::json& report) {
  report["checks"] = {{"ok", check.ok()}, {"volume_tolerance", a.volume_tolerance}, {"frames", checks_json(check)}};
  if (check.ok()) return;
  std::string hint = fmt::format("nothing was written to {}", a.output);
  if (!a.keep_failed.empty()) {
    OutputDir failed(a.keep_failed);
    report["FAILED"] = check.summary();
    write_mesh_sequence(failed, result, fmt::format("FAILED contour4d reconstruct {}", a.input));
    failed.write("report.json", report.dump(2) + "\n");
    failed.write("FAILED.txt", "This result FAILED its checks and is kept only for debugging:\n" + check.summary() + "\n");
    failed.commit();
    hint += fmt::format("; the failed result is in {} (marked FAILED)", a.keep_failed);
  } else {
    hint += "; --keep-failed DIR writes the failed result there for debugging";
  }
  throw SolverError(ErrorCode::InvalidResult, Location{a.input},
                    "the reconstruction failed its checks: " + check.summary(), hint);
}

// The default morph failed its checks: it can fold a frame onto a neighbouring sheet (a myocardium's two
// walls). Every frame is then carried from frame 0 on its own, and that result replaces the morph's if it
// passes the checks.
void carry_instead(const ReconstructArgs& a, const Sequence& seq, const Reconstruct4DOptions& opt, bool closed,
                   MeshSequence& result, Reconstruct4DReport& rr, ResultCheck& check, nlohmann::json& report) {
  std::cout << fmt::format("  the frame-after-frame morph failed its checks ({}); carrying every frame from frame 0 "
                           "instead\n", check.summary()) << std::flush;
  Reconstruct4DOptions carry = opt;
  carry.all_frames = AllFramesMethod::Carry;
  Reconstruct4DReport rc;
  MeshSequence other = reconstruct_4d(seq, carry, &rc);
  ResultCheck other_check = run_checks(a, seq, opt.surface.label, closed, other);
  report["all_frames_fallback"] = {{"morph_fault", check.summary()}, {"carry_ok", other_check.ok()}};
  if (!other_check.ok()) return;
  result = std::move(other);
  rr = std::move(rc);
  check = std::move(other_check);
  report["options"]["method"] = "carry";
}

// The input summary: what was read, the notes of the reader and the first repairs (flushed before the work).
void print_input_summary(const ReconstructArgs& a, const InputResult& read) {
  std::cout << fmt::format("contour4d reconstruct: {} ({}), {} frames\n", a.input, read.format, read.sequence.frames.size());
  for (const std::string& n : read.notes) std::cout << "  " << n << "\n";
  for (std::size_t k = 0; k < read.repairs.size() && k < 10; ++k) {
    const ContourRepair& r = read.repairs[k];
    std::cout << fmt::format("    repaired frame {}, slice {}, contour {}: {}\n", r.frame, r.slice, r.contour, r.detail);
  }
  if (read.repairs.size() > 10) std::cout << fmt::format("    ... and {} more\n", read.repairs.size() - 10);
  std::cout << std::flush;
}

int run_reconstruct(const ReconstructArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, a.threads);
  const InputResult read = read_contours(a.input, a.in);
  const Sequence& seq = read.sequence;
  OutputDir out(a.output);  // checks the destination is writable before the work starts

  Reconstruct4DOptions opt;
  // Label images name contours by the label's name (or number), which extraction already selected.
  opt.surface.label = read.format == "label-image" ? std::string() : a.in.label;
  opt.surface.edge = a.edge;
  // The paper's tiling (--tiling delaunay) tiles every band, so it goes with the remeshed bands, not rows.
  opt.surface.rows = !a.no_rows && a.tiling != "delaunay";
  opt.frame0_rows = a.fast && opt.surface.rows;
  opt.surface.tiling = a.tiling == "delaunay" ? Tiling::Delaunay : Tiling::Bands;
  // auto: the library's defaults (ours with rows and for a 4D run's frame 0, Reconstruct4DOptions::frame0_remesher;
  // CGAL's for a single frame's remeshed bands, SurfaceOptions::remesher).
  if (a.remesher != "auto")
    opt.surface.remesher = opt.surface.rows_remesher = opt.frame0_remesher =
        a.remesher == "fast" ? RemeshEngine::Fast : RemeshEngine::Cgal;
  opt.surface.caps = a.cap == "flat" ? CapStyle::Flat : (a.cap == "open" ? CapStyle::Open : CapStyle::Rounded);
  opt.surface.cap_max_fill = a.cap_fill;
  opt.all_frames = a.method == "carry" ? AllFramesMethod::Carry : AllFramesMethod::Morph;
  opt.morph.method = a.method == "rbf" ? MorphMethod::Rbf : MorphMethod::RbfProject;
  opt.morph.pin_spacing = a.pin_spacing;
  opt.morph.vertical_deformation = a.vertical;
  opt.morph.biharmonic = a.biharmonic;
  ProgressBar bar;
  opt.progress = [&bar](const char* stage, int done, int total) { bar.update(stage, done, total); };

  print_input_summary(a, read);

  nlohmann::json report = {
      {"tool", "contour4d 0.1.0"},
      {"input", a.input},
      {"input_format", read.format},
      {"units", "mm"},
      {"space", seq.space},
      {"stack_normal", {seq.normal.x, seq.normal.y, seq.normal.z}},
      {"frame_times", {{"source", read.timing}, {"known", read.timing != "unknown"}}},
      {"repairs", repairs_json(read.repairs)},
      {"options",
       {{"edge_mm", a.edge}, {"cap", a.cap}, {"cap_fill", a.cap_fill}, {"method", a.method}, {"threshold", opt.surface.threshold},
        {"fast", a.fast}, {"no_rows", a.no_rows}, {"tiling", a.tiling}, {"remesher", a.remesher}, {"pin_spacing", a.pin_spacing},
        {"vertical_deformation", a.vertical},
        {"biharmonic", a.biharmonic}}},
  };
  MeshSequence result;
  ResultCheck check;
  const bool closed = opt.surface.caps != CapStyle::Open;
  if (a.frame >= 0) {
    if (a.frame >= static_cast<int>(seq.frames.size()))
      throw InvalidInput(ErrorCode::Usage, Location{a.input},
                         fmt::format("--frame {} is out of range: the input has {} frames", a.frame, seq.frames.size()));
    SurfaceReport sr;
    const TriangleMesh mesh = reconstruct_frame(seq, a.frame, opt.surface, &sr);
    result.triangles = mesh.triangles;
    result.positions = {mesh.positions};
    result.times_ms = {seq.frames[static_cast<std::size_t>(a.frame)].time_ms};
    report["frames"] = {{{"frame", a.frame}, {"surface", surface_json(sr)}}};
    check = run_checks(a, seq, opt.surface.label, closed, result);
  } else {
    Reconstruct4DReport rr;
    result = reconstruct_4d(seq, opt, &rr);
    check = run_checks(a, seq, opt.surface.label, closed, result);
    if (!check.ok() && a.method == "rbf-project") carry_instead(a, seq, opt, closed, result, rr, check, report);
    nlohmann::json frames = nlohmann::json::array();
    for (std::size_t f = 0; f < result.positions.size(); ++f) {
      const MorphFrameReport& mf = rr.morph.frames[f];
      frames.push_back({{"frame", f},
                        {"time_ms", result.times_ms[f]},
                        {"volume_mm3", signed_volume(result.frame(f))},
                        {"matched_contours", mf.matched},
                        {"rbf_sources", mf.sources},
                        {"angle_repair_moves", mf.angle_repairs},
                        {"sliding_contour_vertices", mf.sliding},
                        {"plane_snapped_vertices", mf.plane_snapped},
                        {"redone", mf.redone},
                        {"biharmonic", mf.biharmonic},
                        {"contour_fit",
                         {{"moved_vertices", mf.fit_moved},
                          {"max_distance_before_mm", mf.fit_max_before},
                          {"max_distance_after_mm", mf.fit_max_after}}},
                        {"intersecting_pairs_after_untangling", mf.intersecting_pairs},
                        {"projection_mean_mm", mf.projection_mean},
                        {"projection_max_mm", mf.projection_max},
                        {"surface", mf.biharmonic ? nlohmann::json() : surface_json(rr.surfaces[f])}});
    }
    report["frames"] = frames;
    nlohmann::json events = nlohmann::json::array();
    for (const SliceEvent& e : rr.morph.events)
      events.push_back({{"frame", e.frame}, {"slice", e.slice}, {"kind", e.kind}, {"before", e.before}, {"after", e.after}});
    report["topology_events"] = events;
    nlohmann::json subs = nlohmann::json::array();
    for (const SubMeshLifetime& s : rr.morph.submeshes)
      subs.push_back({{"slice_below", s.slice_below}, {"slice_above", s.slice_above}, {"first_frame", s.first_frame},
                      {"last_frame", s.last_frame}, {"contours_below", s.contours_below},
                      {"contours_above", s.contours_above}});
    report["submeshes"] = subs;
    std::cout << fmt::format("  topology events (contours split/merge/appear/vanish between frames): {}\n",
                             rr.morph.events.size());
    std::cout << "  sub-meshes (Miara et al. Fig. 14): slices below-above, frames, contours\n";
    for (const SubMeshLifetime& s : rr.morph.submeshes)
      std::cout << fmt::format("    {:>3}-{:<3} frames {:>3}..{:<3} {}:{}\n", s.slice_below, s.slice_above, s.first_frame,
                               s.last_frame, s.contours_below, s.contours_above);
  }
  bar.finish();
  check_before_writing(a, check, result, report);

  std::vector<double> volumes;
  for (std::size_t f = 0; f < result.positions.size(); ++f) volumes.push_back(signed_volume(result.frame(f)));
  const double edv = *std::max_element(volumes.begin(), volumes.end());
  const double esv = *std::min_element(volumes.begin(), volumes.end());
  report["correspondence"] = true;
  report["vertices"] = result.positions.front().size();
  report["triangles"] = result.triangles.size();
  report["edv_ml"] = edv / 1000.0;
  report["esv_ml"] = esv / 1000.0;
  report["ef_percent"] = edv > 0 ? 100.0 * (edv - esv) / edv : 0.0;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // No run time in report.json: the same input must give byte-identical outputs (it is printed below).

  write_mesh_sequence(out, result, fmt::format("contour4d reconstruct {}", a.input));
  out.write("report.json", report.dump(2) + "\n");
  out.commit();

  std::cout << fmt::format("  mesh: {} vertices, {} triangles, the same in all {} frames\n", result.positions.front().size(),
                           result.triangles.size(), result.positions.size());
  std::cout << "  volume per frame (ml):";
  for (double v : volumes) std::cout << fmt::format(" {:.1f}", v / 1000.0);
  std::cout << "\n";
  if (volumes.size() > 1)
    std::cout << fmt::format("  EDV {:.1f} ml, ESV {:.1f} ml, EF {:.1f} %\n", edv / 1000, esv / 1000, 100 * (edv - esv) / edv);
  std::cout << fmt::format("  done in {:.2f} s. Output: {}/mesh.pvd (open in ParaView), frames/, report.json\n", seconds,
                           a.output);
  return 0;
}

}  // namespace

void add_reconstruct_command(CLI::App& root, std::vector<Command>& commands) {
  auto args = std::make_shared<ReconstructArgs>();
  CLI::App* app = root.add_subcommand(
      "reconstruct", "Contours in, 4D mesh out: one watertight mesh per frame with 1-to-1 vertex correspondence");
  app->footer(
      "Examples:\n"
      "  contour4d reconstruct ../shared/data/bivme-patient1/guidepoints -o out/lv\n"
      "  contour4d reconstruct contours.json --frame 0 -o out/frame0      # one frame only\n"
      "  contour4d reconstruct contours.json --label lv-endo --edge 0.8 -o out/lv     # finer mesh (default edge 1 mm)\n"
      "  contour4d reconstruct contours.json --cap open -o out/cfd        # open ends for CFD inlets\n"
      "  contour4d reconstruct ../shared/data/sunnybrook-SC-HF-I-1 -o out/sb   # DICOM-referenced contours\n"
      "  contour4d reconstruct seg.nii.gz --labels acdc --label lv -o out/lv  # label masks (nnU-Net, Slicer)\n"
      "  contour4d reconstruct seg.nii.gz --labels acdc --label myo --method carry --cycle-ms 800 -o out/myo\n"
      "                                      # a myocardial wall, every frame on its own; frames 800/N ms apart\n"
      "  contour4d reconstruct contours.json --strict -o out/lv      # refuse flawed contours instead of repairing them\n"
      "INPUT is a contour JSON file, a biv-me GPFile folder, a Sunnybrook folder or label image(s). Outputs: OUTDIR/mesh.pvd (open in ParaView),\n"
      "OUTDIR/frames/frame_NNN.{vtp,obj}, OUTDIR/report.json. Coordinates in mm, in the input's patient space.\n"
      "Every frame is checked before anything is written; a frame that fails exits with code 26, naming it.");
  app->add_option("INPUT", args->input, "contour JSON file or GPFile folder")->required();
  app->add_option("-o,--output", args->output, "output folder (replaced atomically)")->required();
  app->add_option("--frame", args->frame, "reconstruct this frame only (0-based)");
  add_input_options(app, args->in);
  app->add_option("--edge", args->edge, "target edge length in mm")->capture_default_str()->check(CLI::Range(0.05, 50.0));
  app->add_option("--cap", args->cap, "end caps: rounded, flat or open")
      ->capture_default_str()
      ->check(CLI::IsMember({"rounded", "flat", "open"}));
  app->add_option("--cap-fill", args->cap_fill,
                  "rounded caps on ends that keep their size are filled towards the trend of the last two sections, "
                  "up to this fraction of the half-spacing prism, and walls into closing ends follow a smooth "
                  "section-area curve (0: plain faired domes)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  app->add_option("--method", args->method,
                  "all frames: carry (every frame on its own, in parallel: frame 0's mesh onto the frame's own surface), "
                  "rbf-project (frame after frame: RBF + projection on each frame's surface) or rbf (the paper's RBF only)")
      ->capture_default_str()
      ->check(CLI::IsMember({"carry", "rbf-project", "rbf"}));
  app->add_option("--pin-spacing", args->pin_spacing,
                  "0 (default): later frames fit their contours through each frame's own surface; > 0: also hold "
                  "frame-0 contour vertices on later contours, at least this x the median edge apart (exact "
                  "contour vertices, worse triangles where contours shrink)")
      ->capture_default_str();
  app->add_flag("--vertical-deformation", args->vertical,
                "where a slice's contours split or merge between frames, first apply Lim et al.'s sine-shaped "
                "vertical deformation centred on the ridge (eq. 10, Table 1), then match and deform");
  app->add_flag("--biharmonic", args->biharmonic,
                "frames whose contours all match the previous frame's one-to-one follow them by a biharmonic "
                "displacement of the previous mesh (one sparse solve, no relaxation), unless that leaves the mesh over "
                "0.2 mm from a contour, an angle below 25 deg, fewer than 85% of angles in 40-80 deg or crossing "
                "triangles; other frames as usual. Opt-in: no faster overall (frames that fail the guard are done twice), "
                "smaller smallest angles");
  app->add_option("--tiling", args->tiling,
                  "surface between slices: bands (default: optimal bands, bridges at branchings) or delaunay (Lim et "
                  "al.'s constrained Delaunay of the projected slices with chordal-axis lifting points)")
      ->check(CLI::IsMember({"bands", "delaunay"}))
      ->capture_default_str();
  app->add_option("--remesher", args->remesher,
                  "isotropic remeshing of the surface: auto (default: ours with interpolated rows and for frame 0 of "
                  "all frames, CGAL's for one frame with --no-rows), cgal (CGAL's) or fast (ours, the same algorithm "
                  "on flat arrays: 1.3-2x faster per frame; for one frame with --no-rows slab accuracy within about 10% "
                  "of cgal's either way and smallest angles not guaranteed)")
      ->check(CLI::IsMember({"auto", "cgal", "fast"}))
      ->capture_default_str();
  app->add_flag("--fast", args->fast,
               "all frames: frame 0 by interpolated rows too (the default one-frame surface) instead of remeshed "
               "bands: about 1 s less per run, but the mesh carried through the cycle is less even (left heart ES "
               "86.6 against 95.4% of angles in 40-80 deg)");
  app->add_flag("--no-rows", args->no_rows,
                "remesh every band between slices (CGAL isotropic remeshing) instead of interpolated rows one edge "
                "apart: 1.9-3.2x slower per frame, slightly more even triangles (left heart ES 96.5 against 92.2% of "
                "angles in 40-80 deg), as close to the true surface (ES 0.018 against 0.017 mm mean)");
  app->add_option("--threads", args->threads, "worker threads (0: all cores); output does not depend on it");
  app->add_option("--keep-failed", args->keep_failed,
                  "every frame is checked before writing (closed, manifold, outward, no crossing triangles, volume near "
                  "Simpson's discs); a failing result exits with code 26 and writes nothing, or with this option writes "
                  "it to this folder marked FAILED, for debugging");
  app->add_option("--volume-tolerance", args->volume_tolerance,
                  "output check: largest accepted |mesh volume / Simpson's discs volume - 1| per frame")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  commands.push_back({app, [args] { return run_reconstruct(*args); }});
}

}  // namespace c4d::cli
