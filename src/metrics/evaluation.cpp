// The papers' evaluation of a 4D mesh (Lim et al. 2014, "Experimental Setup" and "Results"):
// conformity to the input contours (Figure 10), triangle angle quality (Tables 3 and 4), accuracy
// against an idealized model (Table 5), vertex correspondence, plus what the issue adds: the
// validity of each surface and volumes with EF next to Simpson's method of discs.
//
// Frames are measured in parallel, each into its own slot, and every per-frame computation is
// sequential, so the result does not depend on the number of threads. Each frame builds its AABB
// trees once and reuses them for conformity and accuracy.
#include "contour4d/metrics/evaluation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include "metrics_internal.h"

namespace c4d {
namespace {
using Json = nlohmann::ordered_json;

// Rounds to 6 decimals so the JSON stays readable; the measures are not that precise anyway.
double r6(double x) { return std::isfinite(x) ? std::round(x * 1e6) / 1e6 : x; }

// Facet normal angles against the truth (degrees); with the frame they were measured on, when given.
Json normals_json(const NormalDeviation& d, int frame = -1) {
  Json j{{"triangles", d.triangles},
         {"mean_deg", r6(d.mean_deg)},
         {"median_deg", r6(d.median_deg)},
         {"p99_deg", r6(d.p99_deg)},
         {"max_deg", r6(d.max_deg)}};
  if (frame >= 0) j["frame"] = frame;
  return j;
}

Json stats_json(const DistanceStats& s) {
  return Json{{"samples", s.samples},
              {"mean_mm", r6(s.mean)},
              {"max_mm", r6(s.max)},
              {"rms_mm", r6(s.rms)},
              {"std_mm", r6(s.std)}};
}

Json surface_json(const SurfaceDistance& d) {
  return Json{{"mesh_to_truth", stats_json(d.mesh_to_truth)},
              {"truth_to_mesh", stats_json(d.truth_to_mesh)},
              {"hausdorff_mm", r6(d.hausdorff)}};
}

Json quality_json(const AngleQuality& q) {
  return Json{{"triangles", q.triangles},
              {"angles_40_50_pct", r6(q.pct_40_50)},
              {"angles_50_60_pct", r6(q.pct_50_60)},
              {"angles_60_70_pct", r6(q.pct_60_70)},
              {"angles_70_80_pct", r6(q.pct_70_80)},
              {"angles_40_80_pct", r6(q.pct_40_80)},
              {"bad_triangles", q.bad_triangles},
              {"bad_triangles_pct", r6(q.bad_pct)},
              {"min_angle_deg", r6(q.min_angle_deg)},
              {"max_angle_deg", r6(q.max_angle_deg)}};
}

Json topology_json(const TopologyReport& t) {
  Json comps = Json::array();
  for (const ComponentTopology& c : t.components)
    comps.push_back({{"vertices", c.vertices},
                     {"edges", c.edges},
                     {"triangles", c.triangles},
                     {"boundary_loops", c.boundary_loops},
                     {"euler", c.euler},
                     {"genus", c.genus}});
  return Json{{"closed", t.closed()},
              {"edge_manifold", t.edge_manifold()},
              {"vertex_manifold", t.vertex_manifold()},
              {"consistently_oriented", t.consistently_oriented()},
              {"outward", t.outward()},
              {"components", t.components.size()},
              {"genus", t.genus},
              {"edges", t.edges},
              {"boundary_edges", t.boundary_edges},
              {"nonmanifold_edges", t.nonmanifold_edges},
              {"nonmanifold_vertices", t.nonmanifold_vertices},
              {"misoriented_edges", t.misoriented_edges},
              {"flipped_triangles", t.flipped_triangles},
              {"self_intersections_checked", t.self_intersections_checked},
              {"self_intersecting_pairs", t.self_intersections},
              {"degenerate_triangles", t.degenerate_triangles},
              {"invalid_triangles", t.invalid_triangles},
              {"duplicate_triangles", t.duplicate_triangles},
              {"duplicate_vertices", t.duplicate_vertices},
              {"unreferenced_vertices", t.unreferenced_vertices},
              {"component_list", comps},
              {"faults", t.faults}};
}

Json ef_json(const EjectionFraction& e) {
  return Json{{"edv_mm3", r6(e.edv)},
              {"esv_mm3", r6(e.esv)},
              {"ef_pct", r6(e.ef_pct)},
              {"ed_frame", e.ed_frame},
              {"es_frame", e.es_frame}};
}

// The slab between the first and last slice plane of a frame's contours.
bool frame_slab(const Sequence& seq, const Frame& frame, Slab& slab) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Slice& s : frame.slices)
    for (const Contour& c : s.contours)
      for (const Vec3& p : c.points) {
        lo = std::min(lo, dot(p, seq.normal));
        hi = std::max(hi, dot(p, seq.normal));
      }
  if (!(lo <= hi)) return false;
  slab = {seq.normal, lo, hi};
  return true;
}

std::string mm(double x) { return std::isfinite(x) ? fmt::format("{:.3f}", x) : "-"; }
}  // namespace

bool Evaluation::has_topology_fault() const {
  for (const FrameEvaluation& f : frames)
    if (!f.topology.ok()) return true;
  return !correspondence.ok();
}

Evaluation evaluate(const MeshFrames& meshes, const Sequence* contours, const MeshFrames* truth,
                    const EvaluationOptions& options) {
  Evaluation ev;
  ev.conformity_step = options.conformity.step;
  const std::size_t nf = meshes.meshes.size();
  ev.frames.resize(nf);
  if (contours != nullptr && contours->frames.size() != nf)
    ev.notes.push_back(fmt::format("the contours have {} frames and the meshes {}: only frames 0..{} are compared",
                                   contours->frames.size(), nf, std::min(contours->frames.size(), nf) - 1));
  if (truth != nullptr && truth->meshes.size() != nf)
    ev.notes.push_back(fmt::format("the truth has {} frames and the meshes {}: only frames 0..{} are compared",
                                   truth->meshes.size(), nf, std::min(truth->meshes.size(), nf) - 1));
  std::vector<DiscVolume> discs;
  if (contours != nullptr) discs = simpson_volumes(*contours);

  tbb::parallel_for(std::size_t{0}, nf, [&](std::size_t f) {
    FrameEvaluation& fe = ev.frames[f];
    const TriangleMesh& mesh = meshes.meshes[f];
    fe.frame = static_cast<int>(f);
    fe.time_ms = f < meshes.times_ms.size() ? meshes.times_ms[f] : static_cast<double>(f);
    fe.topology = check_topology(mesh, options.topology);
    fe.quality = angle_quality(mesh, options.quality);
    fe.volume = fe.topology.signed_volume;
    const bool has_contours = contours != nullptr && f < contours->frames.size();
    const bool has_truth = truth != nullptr && f < truth->meshes.size();
    if (has_contours) fe.simpson = discs[f];
    if (!has_contours && !has_truth) return;
    const metrics_internal::TriangleDistance tree(mesh);
    if (!tree.valid()) return;  // "no triangles" is already a topology fault
    std::vector<Vec3> samples;
    if (has_contours) {
      samples = metrics_internal::contour_samples(contours->frames[f], options.conformity.step);
      fe.conformity = summarize_distances(tree.distances(samples));
      fe.creases = crease_angles(mesh, *contours, contours->frames[f]);
    }
    if (has_truth) {
      const metrics_internal::TriangleDistance truth_tree(truth->meshes[f]);
      if (!truth_tree.valid()) return;
      SurfaceDistanceOptions sd;
      sd.sampling = options.sampling;
      if (has_contours) sd.use_slab = frame_slab(*contours, contours->frames[f], sd.slab);
      const auto forward = metrics_internal::measure_samples(sample_surface(mesh, sd.sampling), truth_tree, sd);
      const auto backward = metrics_internal::measure_samples(sample_surface(truth->meshes[f], sd.sampling), tree, sd);
      fe.accuracy = metrics_internal::combine(forward, backward, sd);
      if (has_contours) fe.contours_to_truth = summarize_distances(truth_tree.distances(samples));
      fe.normals = normal_deviation(mesh, truth_tree.surface());
    }
  });

  for (const FrameEvaluation& fe : ev.frames) {
    for (const std::string& s : fe.topology.faults) ev.faults.push_back(fmt::format("frame {}: {}", fe.frame, s));
    if (truth != nullptr && static_cast<std::size_t>(fe.frame) < truth->meshes.size() && !fe.accuracy)
      ev.notes.push_back(
          fmt::format("frame {}: accuracy not measured (a mesh has no triangle of non-zero area)", fe.frame));
  }
  ev.correspondence = check_correspondence(meshes.meshes, options.correspondence);
  for (const std::string& s : ev.correspondence.faults) ev.faults.push_back(s);

  std::vector<double> vols, svols;
  for (const FrameEvaluation& fe : ev.frames) {
    vols.push_back(fe.volume);
    if (fe.simpson) svols.push_back(fe.simpson->volume);
  }
  ev.mesh_ef = ejection_fraction(vols);
  if (contours != nullptr) ev.simpson_ef = ejection_fraction(svols);
  return ev;
}

// The angles between neighbouring triangles on the contour lines against those between them.
Json creases_json(const CreaseAngles& c, int frame = -1) {
  Json j{{"on_contours_p95_deg", r6(c.on_contours_p95)},
         {"between_p95_deg", r6(c.between_p95)},
         {"ratio", r6(c.ratio())},
         {"on_end_contours_p95_deg", r6(c.on_ends_p95)},
         {"end_ratio", r6(c.ends_ratio())},
         {"edges_on_contours", c.on_contours},
         {"edges_between", c.between}};
  if (frame >= 0) j["frame"] = frame;
  return j;
}

// The frame whose contour lines crease most against its wall (largest ratio), or null.
const FrameEvaluation* worst_creases(const Evaluation& ev) {
  const FrameEvaluation* worst = nullptr;
  for (const FrameEvaluation& fe : ev.frames)
    if (fe.creases && (!worst || fe.creases->ratio() > worst->creases->ratio())) worst = &fe;
  return worst;
}

std::string format_evaluation_json(const Evaluation& ev) {
  Json j;
  j["format"] = "contour4d-evaluation";
  j["version"] = 1;
  j["units"] = {{"length", "mm"},     {"area", "mm²"},   {"volume", "mm³"},
                {"angle", "degrees"}, {"fraction", "%"}, {"time", "ms"}};
  j["measures"] = {
      {"conformity",
       "distance from points every step mm along each contour to the nearest mesh point (Lim et al. 2014)"},
      {"quality", "% of triangle angles per 10-degree bin; bad triangles have an angle below 25 degrees (Tables 3, 4)"},
      {"accuracy",
       "area-weighted surface distances both ways, exact point-to-triangle (Table 5); slab: between first and last "
       "slice"},
      {"simpson", "sum over slices of enclosed area × disc thickness (half-way to each neighbouring slice)"},
      {"creases",
       "95th percentile of the angle between the normals of an edge's two triangles: on the contour lines (edges in a "
       "slice plane), on the first and last contours, and between the slices"},
      {"correspondence", "median relative edge-length change against each edge's median length over all frames"}};
  Json frames = Json::array();
  for (const FrameEvaluation& fe : ev.frames) {
    Json f;
    f["frame"] = fe.frame;
    f["time_ms"] = r6(fe.time_ms);
    f["vertices"] = fe.topology.vertices;
    f["triangles"] = fe.topology.triangles;
    f["topology"] = topology_json(fe.topology);
    f["quality"] = quality_json(fe.quality);
    f["volume_mm3"] = r6(fe.volume);
    if (fe.conformity) f["conformity"] = stats_json(*fe.conformity);
    if (fe.creases) f["creases"] = creases_json(*fe.creases);
    if (fe.simpson) {
      Json slices = Json::array();
      for (const SliceArea& s : fe.simpson->slices)
        slices.push_back({{"slice", s.slice}, {"offset_mm", r6(s.offset)}, {"area_mm2", r6(s.area)}});
      f["simpson"] = {{"volume_mm3", r6(fe.simpson->volume)},
                      {"trapezoid_volume_mm3", r6(fe.simpson->trapezoid_volume)},
                      {"slices", slices}};
    }
    if (fe.accuracy) {
      f["accuracy"] = surface_json(fe.accuracy->whole);
      if (fe.accuracy->has_slab) f["accuracy_slab"] = surface_json(fe.accuracy->slab);
    }
    if (fe.contours_to_truth) f["contours_to_truth"] = stats_json(*fe.contours_to_truth);
    if (fe.normals) f["normals_to_truth"] = normals_json(*fe.normals);
    frames.push_back(f);
  }
  j["frames"] = frames;

  const CorrespondenceReport& c = ev.correspondence;
  Json corr{{"same_vertex_count", c.same_vertex_count},         {"same_triangles", c.same_triangles},
            {"first_differing_frame", c.first_differing_frame}, {"difference", c.difference},
            {"median_edge_change_pct", Json::array()},          {"edge_jump_pct", Json::array()},
            {"suspicious_frames", c.suspicious_frames}};
  for (double x : c.median_edge_change_pct) corr["median_edge_change_pct"].push_back(r6(x));
  for (double x : c.edge_jump_pct) corr["edge_jump_pct"].push_back(r6(x));
  j["correspondence"] = corr;

  // Summary over frames: the papers report per-dataset figures.
  Json s;
  s["frames"] = ev.frames.size();
  s["topology_ok"] = !ev.has_topology_fault();
  s["correspondence"] = c.ok() ? "yes" : "no";
  std::vector<double> means;
  double cmax = 0.0;
  for (const FrameEvaluation& fe : ev.frames)
    if (fe.conformity) {
      means.push_back(fe.conformity->mean);
      cmax = std::max(cmax, fe.conformity->max);
    }
  if (!means.empty()) {
    const DistanceStats m = summarize_distances(means);
    s["conformity"] = {
        {"mean_of_frame_means_mm", r6(m.mean)}, {"std_of_frame_means_mm", r6(m.std)}, {"max_mm", r6(cmax)}};
  }
  if (!ev.frames.empty()) {
    const std::size_t n = ev.frames.size();
    s["quality_first_mid_last"] = {quality_json(ev.frames[0].quality), quality_json(ev.frames[n / 2].quality),
                                   quality_json(ev.frames[n - 1].quality)};
    double bad = 0.0, bad_pct = 0.0, min_angle = 180.0;
    for (const FrameEvaluation& fe : ev.frames) {
      bad += static_cast<double>(fe.quality.bad_triangles);
      bad_pct += fe.quality.bad_pct;
      if (fe.quality.triangles > 0) min_angle = std::min(min_angle, fe.quality.min_angle_deg);
    }
    s["bad_triangles_per_frame"] = r6(bad / static_cast<double>(n));
    s["bad_triangles_pct"] = r6(bad_pct / static_cast<double>(n));
    s["min_angle_deg"] = r6(min_angle);
  }
  double amean = 0.0, amax = 0.0, arms2 = 0.0, haus = 0.0;
  std::size_t na = 0;
  for (const FrameEvaluation& fe : ev.frames)
    if (fe.accuracy) {
      ++na;
      amean += fe.accuracy->whole.mesh_to_truth.mean;
      amax = std::max(amax, fe.accuracy->whole.mesh_to_truth.max);
      arms2 += fe.accuracy->whole.mesh_to_truth.rms * fe.accuracy->whole.mesh_to_truth.rms;
      haus = std::max(haus, fe.accuracy->whole.hausdorff);
    }
  if (na > 0)
    s["accuracy_mesh_to_truth"] = {{"mean_mm", r6(amean / na)},
                                   {"max_mm", r6(amax)},
                                   {"rms_mm", r6(std::sqrt(arms2 / na))},
                                   {"hausdorff_mm", r6(haus)}};
  // The worst frame's facet normals against the truth's (the shading a viewer shows).
  const FrameEvaluation* worst = nullptr;
  for (const FrameEvaluation& fe : ev.frames)
    if (fe.normals && (!worst || fe.normals->p99_deg > worst->normals->p99_deg)) worst = &fe;
  if (worst) s["normals_to_truth_worst_frame"] = normals_json(*worst->normals, worst->frame);
  if (const FrameEvaluation* crease = worst_creases(ev))
    s["creases_worst_frame"] = creases_json(*crease->creases, crease->frame);
  s["mesh_volume"] = ef_json(ev.mesh_ef);
  if (ev.simpson_ef) s["simpson_volume"] = ef_json(*ev.simpson_ef);
  j["summary"] = s;
  j["faults"] = ev.faults;
  j["notes"] = ev.notes;
  return j.dump(2) + "\n";
}

std::string format_evaluation_table(const Evaluation& ev) {
  std::string out;
  bool any_conf = false, any_acc = false, any_simpson = false;
  for (const FrameEvaluation& fe : ev.frames) {
    any_conf |= fe.conformity.has_value();
    any_acc |= fe.accuracy.has_value();
    any_simpson |= fe.simpson.has_value();
  }
  out += fmt::format("{:>5} {:>9} {:>8} {:>8} {:>6} {:>6} {:>5} {:>6} {:>6} {:>6} {:>12}", "frame", "time ms",
                     "vertices", "tris", "faults", "closed", "genus", "SI", "40-80%", "min°", "volume ml");
  if (any_simpson) out += fmt::format(" {:>12}", "simpson ml");
  if (any_conf) out += fmt::format(" {:>9} {:>9}", "conf mean", "conf max");
  if (any_acc)
    out += fmt::format(" {:>9} {:>9} {:>9} {:>9} {:>9}", "acc mean", "acc max", "acc rms", "hausdorff", "normal99°");
  out += "\n";
  for (const FrameEvaluation& fe : ev.frames) {
    const TopologyReport& t = fe.topology;
    out += fmt::format("{:>5} {:>9.1f} {:>8} {:>8} {:>6} {:>6} {:>5} {:>6} {:>6.2f} {:>6.2f} {:>12.2f}", fe.frame,
                       fe.time_ms, t.vertices, t.triangles, t.faults.size(), t.closed() ? "yes" : "no",
                       t.genus < 0 ? std::string("-") : std::to_string(t.genus),
                       t.self_intersections_checked ? std::to_string(t.self_intersections) : std::string("-"),
                       fe.quality.pct_40_80, fe.quality.min_angle_deg, fe.volume / 1000.0);
    if (any_simpson)
      out += fmt::format(" {:>12}", fe.simpson ? fmt::format("{:.2f}", fe.simpson->volume / 1000.0) : "-");
    if (any_conf)
      out += fmt::format(" {:>9} {:>9}", fe.conformity ? mm(fe.conformity->mean) : "-",
                         fe.conformity ? mm(fe.conformity->max) : "-");
    if (any_acc) {
      if (fe.accuracy) {
        const DistanceStats& a = fe.accuracy->whole.mesh_to_truth;
        out += fmt::format(" {:>9} {:>9} {:>9} {:>9} {:>9}", mm(a.mean), mm(a.max), mm(a.rms),
                           mm(fe.accuracy->whole.hausdorff),
                           fe.normals ? fmt::format("{:.2f}", fe.normals->p99_deg) : std::string("-"));
      } else {
        out += fmt::format(" {:>9} {:>9} {:>9} {:>9} {:>9}", "-", "-", "-", "-", "-");
      }
    }
    out += "\n";
  }
  out += "\nsummary (mm, ml, degrees, %)\n";
  std::vector<double> means;
  for (const FrameEvaluation& fe : ev.frames)
    if (fe.conformity) means.push_back(fe.conformity->mean);
  if (!means.empty()) {
    const DistanceStats m = summarize_distances(means);
    out += fmt::format("  conformity: mean of frame means {:.4f} mm, std {:.4f} mm (contour samples every {:g} mm)\n",
                       m.mean, m.std, ev.conformity_step);
  }
  if (const FrameEvaluation* c = worst_creases(ev))
    out += fmt::format(
        "  creases (95th percentile of the angle between neighbouring triangles), worst frame {}: {:.2f}° on the "
        "contour lines, {:.2f}° between them ({:.2f}×); {:.2f}° on the end contours ({:.2f}×)\n",
        c->frame, c->creases->on_contours_p95, c->creases->between_p95, c->creases->ratio(), c->creases->on_ends_p95,
        c->creases->ends_ratio());
  if (!ev.frames.empty()) {
    const std::size_t n = ev.frames.size();
    std::vector<std::size_t> shown{0};  // the first, middle and last frame, each once
    for (std::size_t f : {n / 2, n - 1})
      if (f != shown.back()) shown.push_back(f);
    for (std::size_t f : shown) {
      const AngleQuality& q = ev.frames[f].quality;
      out += fmt::format(
          "  angles frame {:>3}: 40-50 {:.2f}%  50-60 {:.2f}%  60-70 {:.2f}%  70-80 {:.2f}%  total {:.2f}%  "
          "(<25°: {} triangles, {:.4f}%)\n",
          f, q.pct_40_50, q.pct_50_60, q.pct_60_70, q.pct_70_80, q.pct_40_80, q.bad_triangles, q.bad_pct);
    }
  }
  out += fmt::format("  mesh volume: EDV {:.2f} ml (frame {}), ESV {:.2f} ml (frame {}), EF {:.1f} %\n",
                     ev.mesh_ef.edv / 1000.0, ev.mesh_ef.ed_frame, ev.mesh_ef.esv / 1000.0, ev.mesh_ef.es_frame,
                     ev.mesh_ef.ef_pct);
  if (ev.simpson_ef)
    out += fmt::format("  Simpson discs: EDV {:.2f} ml (frame {}), ESV {:.2f} ml (frame {}), EF {:.1f} %\n",
                       ev.simpson_ef->edv / 1000.0, ev.simpson_ef->ed_frame, ev.simpson_ef->esv / 1000.0,
                       ev.simpson_ef->es_frame, ev.simpson_ef->ef_pct);
  const CorrespondenceReport& c = ev.correspondence;
  out += fmt::format("  vertex correspondence: {}\n", c.ok() ? "yes" : "no");
  out += ev.faults.empty() ? std::string("no faults\n") : fmt::format("{} faults:\n", ev.faults.size());
  for (const std::string& f : ev.faults) out += "  " + f + "\n";
  for (const std::string& n : ev.notes) out += "note: " + n + "\n";
  return out;
}

}  // namespace c4d
