// The end-to-end reconstruction run (reconstruct_run.h): options to Reconstruct4DOptions, one frame or
// all, the fallback to carried frames, the output checks and the report.
#include "contour4d/pipeline/reconstruct_run.h"

#include <algorithm>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "contour4d/core/errors.h"
#include "contour4d/io/mesh_output.h"

namespace c4d {
namespace {

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

nlohmann::json checks_json(const ResultCheck& check) {
  nlohmann::json a = nlohmann::json::array();
  for (const FrameCheck& c : check.frames)
    a.push_back({{"frame", c.frame}, {"ok", c.ok()}, {"volume_mm3", c.volume}, {"simpson_volume_mm3", c.simpson_volume},
                 {"crossing_triangle_pairs", c.self_intersections}, {"faults", c.faults}});
  return a;
}

// The library's options from the user's.
Reconstruct4DOptions library_options(const ReconstructRunOptions& a, const std::string& format) {
  Reconstruct4DOptions opt;
  // Label images name contours by the label's name (or number), which extraction already selected.
  opt.surface.label = format == "label-image" ? std::string() : a.label;
  opt.surface.edge = a.edge;
  // The paper's tiling (delaunay) tiles every band, so it goes with the remeshed bands, not rows.
  opt.surface.rows = !a.no_rows && a.tiling != "delaunay";
  opt.frame0_rows = a.fast && opt.surface.rows;
  opt.surface.tiling = a.tiling == "delaunay" ? Tiling::Delaunay : Tiling::Bands;
  // auto: the library's defaults (Reconstruct4DOptions::frame0_remesher, SurfaceOptions::remesher).
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
  return opt;
}

nlohmann::json start_report(const InputResult& read, const std::string& input, const ReconstructRunOptions& a,
                            const Reconstruct4DOptions& opt) {
  return {
      {"tool", "contour4d 0.1.0"},
      {"input", input},
      {"input_format", read.format},
      {"units", "mm"},
      {"space", read.sequence.space},
      {"stack_normal", {read.sequence.normal.x, read.sequence.normal.y, read.sequence.normal.z}},
      {"frame_times", {{"source", read.timing}, {"known", read.timing != "unknown"}}},
      {"repairs", repairs_json(read.repairs)},
      {"options",
       {{"edge_mm", a.edge}, {"cap", a.cap}, {"cap_fill", a.cap_fill}, {"method", a.method}, {"threshold", opt.surface.threshold},
        {"fast", a.fast}, {"no_rows", a.no_rows}, {"tiling", a.tiling}, {"remesher", a.remesher}, {"pin_spacing", a.pin_spacing},
        {"vertical_deformation", a.vertical},
        {"biharmonic", a.biharmonic}}},
  };
}

// The contours each output frame was built from (one structure; one frame: that frame only), for the
// volume comparison of the output checks.
Sequence checked_contours(const Sequence& seq, const std::string& label, int frame) {
  Sequence sub = label.empty() ? seq : select_label(seq, label);
  if (frame >= 0) sub.frames = {sub.frames[static_cast<std::size_t>(frame)]};
  return sub;
}

// Every frame's output checks (the contours of the one frame only).
ResultCheck run_checks(const ReconstructRunOptions& a, const Sequence& seq, const std::string& label, bool closed,
                       const MeshSequence& result) {
  ResultCheckOptions opt;
  opt.closed = closed;
  opt.volume_tolerance = a.volume_tolerance;
  ResultCheck check = check_result(result, checked_contours(seq, label, a.frame), opt);
  if (a.frame >= 0)
    for (FrameCheck& c : check.frames) c.frame = a.frame;
  return check;
}

void one_frame(const ReconstructRunOptions& a, const Sequence& seq, const Reconstruct4DOptions& opt, ReconstructRun& run,
               nlohmann::json& report) {
  if (a.frame >= static_cast<int>(seq.frames.size()))
    throw InvalidInput(ErrorCode::Usage, Location{run.input},
                       fmt::format("--frame {} is out of range: the input has {} frames", a.frame, seq.frames.size()));
  SurfaceReport sr;
  const TriangleMesh mesh = reconstruct_frame(seq, a.frame, opt.surface, &sr);
  run.result.triangles = mesh.triangles;
  run.result.positions = {mesh.positions};
  run.result.times_ms = {seq.frames[static_cast<std::size_t>(a.frame)].time_ms};
  report["frames"] = {{{"frame", a.frame}, {"surface", surface_json(sr)}}};
}

// The default morph failed its checks: it can fold a frame onto a neighbouring sheet (a myocardium's two
// walls). Every frame is then carried from frame 0 on its own, and that result replaces the morph's if it
// passes the checks.
void carry_instead(const ReconstructRunOptions& a, const Sequence& seq, const Reconstruct4DOptions& opt, bool closed,
                   ReconstructRun& run, Reconstruct4DReport& rr, nlohmann::json& report, const RunMessage& say) {
  if (say)
    say(fmt::format("  the frame-after-frame morph failed its checks ({}); carrying every frame from frame 0 instead",
                    run.check.summary()));
  Reconstruct4DOptions carry = opt;
  carry.all_frames = AllFramesMethod::Carry;
  Reconstruct4DReport rc;
  MeshSequence other = reconstruct_4d(seq, carry, &rc);
  ResultCheck other_check = run_checks(a, seq, opt.surface.label, closed, other);
  report["all_frames_fallback"] = {{"morph_fault", run.check.summary()}, {"carry_ok", other_check.ok()}};
  if (!other_check.ok()) return;
  run.result = std::move(other);
  rr = std::move(rc);
  run.check = std::move(other_check);
  report["options"]["method"] = "carry";
}

nlohmann::json frames_json(const MeshSequence& result, const Reconstruct4DReport& rr) {
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
  return frames;
}

// Topology events and sub-mesh lifetimes (Miara et al. Fig. 14), in the report and for the user.
void describe_topology(const Reconstruct4DReport& rr, nlohmann::json& report, const RunMessage& say) {
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
  if (!say) return;
  say(fmt::format("  topology events (contours split/merge/appear/vanish between frames): {}", rr.morph.events.size()));
  say("  sub-meshes (Miara et al. Fig. 14): slices below-above, frames, contours");
  for (const SubMeshLifetime& s : rr.morph.submeshes)
    say(fmt::format("    {:>3}-{:<3} frames {:>3}..{:<3} {}:{}", s.slice_below, s.slice_above, s.first_frame,
                    s.last_frame, s.contours_below, s.contours_above));
}

void all_frames(const ReconstructRunOptions& a, const Sequence& seq, const Reconstruct4DOptions& opt, bool closed,
                ReconstructRun& run, nlohmann::json& report, const RunMessage& say) {
  Reconstruct4DReport rr;
  run.result = reconstruct_4d(seq, opt, &rr);
  run.check = run_checks(a, seq, opt.surface.label, closed, run.result);
  if (!run.check.ok() && a.method == "rbf-project") carry_instead(a, seq, opt, closed, run, rr, report, say);
  report["frames"] = frames_json(run.result, rr);
  describe_topology(rr, report, say);
}

// The volumes and EDV/ESV/EF of a valid result.
void add_volumes(const MeshSequence& result, nlohmann::json& report) {
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
}

}  // namespace

ReconstructRun reconstruct_run(const InputResult& read, const std::string& input_name, const ReconstructRunOptions& a,
                               const ProgressFn& progress, const RunMessage& say) {
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, a.threads);
  const Sequence& seq = read.sequence;
  Reconstruct4DOptions opt = library_options(a, read.format);
  opt.progress = progress;
  ReconstructRun run;
  run.input = input_name;
  nlohmann::json report = start_report(read, input_name, a, opt);
  const bool closed = opt.surface.caps != CapStyle::Open;
  if (a.frame >= 0) {
    one_frame(a, seq, opt, run, report);
    run.check = run_checks(a, seq, opt.surface.label, closed, run.result);
  } else {
    all_frames(a, seq, opt, closed, run, report, say);
  }
  report["checks"] = {{"ok", run.check.ok()}, {"volume_tolerance", a.volume_tolerance}, {"frames", checks_json(run.check)}};
  if (run.check.ok()) add_volumes(run.result, report);
  // No run time in the report: the same input must give byte-identical outputs.
  run.report = report.dump(2) + "\n";
  return run;
}

void write_run(OutputDir& out, const ReconstructRun& run, const std::string& keep_failed) {
  if (!run.check.ok()) {
    std::string hint = fmt::format("nothing was written to {}", out.destination().string());
    if (!keep_failed.empty()) {
      OutputDir failed(keep_failed);
      nlohmann::json report = nlohmann::json::parse(run.report);
      report["FAILED"] = run.check.summary();
      write_mesh_sequence(failed, run.result, fmt::format("FAILED contour4d reconstruct {}", run.input));
      failed.write("report.json", report.dump(2) + "\n");
      failed.write("FAILED.txt", "This result FAILED its checks and is kept only for debugging:\n" + run.check.summary() + "\n");
      failed.commit();
      hint += fmt::format("; the failed result is in {} (marked FAILED)", keep_failed);
    } else {
      hint += "; --keep-failed DIR writes the failed result there for debugging";
    }
    throw SolverError(ErrorCode::InvalidResult, Location{run.input},
                      "the reconstruction failed its checks: " + run.check.summary(), hint);
  }
  write_mesh_sequence(out, run.result, fmt::format("contour4d reconstruct {}", run.input));
  out.write("report.json", run.report);
  out.commit();
}

}  // namespace c4d
