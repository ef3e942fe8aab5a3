// The end-to-end reconstruction run (reconstruct_run.h): options to Reconstruct4DOptions, one frame or
// all, the fallback to carried frames, the output checks and the report.
#include "contour4d/pipeline/reconstruct_run.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "contour4d/core/errors.h"
#include "contour4d/io/mesh_output.h"
#include "contour4d/metrics/correspondence.h"
#include "contour4d/metrics/quality.h"
#include "contour4d/pipeline/structures.h"

namespace c4d {
namespace {

// report.json keeps its keys in the order written: the summary first, per-frame details after.
using Json = nlohmann::ordered_json;

Json connections_json(const std::vector<Connection>& cs) {
  Json a = Json::array();
  for (const Connection& c : cs)
    a.push_back({{"frame_a", c.frame_a},
                 {"slice_a", c.slice_a},
                 {"contour_a", c.contour_a},
                 {"frame_b", c.frame_b},
                 {"slice_b", c.slice_b},
                 {"contour_b", c.contour_b},
                 {"similarity", c.similarity},
                 {"kept_by_threshold", c.kept_by_threshold}});
  return a;
}

Json repairs_json(const std::vector<ContourRepair>& repairs) {
  Json a = Json::array();
  for (const ContourRepair& r : repairs)
    a.push_back({{"frame", r.frame},
                 {"slice", r.slice},
                 {"contour", r.contour},
                 {"kind", r.kind},
                 {"detail", r.detail},
                 {"moved_mm", r.moved_mm}});
  return a;
}

// How the contours were smoothed (contour_smoothing.h): the tolerance, where it came from, and each contour.
Json smoothing_json(const InputResult& read) {
  Json each = Json::array();
  double worst = 0.0;
  for (const ContourSmoothing& c : read.smoothing) {
    worst = std::max(worst, c.moved_max_mm);
    each.push_back({{"frame", c.frame},
                    {"slice", c.slice},
                    {"contour", c.contour},
                    {"stiffness", c.stiffness},
                    {"moved_max_mm", c.moved_max_mm},
                    {"moved_mean_mm", c.moved_mean_mm}});
  }
  return {{"tolerance_mm", read.smoothing_tolerance_mm},
          {"source", read.smoothing_source},
          {"smoothed", !read.smoothing.empty()},
          {"moved_max_mm", worst},
          {"contours", each}};
}

// Slices contoured in some frames only (each frame reconstructed from what it has).
Json gaps_json(const std::vector<SliceGap>& gaps) {
  Json a = Json::array();
  for (const SliceGap& g : gaps) a.push_back({{"slice", g.slice}, {"missing_frames", g.missing_frames}});
  return a;
}

// How far each slice was moved in plane (--align-slices; slice_alignment.h).
Json alignment_json(const InputResult& read) {
  if (!read.aligned) return {{"applied", false}};
  Json shifts = Json::array();
  for (const SliceShift& s : read.alignment.shifts)
    shifts.push_back({{"slice", s.slice},
                      {"offset_mm", s.offset_mm},
                      {"shift_mm", {s.shift.x, s.shift.y, s.shift.z}},
                      {"length_mm", s.shift_mm},
                      {"fit_weight", s.weight}});
  if (read.alignment.method == "long-axis")
    for (std::size_t k = 0; k < shifts.size(); ++k) {
      shifts[k]["crossings"] = read.alignment.shifts[k].crossings;
      shifts[k]["median_residual_mm"] = read.alignment.shifts[k].residual_mm;
    }
  return {{"applied", true},
          {"method", read.alignment.method},
          {"label", read.alignment.label},
          {"axis_degree", read.alignment.degree},
          {"slices", shifts}};
}

Json surface_json(const SurfaceReport& r) {
  return {{"contours", r.contours},
          {"caps", r.caps},
          {"branchings", r.branchings},
          {"opening_holes", r.opening_holes},
          {"vertices", r.vertices},
          {"triangles", r.triangles},
          {"closed", r.closed},
          {"self_intersects", r.self_intersections_checked ? Json(r.self_intersects) : Json()},
          {"euler", r.euler},
          {"components", r.components},
          {"volume_mm3", r.volume},
          {"warnings", r.warnings},
          {"connections", connections_json(r.connections)}};
}

Json checks_json(const ResultCheck& check) {
  Json a = Json::array();
  for (const FrameCheck& c : check.frames)
    a.push_back({{"frame", c.frame},
                 {"ok", c.ok()},
                 {"volume_mm3", c.volume},
                 {"simpson_volume_mm3", c.simpson_volume},
                 {"simpson_outer_volume_mm3", c.simpson_outer_volume},
                 {"crossing_triangle_pairs", c.self_intersections},
                 {"faults", c.faults}});
  return a;
}

// The library's options from the user's.
Reconstruct4DOptions library_options(const ReconstructRunOptions& a, const std::string& format) {
  Reconstruct4DOptions opt;
  // Label images name contours by the label's name (or number), which extraction already selected; an RT
  // structure set's ROI (by label, name or number) was chosen on reading.
  opt.surface.label = format == "label-image" || format == "dicom-rtstruct" ? std::string() : a.label;
  opt.surface.edge = a.edge;
  // The paper's tiling (delaunay) tiles every band, so it goes with the remeshed bands, not rows.
  opt.surface.rows = a.tiling != "delaunay";
  opt.surface.tiling = a.tiling == "delaunay" ? Tiling::Delaunay : Tiling::Bands;
  opt.surface.caps = a.cap == "flat" ? CapStyle::Flat : (a.cap == "open" ? CapStyle::Open : CapStyle::Rounded);
  opt.all_frames = a.method == "carry"     ? AllFramesMethod::Carry
                   : a.method == "auto"    ? AllFramesMethod::Auto
                   : a.method == "rebuild" ? AllFramesMethod::Rebuild
                                           : AllFramesMethod::Morph;
  opt.morph.method = a.method == "rbf" ? MorphMethod::Rbf : MorphMethod::RbfProject;
  opt.morph.vertical_deformation = a.vertical;
  return opt;
}

Json start_report(const InputResult& read, const std::string& input, const ReconstructRunOptions& a,
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
      {"contour_smoothing", smoothing_json(read)},
      {"slice_alignment", alignment_json(read)},
      {"slices_in_some_frames", gaps_json(read.slices_in_some_frames)},
      {"input_notes", read.notes},
      {"options",
       {{"edge_mm", a.edge},
        {"cap", a.cap},
        {"method", a.method},
        {"threshold", opt.surface.threshold},
        {"tiling", a.tiling},
        {"vertical_deformation", a.vertical}}},
  };
}

// The median distance between neighbouring slice planes of frame 0 (mm); 0 for a single slice.
double median_slice_gap(const Sequence& seq) {
  std::vector<double> gaps;
  const std::vector<Slice>& slices = seq.frames.front().slices;
  for (std::size_t k = 1; k < slices.size(); ++k) gaps.push_back(slices[k].offset - slices[k - 1].offset);
  if (gaps.empty()) return 0.0;
  std::nth_element(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2), gaps.end());
  return gaps[gaps.size() / 2];
}

// An edge length out of proportion to the slice spacing: coarser than half the gap leaves less than two rows
// of triangles between slices; finer than a hundredth of it makes a mesh far larger than the data supports.
std::string edge_warning(const Sequence& seq, double edge) {
  const double gap = seq.frames.empty() ? 0.0 : median_slice_gap(seq);
  if (gap <= 0.0) return {};
  if (edge > 0.5 * gap)
    return fmt::format(
        "--edge {:g} mm is coarse for slices {:.1f} mm apart: less than two rows of triangles between "
        "slices (try --edge {:.1f} or less)",
        edge, gap, 0.25 * gap);
  if (edge < 0.01 * gap)
    return fmt::format(
        "--edge {:g} mm is fine for slices {:.1f} mm apart: a very large mesh, slow to make (try --edge "
        "{:.1f})",
        edge, gap, std::max(0.1 * gap, 0.5));
  return {};
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

void one_frame(const ReconstructRunOptions& a, const Sequence& seq, const Reconstruct4DOptions& opt,
               ReconstructRun& run, Json& report, const RunMessage& say) {
  if (a.frame >= static_cast<int>(seq.frames.size()))
    throw InvalidInput(ErrorCode::Usage, Location{run.input},
                       fmt::format("--frame {} is out of range: the input has {} frames", a.frame, seq.frames.size()));
  SurfaceReport sr;
  const TriangleMesh mesh = reconstruct_frame(seq, a.frame, opt.surface, &sr);
  run.result.triangles = mesh.triangles;
  run.result.positions = {mesh.positions};
  run.result.times_ms = {seq.frames[static_cast<std::size_t>(a.frame)].time_ms};
  report["frames"] = {{{"frame", a.frame}, {"surface", surface_json(sr)}}};
  if (!say) return;
  if (sr.opening_holes > 0)
    say(fmt::format("  {} hole(s) open into the outside between slices (a C-shaped section beyond a ring)",
                    sr.opening_holes));
  for (const std::string& w : sr.warnings) say("  warning: " + w);
}

// Where frames were carried onto a changed topology, the result must also keep triangles this well shaped in
// every frame (the share of angles in 40–80° and the smallest angle), else the morph is tried as well.
constexpr double kCarriedMinShare4080 = 85.0;
constexpr double kCarriedMinAngleDeg = 5.0;

// The worst frame's triangle shape: the smallest share of angles in 40–80° (%) and the smallest angle (°).
std::pair<double, double> worst_angles(const MeshSequence& m) {
  double share = 100.0, smallest = 180.0;
  for (std::size_t f = 0; f < m.positions.size(); ++f) {
    const AngleQuality q = angle_quality(m.frame(f));
    share = std::min(share, q.pct_40_80);
    smallest = std::min(smallest, q.min_angle_deg);
  }
  return {share, smallest};
}

// Whether no frame of `m` looks permuted to evaluate's correspondence test (correspondence.h): a morph that
// crumples the band of a vanishing contour into tiny triangles and leaves it so after the contour is back
// (biv-me's right ventricle: 4 % of the edges under a quarter of their frame-0 length in 20 of 25 frames, so
// that frames 0-4 look grown 4-fold) passes the checks but is no better than the frames rebuilt on one mesh.
bool edges_keep_their_length(const MeshSequence& m) {
  std::vector<TriangleMesh> frames;
  for (std::size_t f = 0; f < m.positions.size(); ++f) frames.push_back(m.frame(f));
  return check_correspondence(frames).suspicious_frames.empty();
}

// The frames rebuilt on one mesh (rebuild.h) failed their checks, or frames carried where the contours change
// left poor triangles: the frame-after-frame morph is tried, and its result replaces the rebuilt one if that
// failed its checks, or if the morph's passes with better-shaped triangles (its smallest share of angles in
// 40–80° larger) and no frame whose edges look permuted (edges_keep_their_length).
void morph_instead(const ReconstructRunOptions& a, const Sequence& seq, const Reconstruct4DOptions& opt, bool closed,
                   ReconstructRun& run, Reconstruct4DReport& rr, Json& report, const RunMessage& say,
                   const std::string& why) {
  if (say) say(fmt::format("  the frames on one mesh {}; trying the frame-after-frame morph", why));
  Reconstruct4DOptions morph = opt;
  morph.all_frames = AllFramesMethod::Morph;
  Reconstruct4DReport rm;
  MeshSequence other = reconstruct_4d(seq, morph, &rm);
  ResultCheck other_check = run_checks(a, seq, opt.surface.label, closed, other);
  report["all_frames"]["rebuild_fault"] = why;
  const bool better =
      !run.check.ok() || (other_check.ok() && worst_angles(other).first > worst_angles(run.result).first &&
                          edges_keep_their_length(other));
  if (!better) return;
  run.result = std::move(other);
  rm.rebuild = rr.rebuild;
  rr = std::move(rm);
  run.check = std::move(other_check);
  report["all_frames"]["method"] = "morph";
}

// The default morph failed its checks (`failed` "the frame-after-frame morph"), or the frames on one mesh
// failed theirs on a shell: the morph can fold a frame onto a neighbouring sheet (a myocardium's two walls).
// Every frame is then carried from frame 0 on its own, and that result replaces the failed one if it passes the
// checks.
void carry_instead(const ReconstructRunOptions& a, const Sequence& seq, const Reconstruct4DOptions& opt, bool closed,
                   ReconstructRun& run, Reconstruct4DReport& rr, Json& report, const RunMessage& say,
                   const std::string& failed) {
  if (say)
    say(fmt::format("  {} failed its checks ({}); carrying every frame from frame 0 instead", failed,
                    run.check.summary()));
  Reconstruct4DOptions carry = opt;
  carry.all_frames = AllFramesMethod::Carry;
  Reconstruct4DReport rc;
  MeshSequence other = reconstruct_4d(seq, carry, &rc);
  ResultCheck other_check = run_checks(a, seq, opt.surface.label, closed, other);
  report["all_frames_fallback"] = {{"failed", failed}, {"fault", run.check.summary()}, {"carry_ok", other_check.ok()}};
  if (!other_check.ok()) return;
  rc.rebuild = rr.rebuild;  // as morph_instead: the report keeps why frames were carried
  run.result = std::move(other);
  rr = std::move(rc);
  run.check = std::move(other_check);
  report["options"]["method"] = "carry";
  report["all_frames"]["method"] = "carry";
}

// Whether some slice holds a contour inside another (a myocardial wall: its outer contours enclose more than
// the wall's own discs).
bool is_shell(const ResultCheck& check) {
  return std::any_of(check.frames.begin(), check.frames.end(),
                     [](const FrameCheck& f) { return f.simpson_outer_volume > f.simpson_volume; });
}

const char* all_frames_name(AllFramesMethod m) {
  switch (m) {
    case AllFramesMethod::Rebuild:
      return "rebuild";
    case AllFramesMethod::Carry:
      return "carry";
    default:
      return "morph";
  }
}

Json frames_json(const MeshSequence& result, const Reconstruct4DReport& rr) {
  Json frames = Json::array();
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
                      {"contour_fit",
                       {{"moved_vertices", mf.fit_moved},
                        {"max_distance_before_mm", mf.fit_max_before},
                        {"max_distance_after_mm", mf.fit_max_after}}},
                      {"intersecting_pairs_after_untangling", mf.intersecting_pairs},
                      {"projection_mean_mm", mf.projection_mean},
                      {"projection_max_mm", mf.projection_max},
                      {"surface", surface_json(rr.surfaces[f])}});
    if (f < rr.carry.frames.size() && rr.carry.frames[f].source >= 0)
      frames.back()["carried_from"] = rr.carry.frames[f].source;
  }
  return frames;
}

// Topology events and sub-mesh lifetimes (Miara et al. Fig. 14), in the report and for the user.
void describe_topology(const Reconstruct4DReport& rr, Json& report, const RunMessage& say) {
  Json events = Json::array();
  for (const SliceEvent& e : rr.morph.events)
    events.push_back(
        {{"frame", e.frame}, {"slice", e.slice}, {"kind", e.kind}, {"before", e.before}, {"after", e.after}});
  report["topology_events"] = events;
  Json subs = Json::array();
  for (const SubMeshLifetime& s : rr.morph.submeshes)
    subs.push_back({{"slice_below", s.slice_below},
                    {"slice_above", s.slice_above},
                    {"first_frame", s.first_frame},
                    {"last_frame", s.last_frame},
                    {"contours_below", s.contours_below},
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
                ReconstructRun& run, Json& report, const RunMessage& say) {
  Reconstruct4DReport rr;
  run.result = reconstruct_4d(seq, opt, &rr);
  run.check = run_checks(a, seq, opt.surface.label, closed, run.result);
  report["all_frames"] = {{"method", all_frames_name(rr.used)}, {"why_not_rebuilt", rr.rebuild.why_not}};
  Json carried = Json::array();
  for (std::size_t k = 0; k < rr.rebuild.unfit.size(); ++k)
    carried.push_back({{"frame", rr.rebuild.unfit[k]}, {"why", rr.rebuild.unfit_why[k]}});
  report["all_frames"]["carried_frames"] = carried;
  if (say && rr.used != AllFramesMethod::Rebuild && a.method == "auto")
    say(fmt::format("  every frame on one mesh is not possible ({}): frame after frame instead", rr.rebuild.why_not));
  bool carried_first = false;  // every frame carried from frame 0 before the morph was tried
  if (rr.used == AllFramesMethod::Rebuild && a.method == "auto") {
    if (!run.check.ok()) {
      // On a shell the carry from frame 0 goes first: it lands every vertex on its own sheet, where the morph
      // folds onto the other (biv-me's wall: the morph ran 16 min and failed, the carry passed in 2 min).
      carried_first = is_shell(run.check);
      if (carried_first) carry_instead(a, seq, opt, closed, run, rr, report, say, "every frame on one mesh");
      if (!run.check.ok())
        morph_instead(a, seq, opt, closed, run, rr, report, say, "failed their checks (" + run.check.summary() + ")");
    } else if (!rr.rebuild.unfit.empty()) {
      const auto [share, smallest] = worst_angles(run.result);
      if (share < kCarriedMinShare4080 || smallest < kCarriedMinAngleDeg)
        morph_instead(a, seq, opt, closed, run, rr, report, say,
                      fmt::format("have poorly shaped triangles where the contours change ({:.1f} % of angles in "
                                  "40-80°, smallest {:.1f}°)",
                                  share, smallest));
    }
  }
  const bool morphed = rr.used == AllFramesMethod::Morph && (a.method == "rbf-project" || a.method == "auto");
  if (!run.check.ok() && morphed && !carried_first)
    carry_instead(a, seq, opt, closed, run, rr, report, say, "the frame-after-frame morph");
  report["frames"] = frames_json(run.result, rr);
  describe_topology(rr, report, say);
}

// What a person or a script reads first: the structure, the frames and their times, the volume curve with
// its end-diastolic (largest) and end-systolic (smallest) frames, EDV/ESV/EF, the mesh and whether it passed.
Json summary_json(const ReconstructRun& run, const InputResult& read, const ReconstructRunOptions& a,
                  const Json& report) {
  const MeshSequence& result = run.result;
  std::vector<double> volumes_ml;
  for (std::size_t f = 0; f < result.positions.size(); ++f)
    volumes_ml.push_back(signed_volume(result.frame(f)) / 1000.0);
  const auto ed = std::max_element(volumes_ml.begin(), volumes_ml.end());
  const auto es = std::min_element(volumes_ml.begin(), volumes_ml.end());
  const int first = a.frame >= 0 ? a.frame : 0;
  Json s;
  s["input"] = run.input;
  s["structure"] = a.label;
  s["frames"] = result.positions.size();
  s["frame_times_ms"] = result.times_ms;
  s["frame_times_source"] = read.timing;
  s["volume_ml"] = volumes_ml;
  s["ed_frame"] = first + static_cast<int>(ed - volumes_ml.begin());
  s["es_frame"] = first + static_cast<int>(es - volumes_ml.begin());
  s["edv_ml"] = *ed;
  s["esv_ml"] = *es;
  s["ef_percent"] = *ed > 0 ? 100.0 * (*ed - *es) / *ed : 0.0;
  s["vertices"] = result.positions.front().size();
  s["triangles"] = result.triangles.size();
  if (a.label == kLvWall) {
    std::vector<double> mass_g;
    for (double v : volumes_ml) mass_g.push_back(v * kMyocardiumDensity);
    s["mass_g"] = mass_g;  // the myocardium's mass per frame
  }
  s["correspondence"] = true;  // one triangle list for every frame, by construction
  s["checks_ok"] = run.check.ok();
  s["method"] = report.contains("all_frames") ? report["all_frames"]["method"] : report["options"]["method"];
  s["repairs"] = read.repairs.size();
  s["units"] = "mm";
  s["space"] = read.sequence.space;
  return s;
}

// Floats rounded to what they mean: lengths to 0.1 µm, volumes to 0.0001 mm³ or ml, angles and percentages
// to 0.0001 (no 17-digit noise).
void round_floats(Json& j) {
  if (j.is_number_float()) {
    const double v = j.get<double>();
    const double r = std::isfinite(v) ? std::round(v * 1e4) / 1e4 : v;
    j = r == 0.0 ? 0.0 : r;  // no -0
  } else if (j.is_structured()) {
    for (Json& e : j) round_floats(e);
  }
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
  Json report = start_report(read, input_name, a, opt);
  if (const std::string w = edge_warning(seq, a.edge); !w.empty()) {
    report["warnings"] = {w};
    if (say) say("  warning: " + w);
  }
  const bool closed = opt.surface.caps != CapStyle::Open;
  if (a.frame >= 0) {
    one_frame(a, seq, opt, run, report, say);
    run.check = run_checks(a, seq, opt.surface.label, closed, run.result);
  } else {
    all_frames(a, seq, opt, closed, run, report, say);
  }
  report["checks"] = {
      {"ok", run.check.ok()}, {"volume_tolerance", a.volume_tolerance}, {"frames", checks_json(run.check)}};
  Json whole;
  whole["summary"] = summary_json(run, read, a, report);
  whole.update(report);
  round_floats(whole);
  // No run time in the report: the same input must give byte-identical outputs.
  run.report = whole.dump(2) + "\n";
  return run;
}

void throw_if_failed(const ReconstructRun& run, const std::string& hint) {
  if (!run.check.ok())
    throw SolverError(ErrorCode::InvalidResult, Location{run.input},
                      "the reconstruction failed its checks: " + run.check.summary(), hint);
}

void write_run(OutputDir& out, const ReconstructRun& run, const MeshFormats& formats, const std::string& keep_failed) {
  if (!run.check.ok()) {
    std::string hint = fmt::format("nothing was written to {}", out.destination().string());
    if (!keep_failed.empty()) {
      OutputDir failed(keep_failed);
      Json report = Json::parse(run.report);
      report["FAILED"] = run.check.summary();
      write_mesh_sequence(failed, run.result, fmt::format("FAILED contour4d reconstruct {}", run.input), formats);
      failed.write("report.json", report.dump(2) + "\n");
      failed.write("FAILED.txt",
                   "This result FAILED its checks and is kept only for debugging:\n" + run.check.summary() + "\n");
      failed.commit();
      hint += fmt::format("; the failed result is in {} (marked FAILED)", keep_failed);
    } else {
      hint += "; --keep-failed DIR writes the failed result there for debugging";
    }
    throw_if_failed(run, hint);
  }
  write_mesh_sequence(out, run.result, fmt::format("contour4d reconstruct {}", run.input), formats);
  out.write("report.json", run.report);
  out.commit();
}

}  // namespace c4d
