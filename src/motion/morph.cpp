// Lim et al. 2014, "4D Morphing of the Heart Model" and "Contour Matching" (Fig. 7); Miara et al.
// §III.E (sub-mesh lifetimes, Fig. 14).
//
// Per frame t, the previous mesh is cut by every slice plane; each section loop that matches one
// contour of frame t one-to-one (similarity index over the threshold both ways) is mapped onto it
// (contour matching) and the matched points drive a Hardy-multiquadric RBF (eq. 9) that moves the
// whole mesh. Slices whose contours split, merge, appear or vanish give no constraint; they are
// reported as events. The paper resolves them with a sine-shaped vertical pre-deformation; our
// default instead projects the mesh onto frame t's own surface (reconstructed from its contours,
// branching included), with a Laplacian term that keeps the previous frame's shape (Sorkine et al.,
// "Laplacian Surface Editing", 2004) — its matrix depends only on the connectivity, so it is
// factored once for the whole sequence — followed by tangential relaxation that keeps triangle
// quality (vertices move within the surface, so the contours stay on it).
//
// This file drives the steps (morph_frame) and holds the RBF guess, the projection and the retries; the
// other steps live in morph_match.cpp, morph_relax.cpp, morph_snap.cpp and morph_fit.cpp
// (morph_work_internal.h lists them).
#include "contour4d/motion/morph.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include "contour4d/core/errors.h"
#include "contour4d/metrics/quality.h"
#include "contour4d/motion/rbf.h"
#include "contour4d/surface/angle_repair.h"
#include "morph_internal.h"
#include "morph_work_internal.h"

namespace c4d {
namespace detail {
namespace {

constexpr int kGuessSourcesPerContour = 24;  // RbfProject's first-guess RBF: chain points per matched contour used
                                             // as sources (the projection and relaxation refine the rest; 48
                                             // gave the same meshes at 4× the RBF time)
constexpr int kProjectionIterations = 3;     // regularised projection rounds (the relaxation re-projects)
constexpr double kStiffness = 1.0;           // weight of the Laplacian term against the closest-point term
constexpr double kRetryMinGoodShare = 0.85;  // a frame with fewer of its angles in 40–80° is tried again
constexpr int kRetrySweepFactor = 8;         // the first retry's relaxation rounds × this, each retry's after it × 2
constexpr int kPlaneSnapRelaxRounds = 1;     // relaxation rounds after the plane snap, each followed by another snap
constexpr int kUntangleRounds = 4;           // where triangles intersect after the relaxation, rounds of umbrella steps
                                             // within the surface around them (angle_repair.h untangle)

// Uniform ("umbrella") Laplacian: (L x)_i = x_i − mean of the neighbours of i.
SparseMatrix uniform_laplacian(const std::vector<std::vector<std::uint32_t>>& nb) {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t i = 0; i < nb.size(); ++i) {
    const auto I = static_cast<int>(i);
    t.emplace_back(I, I, 1.0);
    for (std::uint32_t j : nb[i]) t.emplace_back(I, static_cast<int>(j), -1.0 / static_cast<double>(nb[i].size()));
  }
  SparseMatrix L(static_cast<int>(nb.size()), static_cast<int>(nb.size()));
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

Eigen::MatrixXd to_matrix(const std::vector<Vec3>& p) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(p.size()), 3);
  for (std::size_t i = 0; i < p.size(); ++i) m.row(static_cast<Eigen::Index>(i)) << p[i].x, p[i].y, p[i].z;
  return m;
}

std::vector<Vec3> from_matrix(const Eigen::MatrixXd& m) {
  std::vector<Vec3> p(static_cast<std::size_t>(m.rows()));
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto I = static_cast<Eigen::Index>(i);
    p[i] = {m(I, 0), m(I, 1), m(I, 2)};
  }
  return p;
}

// Frame 0's median edge length (mm): the unit of the spacings and reaches.
double median_edge_length(const TriangleMesh& m) {
  std::vector<double> edge_lengths;
  for (const Triangle& tri : m.triangles) edge_lengths.push_back(distance(m.positions[tri[0]], m.positions[tri[1]]));
  std::nth_element(edge_lengths.begin(), edge_lengths.begin() + static_cast<std::ptrdiff_t>(edge_lengths.size() / 2),
                   edge_lengths.end());
  return edge_lengths.empty() ? 0.0 : edge_lengths[edge_lengths.size() / 2];
}

// Everything the frames share, from frame 0's mesh (MorphWork).
void prepare(MorphWork& w) {
  const TriangleMesh& frame0 = w.frame0;
  w.project = w.opt.method == MorphMethod::RbfProject;
  w.nv = frame0.positions.size();
  w.nb = vertex_neighbours(w.nv, frame0.triangles);
  w.chains = find_chains(w.seq, frame0);
  build_bands(w);
  w.incident.resize(w.nv);
  for (std::size_t f = 0; f < frame0.triangles.size(); ++f)
    for (std::uint32_t v : frame0.triangles[f]) w.incident[v].push_back(static_cast<std::uint32_t>(f));
  w.ring_start.assign(w.nv + 1, 0);
  for (std::size_t i = 0; i < w.nv; ++i) {
    w.ring_index.insert(w.ring_index.end(), w.nb[i].begin(), w.nb[i].end());
    w.ring_start[i + 1] = w.ring_index.size();
  }
  if (w.project) build_relax_layout(w);
  w.median_edge = median_edge_length(frame0);
  w.slide_spacing = w.project ? w.steps.slide_spacing * w.median_edge : 0.0;
  for (const Slice& s0 : w.seq.frames.front().slices) w.counts[s0.id] = static_cast<int>(s0.contours.size());
  if (w.project && w.seq.frames.size() > 1) {
    const SparseMatrix L = uniform_laplacian(w.nb);
    w.LtL = SparseMatrix(L.transpose() * L);
  }
  w.carry = frame0.positions;
}

// Adds the vertex farthest from the sources' plane as a fixed point when all sources are coplanar
// (the paper's "far point"), so the RBF system stays regular.
void add_far_point(const std::vector<Vec3>& verts, const Vec3& normal, std::vector<Vec3>& src, std::vector<Vec3>& dst) {
  if (src.empty()) return;
  double lo = 1e300, hi = -1e300;
  for (const Vec3& p : src) {
    lo = std::min(lo, dot(p, normal));
    hi = std::max(hi, dot(p, normal));
  }
  if (hi - lo > 1e-6) return;
  std::size_t best = 0;
  double far = -1;
  for (std::size_t i = 0; i < verts.size(); ++i) {
    const double d = std::abs(dot(verts[i], normal) - lo);
    if (d > far) {
      far = d;
      best = i;
    }
  }
  src.push_back(verts[best]);
  dst.push_back(verts[best]);
}

// Step 1: the paper's RBF (eq. 9) from the matched chain points, subsampled as sources. RbfProject takes it
// as a first guess (one step; where its system fails, the projection starts from the previous frame).
void rbf_guess(const MorphWork& w, FrameWork& f) {
  std::vector<Vec3> src, dst;
  const int per_contour = w.project ? kGuessSourcesPerContour : w.opt.sources_per_contour;
  const std::size_t budget =
      static_cast<std::size_t>(std::max(1, per_contour)) * static_cast<std::size_t>(std::max(1, f.fr.matched));
  const std::size_t stride = std::max<std::size_t>(1, f.matched.size() / budget);
  for (std::size_t k = 0; k < f.matched.size(); k += stride) {
    src.push_back(f.x[f.matched[k].vertex]);
    dst.push_back(f.matched[k].position);
  }
  add_far_point(f.x, w.seq.normal, src, dst);
  f.fr.sources = static_cast<int>(src.size());
  if (src.empty()) return;
  try {
    deform_rbf(f.x, src, dst, w.project ? 1 : w.opt.rbf_steps);
  } catch (const SolverError&) {
    if (!w.project) throw;
    f.x = w.carry;  // the projection still fits the frame
  }
}

// The chain vertices that slide along a matched contour (f.slide_line), and those that do so through the
// relaxation (f.sliding: not on a held slice).
void mark_sliding(const MorphWork& w, FrameWork& f) {
  f.slide_line.assign(w.nv, -1);
  f.slide_hint.assign(w.nv, -1);
  f.sliding.assign(w.nv, 0);
  f.on_contour.assign(w.nv, 0);
  for (const ChainTarget& m : f.matched)
    if (m.line >= 0) {
      f.slide_line[m.vertex] = m.line;
      f.sliding[m.vertex] = !f.held.count(m.slice);
    }
}

// Step 2: Laplacian-regularised projection onto frame t's own `surface` (kProjectionIterations rounds of
// x = (I + αLᵀL)⁻¹ (closest points + αLᵀL x₀)), then an exact projection, whose normals serve the first
// relaxation round (each round's closing projection gives the next one's).
void project_onto_surface(MorphWork& w, FrameWork& f, const TriangleMesh& surface) {
  const std::size_t nv = w.nv;
  f.surface = std::make_unique<SurfaceProjector>(surface);
  f.proj = Projector{f.surface.get(), {}, &w.layout.order};
  if (!w.factored) {  // the system depends on the connectivity only: factored once
    SparseMatrix W(static_cast<int>(nv), static_cast<int>(nv));
    std::vector<Eigen::Triplet<double>> diagonal;
    for (std::size_t i = 0; i < nv; ++i) diagonal.emplace_back(static_cast<int>(i), static_cast<int>(i), 1.0);
    W.setFromTriplets(diagonal.begin(), diagonal.end());
    if (!factor_lower(w.solver, SparseMatrix(W + kStiffness * w.LtL)))
      throw SolverError(ErrorCode::Internal, Location{w.seq.source, -1, f.t},
                        "failed to factor the deformation system");
    w.factored = true;
  }
  const Eigen::MatrixXd ref_term = kStiffness * (w.LtL * to_matrix(f.x));
  for (int it = 0; it < kProjectionIterations; ++it) {
    const std::vector<Vec3> p = f.proj.project(f.x);
    f.x = from_matrix(ldlt_solve(w.solver, Eigen::MatrixXd(to_matrix(p) + ref_term)));
  }
  const std::vector<Vec3> p = f.proj.project(f.x, &f.normals);
  double sum = 0, mx = 0;
  for (std::size_t i = 0; i < nv; ++i) {
    const double d = distance(p[i], f.x[i]);
    sum += d;
    mx = std::max(mx, d);
    f.x[i] = p[i];
  }
  f.fr.projection_mean = nv ? sum / static_cast<double>(nv) : 0;
  f.fr.projection_max = mx;
}

// What decides whether a frame is redone, and which of two tries is kept.
struct FrameQuality {
  std::size_t crossings = 0;  // intersecting triangle pairs left
  double worst = 0;           // smallest angle (degrees)
  double good = 0;            // share of angles in 40–80°
};

FrameQuality frame_quality(const std::vector<Vec3>& x, const std::vector<Triangle>& tris, std::size_t crossings) {
  const AngleQuality q = angle_quality(TriangleMesh{x, tris});
  return {crossings, q.min_angle_deg, q.pct_40_80 / 100.0};
}

// A frame needs no retry: no crossings, no angle below kRetryMinAngleDeg, at least kRetryMinGoodShare of its
// angles in 40–80°.
bool acceptable(const FrameQuality& q) {
  return q.crossings == 0 && q.worst >= kRetryMinAngleDeg && q.good >= kRetryMinGoodShare;
}

// a better than b: fewer crossings; then above the angle floor; then the larger smallest angle below it,
// or the larger share of good angles above it.
bool better(const FrameQuality& a, const FrameQuality& b, double floor_deg) {
  if (a.crossings != b.crossings) return a.crossings < b.crossings;
  const bool fa = a.worst >= floor_deg, fb = b.worst >= floor_deg;
  if (fa != fb) return fa;
  return fa ? a.good > b.good : a.worst > b.worst;
}

// Step 4: the few triangles the relaxation leaves crossing or thin (saddles of splitting contours): their
// vertices move within the frame's surface (along their contour when on one), untangling, then maximising
// their ring's smallest angle. `fixed` vertices stay.
void repair_triangles(const MorphWork& w, FrameWork& f, const std::vector<char>& fixed) {
  auto snap_to = [&](std::uint32_t v, Vec3 c) {
    return f.on_contour[v] ? slide(f, v, c) : f.surface->walk(c, nullptr, &f.proj.hints[v]);
  };
  f.fr.intersecting_pairs = untangle(f.x, w.frame0.triangles, fixed, snap_to, kUntangleRounds);
  if (w.opt.angle_repair.passes > 0)
    f.fr.angle_repairs = repair_small_angles(f.x, w.frame0.triangles, fixed, snap_to, w.opt.angle_repair);
}

// One try of steps 3–4 from the projected frame: sliding chain vertices onto their contours, relaxation,
// the snaps onto the contours, the triangle repair. Returns the frame's quality.
FrameQuality one_try(const MorphWork& w, FrameWork& f, const MorphTry& tr) {
  put_sliding_on_contours(f);
  relax(w, f, tr);
  if (tr.chains_onto_contours) snap_chains_to_contours(w, f);
  if (w.steps.plane_snap && !f.lines.empty()) {
    snap_to_planes(w, f, tr);
    // The triangles around the snapped vertices relax again (those slide along their contours), which
    // brings more vertices near the planes for another snap.
    for (int k = 0; k < kPlaneSnapRelaxRounds; ++k) {
      relax_round(w, f, tr);
      snap_to_planes(w, f, tr);
    }
  }
  const std::vector<char> fixed = snap_contour_corners(w, f, tr);
  repair_triangles(w, f, fixed);
  return frame_quality(f.x, w.frame0.triangles, f.fr.intersecting_pairs);
}

// What every try starts from: the frame after the projection.
struct TryStart {
  std::vector<Vec3> x, normals;
  std::vector<std::int32_t> hints, slide_line;
};

// Back to `start` for a retry, with no chain vertex on its contour.
void restart(FrameWork& f, const TryStart& start) {
  f.x = start.x;
  f.normals = start.normals;
  f.proj.hints = start.hints;
  std::fill(f.sliding.begin(), f.sliding.end(), 0);
  std::fill(f.on_contour.begin(), f.on_contour.end(), 0);
  std::fill(f.slide_hint.begin(), f.slide_hint.end(), -1);
  f.slide_line = start.slide_line;
  f.fr.plane_snapped = 0;
  f.fr.sliding = 0;
  f.fr.redone = true;
}

// Try `attempt` (from 1) after `before`: more sweeps, no saddle weights, no early end of a round, only snaps
// that lose no angle in 40–80°, any vertex for a corner.
MorphTry retry(const MorphTry& before, int attempt) {
  MorphTry tr = before;
  tr.sweep_factor = attempt == 1 ? kRetrySweepFactor : 2 * before.sweep_factor;
  tr.relax_settled = 0;
  tr.saddle_weights = false;
  tr.chains_onto_contours = false;
  tr.plane_snap_good_loss = 0;
  tr.corner_candidates = 1;
  tr.corner_any_vertex = true;
  return tr;
}

// Steps 3–4, tried again while the frame misses the criteria. A frame that ends with a triangle angle below
// kRetryMinAngleDeg, fewer than kRetryMinGoodShare of its angles in 40–80° or crossing triangles (a band
// crowded as a branch point nears a slice or a contour shrinks fast; sliding chains hold the bands between
// them to frame 0's vertex count) is done again from the projection (restart, retry), MorphSteps::
// retry_attempts times, and crossing_retry_attempts more while the best try still has crossing triangles
// (the surface would not be valid), until a try meets the criteria; the best try is kept.
void relax_with_retries(const MorphWork& w, FrameWork& f) {
  const TryStart start{f.x, f.normals, f.proj.hints, f.slide_line};
  std::vector<Vec3> best;  // the best try so far
  MorphFrameReport best_report;
  FrameQuality best_quality;
  MorphTry tr;
  for (int attempt = 0;; ++attempt) {
    if (attempt >= 1) {
      tr = retry(tr, attempt);
      restart(f, start);
    }
    const FrameQuality q = one_try(w, f, tr);
    if (attempt == 0 || better(q, best_quality, kRetryMinAngleDeg)) {
      best = f.x;
      best_report = f.fr;
      best_quality = q;
    }
    if (acceptable(q)) break;
    const int last = std::max(0, w.steps.retry_attempts) +
                     (best_quality.crossings > 0 ? std::max(0, w.steps.crossing_retry_attempts) : 0);
    if (attempt >= last) break;
  }
  if (f.fr.redone) {  // the best of the tries (report: redone, whichever it was)
    f.x = std::move(best);
    f.fr = best_report;
    f.fr.redone = true;
  }
}

// Frame t from the previous frame's mesh (f.x), up to its contour fit (step 5, fit_frame).
void morph_frame(MorphWork& w, FrameWork& f, const SurfaceOf& surface_of) {
  const auto t = static_cast<std::size_t>(f.t);
  if (w.opt.vertical_deformation) vertical_predeformation(w, f);
  match_chains(w, f);
  if (w.project && w.slide_spacing > 0) hold_chains(w, f, surface_of(t));
  rbf_guess(w, f);
  if (w.project) {
    mark_sliding(w, f);
    project_onto_surface(w, f, surface_of(t));
    mark_saddle_zone(w, f);
    relax_with_retries(w, f);
  }
  for (const Vec3& p : f.x)
    if (!is_finite(p))
      throw SolverError(ErrorCode::Internal, Location{w.seq.source, -1, f.t},
                        "the deformation produced non-finite positions");
}

}  // namespace

std::vector<Vec3> Projector::project(const std::vector<Vec3>& x, std::vector<Vec3>* normals) const {
  std::vector<Vec3> p(x.size());
  if (normals) normals->resize(x.size());
  hints.resize(x.size(), -1);
  const bool ordered = order != nullptr && order->size() == x.size();
  tbb::parallel_for(std::size_t(0), x.size(), [&](std::size_t k) {
    const std::size_t i = ordered ? (*order)[k] : k;
    p[i] = surface->walk(x[i], normals ? &(*normals)[i] : nullptr, &hints[i]);
  });
  return p;
}

MeshSequence morph_sequence(const Sequence& seq, const TriangleMesh& frame0, const SurfaceOf& surface_of,
                            const MorphOptions& opt, const MorphSteps& steps, MorphReport* report) {
  const std::size_t frames = seq.frames.size();
  MeshSequence out;
  out.triangles = frame0.triangles;
  out.positions.resize(std::max<std::size_t>(1, frames));
  out.positions[0] = frame0.positions;
  for (const Frame& f : seq.frames) out.times_ms.push_back(f.time_ms);
  MorphReport local;
  MorphWork w(seq, frame0, opt, steps, report ? *report : local);
  w.rep.frames.assign(frames, {});
  w.rep.submeshes = submesh_lifetimes(seq);
  prepare(w);
  // Step 5 (the contour fit) of frame t runs as a task beside frame t+1's morph: the next frame starts from
  // the mesh before the fit (MorphWork::carry), so nothing waits for it. Its result depends on its frame only.
  tbb::task_group fits;
  std::vector<std::exception_ptr> fit_errors(frames);
  std::exception_ptr morph_error;
  try {
    for (std::size_t t = 1; t < frames; ++t) {
      FrameWork f(static_cast<int>(t), w.rep.frames[t], w.carry);
      morph_frame(w, f, surface_of);
      w.carry = f.x;
      if (!(w.project && steps.contour_fit)) {
        out.positions[t] = std::move(f.x);
        continue;
      }
      fits.run([&w, &out, &fit_errors, t, before = std::move(f.x)] {
        try {
          fit_frame(w, t, before, out.positions[t]);
        } catch (...) {
          fit_errors[t] = std::current_exception();
        }
      });
    }
  } catch (...) {
    morph_error = std::current_exception();
  }
  fits.wait();  // the tasks keep their errors
  // Fits run only for frames before one whose morph failed, so a fit's error is reported first (the lowest
  // frame's), as when the frames were done one after the other.
  for (const std::exception_ptr& e : fit_errors)
    if (e) std::rethrow_exception(e);
  if (morph_error) std::rethrow_exception(morph_error);
  return out;
}

}  // namespace detail

MeshSequence morph_sequence(const Sequence& seq, const TriangleMesh& frame0, const std::vector<TriangleMesh>& surfaces,
                            const MorphOptions& opt, MorphReport* report) {
  if (opt.method == MorphMethod::RbfProject && surfaces.size() != seq.frames.size())
    throw SolverError(ErrorCode::Internal, {}, "morph_sequence: RbfProject needs one surface per frame");
  return morph_sequence(
      seq, frame0, [&surfaces](std::size_t t) -> const TriangleMesh& { return surfaces[t]; }, opt, report);
}

MeshSequence morph_sequence(const Sequence& seq, const TriangleMesh& frame0,
                            const std::function<const TriangleMesh&(std::size_t)>& surface_of, const MorphOptions& opt,
                            MorphReport* report) {
  return detail::morph_sequence(seq, frame0, surface_of, opt, detail::MorphSteps{}, report);
}

}  // namespace c4d
