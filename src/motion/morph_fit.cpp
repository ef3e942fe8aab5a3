// Step 5 of the 4D morph (Lim et al. 2014, "4D Morphing of the Heart Model"; Miara et al. §III.E): last,
// a small smooth fit of the frame's mesh onto all its contours where the surface cuts across them
// (contour_fit.h), kept only where it harms nothing: no more crossing triangles, no angle below a floor
// that was above it (angles it takes below kRetryMinAngleDeg are repaired within the fitted surface
// first). The next frame starts from the mesh before the fit, so the fit runs beside it.
#include <algorithm>

#include "contour4d/metrics/quality.h"
#include "contour4d/metrics/topology.h"
#include "contour4d/motion/contour_fit.h"
#include "contour4d/surface/angle_repair.h"
#include "morph_work_internal.h"

namespace c4d::detail {
namespace {

constexpr ContourFitOptions kFit{};     // the fit (contour_fit.h's defaults)
constexpr int kFitRounds = 4;           // guarded_contour_fit: fits, each keeping more vertices in place
constexpr double kFitMinAngleDeg = 20;  // the fit leaves no angle below this that was above it
constexpr double kFitGoalMm = 0.2;      // a frame whose fit leaves a contour sample farther than this from the mesh is
                                        // fitted again from before the fit with kFitFallbackMinAngleDeg, and the
                                        // closer result is kept
constexpr double kFitFallbackMinAngleDeg = 15;  // see kFitGoalMm (contours touching at a saddle need it; as a
                                                // floor on every frame it would leave more small angles)

// Every contour of a frame, as closed polylines (mm).
std::vector<std::vector<Vec3>> frame_contours(const Frame& f) {
  std::vector<std::vector<Vec3>> out;
  for (const Slice& s : f.slices)
    for (const Contour& c : s.contours) out.push_back(c.points);
  return out;
}

// Marks `mark` and `rings` rings of neighbours around the marked vertices (rings in CSR form).
void grow(std::vector<char>& mark, const std::vector<std::size_t>& ring_start,
          const std::vector<std::uint32_t>& ring_index, int rings) {
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<char> grown = mark;
    for (std::size_t v = 0; v < mark.size(); ++v)
      if (mark[v])
        for (std::size_t r = ring_start[v]; r < ring_start[v + 1]; ++r) grown[ring_index[r]] = 1;
    mark.swap(grown);
  }
}

// Vertices of the triangles of `after` whose smallest angle fell below min(its angle in `before`,
// floor_deg); true if any.
bool mark_lost_angles(const std::vector<Vec3>& before, const std::vector<Vec3>& after,
                      const std::vector<Triangle>& tris, double floor_deg, std::vector<char>& mark) {
  bool any = false;
  for (const Triangle& tri : tris) {
    const double a = min_angle_deg(after[tri[0]], after[tri[1]], after[tri[2]]);
    if (a >= floor_deg || a >= min_angle_deg(before[tri[0]], before[tri[1]], before[tri[2]]) - 1e-9) continue;
    any = true;
    for (std::uint32_t v : tri) mark[v] = 1;
  }
  return any;
}

// The fit's state across its rounds (guarded_contour_fit).
struct GuardedFit {
  const MorphWork& w;
  const std::vector<Vec3>& x;                  // the mesh before the fit
  const std::vector<Vec3>& samples;            // the contour samples
  double floor_deg;                            // no angle falls below min(this, its angle before)
  std::vector<char> fixed;                     // vertices that stay
  std::vector<std::int32_t> sample_triangles;  // each call's closest points start the next call's search
                                               // (the meshes differ only near the far samples)
};

// The largest sample distance to (positions, frame 0's triangles).
double largest_distance(GuardedFit& g, const std::vector<Vec3>& positions) {
  ContourFitOptions measure = kFit;
  measure.iterations = 0;
  std::vector<Vec3> probe = positions;
  return fit_to_points(probe, g.w.frame0.triangles, g.samples, g.fixed, measure, &g.sample_triangles).max_before_mm;
}

// Where the fit left a triangle's smallest angle below min(its angle before, kRetryMinAngleDeg), the vertices
// there (and a ring) move within the fitted surface to raise it (repair_small_angles). The repair is kept
// where the fit left an angle below floor_deg, or where it keeps the fit's largest contour distance `fit_max`
// (it moves vertices within the piecewise-flat surface, which can cut across a contour again); `repaired`
// gets its vertices then. `bad` gets the vertices of triangles still below the floor.
void repair_fitted(GuardedFit& g, std::vector<Vec3>& fitted, double fit_max, std::vector<char>& bad,
                   std::vector<char>& repaired) {
  const std::vector<Triangle>& tris = g.w.frame0.triangles;
  const std::size_t nv = g.x.size();
  if (!mark_lost_angles(g.x, fitted, tris, kRetryMinAngleDeg, bad)) return;
  std::vector<char> frozen(nv, 1), near = bad;
  grow(near, g.w.ring_start, g.w.ring_index, 1);
  for (std::size_t v = 0; v < nv; ++v)
    if (near[v]) frozen[v] = g.fixed[v];
  std::vector<Vec3> mended = fitted;
  const SurfaceProjector surface(TriangleMesh{fitted, tris});
  AngleRepairOptions local = g.w.opt.angle_repair;
  local.target_deg = std::max(local.target_deg, kRetryMinAngleDeg);
  repair_small_angles(
      mended, tris, frozen, [&](std::uint32_t, Vec3 p) { return surface.closest(p); }, local);
  std::vector<char> below_floor(nv, 0);
  if (mark_lost_angles(g.x, fitted, tris, g.floor_deg, below_floor) ||
      largest_distance(g, mended) <= fit_max + kFit.tolerance_mm) {
    fitted = std::move(mended);
    repaired = std::move(near);
  }
  std::fill(bad.begin(), bad.end(), 0);
  mark_lost_angles(g.x, fitted, tris, g.floor_deg, bad);
}

// Marks in `bad` the vertices of triangle pairs that cross in `fitted` when more pairs cross than in g.x
// (only pairs with a triangle that moved can have changed).
void mark_new_crossings(const GuardedFit& g, const std::vector<Vec3>& fitted, std::vector<char>& bad) {
  const std::vector<Triangle>& tris = g.w.frame0.triangles;
  std::vector<char> touched(tris.size(), 0);
  for (std::size_t f = 0; f < tris.size(); ++f)
    for (std::uint32_t v : tris[f]) touched[f] |= !(fitted[v] == g.x[v]);
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  if (count_self_intersections_of(TriangleMesh{fitted, tris}, touched, &pairs, tris.size()) >
      count_self_intersections_of(TriangleMesh{g.x, tris}, touched))
    for (const auto& [a, b] : pairs)
      for (std::size_t f : {a, b})
        for (std::uint32_t v : tris[f]) bad[v] = 1;
}

// fit_to_points on the contour samples, kept only where it harms nothing. Where the fit loses angles, they
// are repaired (repair_fitted), and the repaired vertices stay while the fit is done again around them.
// Where triangles still lose angles, or more triangles cross than before, those vertices and two rings
// around them stay at their place before the fit and it is done again. Up to kFitRounds rounds; if no fit
// is harmless, x stays as it was.
ContourFitReport guarded_contour_fit(const MorphWork& w, std::vector<Vec3>& x, const std::vector<Vec3>& samples,
                                     double floor_deg) {
  GuardedFit g{w, x, samples, floor_deg, std::vector<char>(w.nv, 0), {}};
  ContourFitReport rep;
  std::vector<Vec3> start = x;  // what each round fits from
  std::vector<Vec3> harmless;   // the last harmless result
  for (int round = 0; round < kFitRounds; ++round) {
    std::vector<Vec3> fitted = start;
    const ContourFitReport cf = fit_to_points(fitted, w.frame0.triangles, samples, g.fixed, kFit, &g.sample_triangles);
    if (round == 0) rep.max_before_mm = rep.max_after_mm = cf.max_before_mm;
    if (cf.moved == 0) break;
    std::vector<char> bad(x.size(), 0), repaired(x.size(), 0);
    repair_fitted(g, fitted, cf.max_after_mm, bad, repaired);
    mark_new_crossings(g, fitted, bad);
    if (std::find(bad.begin(), bad.end(), 1) == bad.end()) {
      harmless = fitted;
      if (std::find(repaired.begin(), repaired.end(), 1) == repaired.end()) break;
      start = std::move(fitted);  // fit again around the repaired vertices, which stay
      for (std::size_t v = 0; v < x.size(); ++v)
        if (repaired[v]) g.fixed[v] = 1;
      continue;
    }
    grow(bad, w.ring_start, w.ring_index, 2);
    for (std::size_t v = 0; v < x.size(); ++v)
      if (bad[v]) {
        g.fixed[v] = 1;
        start[v] = x[v];
      }
  }
  if (harmless.empty()) return rep;
  for (std::size_t v = 0; v < x.size(); ++v) rep.moved += !(harmless[v] == x[v]);
  x = std::move(harmless);
  rep.max_after_mm = largest_distance(g, x);
  return rep;
}

}  // namespace

// Step 5 of frame t from its mesh `before` into `out`, its report's fit figures filled: the guarded fit with
// kFitMinAngleDeg, and once more with kFitFallbackMinAngleDeg when that leaves a sample beyond kFitGoalMm
// (the closer of the two is kept).
void fit_frame(const MorphWork& w, std::size_t t, const std::vector<Vec3>& before, std::vector<Vec3>& out) {
  std::vector<Vec3> fitted = before;
  const std::vector<Vec3> samples = contour_fit_samples(frame_contours(w.seq.frames[t]), kFit.step_mm);
  ContourFitReport cf = guarded_contour_fit(w, fitted, samples, kFitMinAngleDeg);
  if (cf.max_after_mm > kFitGoalMm) {
    std::vector<Vec3> y = before;
    const ContourFitReport again = guarded_contour_fit(w, y, samples, kFitFallbackMinAngleDeg);
    if (again.max_after_mm < cf.max_after_mm) {
      fitted = std::move(y);
      cf.moved = again.moved;
      cf.max_after_mm = again.max_after_mm;
    }
  }
  MorphFrameReport& r = w.rep.frames[t];  // only this task writes these fields of frame t
  r.fit_moved = cf.moved;
  r.fit_max_before = cf.max_before_mm;
  r.fit_max_after = cf.max_after_mm;
  out = std::move(fitted);
}

}  // namespace c4d::detail
