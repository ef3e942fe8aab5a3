// All frames, the frames carried where the frame on the plan is not their surface (carry_unfit_internal.h):
// Miara et al. §III.D–E's per-frame displacements for the sub-meshes whose contour topology changes (Fig. 14),
// each carried onto the frame's own surface from a placed frame (carry.h); frames left with crossing triangles
// carried again from a neighbour in the cycle.
#include "carry_unfit_internal.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <tuple>

#include <tbb/parallel_for.h>

#include "contour4d/core/contour.h"
#include "contour4d/metrics/quality.h"
#include "contour4d/metrics/topology.h"
#include "contour4d/surface/reconstruct.h"

namespace c4d::detail {

namespace {

// The indices in `f.slices` of its lowest and highest slice with contours along the stack; none when fewer than
// three slices have contours (then no end is left out).
std::optional<std::array<std::size_t, 2>> end_slices(const Sequence& seq, const Frame& f) {
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t k = 0; k < f.slices.size(); ++k)
    if (!f.slices[k].contours.empty()) order.emplace_back(dot(slice_plane(seq, f.slices[k]).origin, seq.normal), k);
  if (order.size() < 3) return std::nullopt;
  std::sort(order.begin(), order.end());
  return std::array<std::size_t, 2>{order.front().second, order.back().second};
}

// Frame `f` with the contours of its first, last or both end slices (along the stack) left out: `ends` 1, 2 or 3.
Frame without_ends(const Sequence& seq, const Frame& f, int ends) {
  Frame out = f;
  const auto e = end_slices(seq, f);
  if (!e) return out;
  if (ends & 1) out.slices[(*e)[0]].contours.clear();
  if (ends & 2) out.slices[(*e)[1]].contours.clear();
  return out;
}

// Rounds of tangential smoothing when a carried frame is carried again (CarryOptions::relax_rounds): biv-me's
// systolic frames carried from diastole keep 83 % of their angles in 40–80° after 6 rounds, 85 % after 20. Not
// the first try's: 20 rounds fold a thin myocardial shell that 6 keep valid.
constexpr int kRetryRelaxRounds = 20;

// How a carried frame came out: crossing triangle pairs, then triangles with an angle below 25°, then the share
// of angles in 40–80°.
struct CarriedShape {
  std::size_t crossings = 0;
  std::size_t bad = 0;
  std::size_t triangles = 0;
  double share_40_80 = 0.0;
  // No crossing, at most 1 % of the triangles with an angle below 25° (rebuild.h's bound for a rebuilt frame),
  // and at least 85 % of the angles in 40–80° (the run's bound for carried frames, reconstruct_run.cpp).
  bool good() const { return crossings == 0 && bad * 100 <= triangles && share_40_80 >= 85.0; }
  bool operator<(const CarriedShape& o) const {
    return std::tie(crossings, bad, o.share_40_80) < std::tie(o.crossings, o.bad, share_40_80);
  }
};

// A frame with no triangle angle below this is taken as free of crossings without the (costly) exact test, as
// the untangling does (angle_repair.h): crossing triangles come from crowded, folded patches, which have slivers.
constexpr double kSliverDeg = 15.0;

// `m`'s shape; with `slivers_only`, the crossings are counted only where some angle is below kSliverDeg.
CarriedShape carried_shape(const TriangleMesh& m, bool slivers_only = false) {
  const TopologyOptions exact{.self_intersections = true, .counts_only = true};
  const AngleQuality q = angle_quality(m);
  const bool test = !slivers_only || q.min_angle_deg < kSliverDeg;
  return {test ? check_topology(m, exact).self_intersections : 0, q.bad_triangles, m.triangles.size(), q.pct_40_80};
}

// The end contours of frame t (the lowest and highest slice along the stack, as without_ends counts them) and how
// far each changed against frame s: |log| of the ratio of the slice's contour perimeters in t and s (infinite
// where s has no contour on that slice).
std::array<double, 2> end_changes(const Sequence& seq, int s, int t) {
  const Frame& to = seq.frames[static_cast<std::size_t>(t)];
  std::array<double, 2> change{0.0, 0.0};
  const auto ends = end_slices(seq, to);
  if (!ends) return change;
  auto length = [](const Slice& sl) {
    double l = 0.0;
    for (const Contour& c : sl.contours) l += perimeter(c.points);
    return l;
  };
  for (std::size_t e = 0; e < 2; ++e) {
    const Slice& end = to.slices[(*ends)[e]];
    double from = 0.0;
    for (const Slice& sl : seq.frames[static_cast<std::size_t>(s)].slices)
      if (sl.id == end.id) from = length(sl);
    const double now = length(end);
    change[e] = from > 0.0 && now > 0.0 ? std::abs(std::log(now / from)) : std::numeric_limits<double>::infinity();
  }
  return change;
}

// The tries after the first for frame t carried from frame s (without_ends' `ends`): more smoothing alone, then
// also the end contour that changed most against s left out of the matching, then the other, then both.
std::array<int, 4> retry_order(const Sequence& seq, int s, int t) {
  const std::array<double, 2> change = end_changes(seq, s, t);
  return change[1] > change[0] ? std::array<int, 4>{0, 2, 1, 3} : std::array<int, 4>{0, 1, 2, 3};
}

// Each carried frame's own one-frame surface (its geometry only), built once for the first carry and its retries,
// in parallel; the lowest frame's error is thrown.
std::map<int, TriangleMesh> own_surfaces(const Sequence& seq, const std::vector<int>& frames,
                                         const SurfaceOptions& options) {
  SurfaceOptions own = options;
  own.geometry_only = true;
  std::vector<TriangleMesh> built(frames.size());
  std::vector<std::exception_ptr> errors(frames.size());
  tbb::parallel_for(std::size_t{0}, frames.size(), [&](std::size_t k) {
    try {
      built[k] = reconstruct_frame(seq, frames[k], own);
    } catch (...) {
      errors[k] = std::current_exception();
    }
  });
  std::map<int, TriangleMesh> out;
  std::exception_ptr first;
  int first_frame = 0;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    if (errors[k] && (!first || frames[k] < first_frame)) first = errors[k], first_frame = frames[k];
    out[frames[k]] = std::move(built[k]);
  }
  if (first) std::rethrow_exception(first);
  return out;
}

// Frames `targets` carried from placed frame s (its positions in `out`) onto their own surfaces (carry.h), in
// one carry that shares its thin-plate factorisations. A carried frame whose triangles cross or are squeezed
// (more than 1 % with an angle below 25°, or less than 85 % of the angles in 40–80°) is carried again with
// more smoothing rounds (kRetryRelaxRounds), then also with an end contour (the one that changed most against
// the source first, then the other, then both) left out of the matching: a base contour that shrank to a
// fraction of the source's folds or squeezes the band above it, while the part beyond the next slice laid
// onto the frame's own dome (carry.h) keeps its shape. The first try that is good is kept, else the best
// (fewest crossings, then fewest poor triangles, then the largest share in 40–80°). Returns each target's
// result and shape, in the order of `targets`; `out` is not changed.
struct CarriedFrame {
  std::vector<Vec3> positions;
  CarryFrameReport report;
  CarriedShape shape;
};

using OwnSurface = std::function<const TriangleMesh&(int)>;  // frame t's own one-frame surface

std::vector<CarriedFrame> carry_from(const Sequence& seq, const MeshSequence& out, int s,
                                     const std::vector<int>& targets, const OwnSurface& own,
                                     const Reconstruct4DOptions& options) {
  const TriangleMesh from{out.positions[static_cast<std::size_t>(s)], out.triangles};
  CarryOptions retry_options = options.carry;
  retry_options.relax_rounds = std::max(retry_options.relax_rounds, kRetryRelaxRounds);
  auto carry = [&](const std::vector<int>& to, int ends, const CarryOptions& co, CarryReport& cr) {
    Sequence group = seq;
    group.frames = {seq.frames[static_cast<std::size_t>(s)]};
    for (int t : to) group.frames.push_back(without_ends(seq, seq.frames[static_cast<std::size_t>(t)], ends));
    return carry_frames(
        group, from, [&](std::size_t k) { return own(to[k - 1]); }, co, &cr);
  };
  CarryReport cr;
  const MeshSequence carried = carry(targets, 0, options.carry, cr);
  std::vector<CarriedFrame> result(targets.size());
  // The frames tried again run in parallel: each writes its own result only.
  tbb::parallel_for(std::size_t{0}, targets.size(), [&](std::size_t k) {
    CarriedFrame best{carried.positions[k + 1], cr.frames[k + 1], {}};
    best.report.source = s;
    best.shape = carried_shape(TriangleMesh{best.positions, out.triangles});
    for (int ends : retry_order(seq, s, targets[k])) {
      if (best.shape.good()) break;
      CarryReport again;
      MeshSequence retry = carry({targets[k]}, ends, retry_options, again);
      const CarriedShape other = carried_shape(TriangleMesh{retry.positions[1], out.triangles});
      if (other < best.shape) {
        best = {std::move(retry.positions[1]), again.frames[1], other};
        best.report.source = s;
      }
    }
    result[k] = std::move(best);
  });
  return result;
}

// The frames of `out` whose triangles cross (`shapes`; a frame not in it has none), each carried again from a
// neighbour in the cycle that has no crossing (the next frame first, then the previous one), in increasing
// frame order, the better result kept (CarriedShape's order): consecutive frames differ little, so the carry
// from a neighbour folds less than the one that failed (from a rebuilt frame far away in the cycle, or the
// morph's frame after frame). The other frames are not touched.
void recarry_crossing_frames(const Sequence& seq, MeshSequence& out, const OwnSurface& own,
                             const Reconstruct4DOptions& options, std::map<int, CarriedShape>& shapes,
                             std::vector<CarryFrameReport>& reports) {
  const auto n = static_cast<int>(seq.frames.size());
  for (auto& [t, shape] : shapes) {
    for (int s : {(t + 1) % n, (t + n - 1) % n}) {
      if (shape.crossings == 0) break;
      const auto found = shapes.find(s);
      if (s == t || (found != shapes.end() && found->second.crossings > 0)) continue;
      CarriedFrame again = std::move(carry_from(seq, out, s, {t}, own, options)[0]);
      if (!(again.shape < shape)) continue;
      shape = again.shape;
      reports[static_cast<std::size_t>(t)] = again.report;
      out.positions[static_cast<std::size_t>(t)] = std::move(again.positions);
    }
  }
}

}  // namespace

// The frames that do not fit the plan (a contour that appears, vanishes, splits or merges) or folded on it:
// the nearest rebuilt frame's mesh (in the cycle; the earlier one on a tie) carried onto each frame's own
// surface (carry_from), one carry per source frame; a frame whose triangles still cross is carried again from
// a neighbour (recarry_crossing_frames): biv-me's right ventricle in early diastole (frame 14), its base contour
// half the nearest rebuilt frame's, is carried again from frame 13, whose mesh is close to its own.
void carry_unfit(const Sequence& seq, MeshSequence& out, const Reconstruct4DOptions& options,
                 Reconstruct4DReport& rep) {
  const std::vector<int>& unfit = rep.rebuild.unfit;
  if (unfit.empty()) return;
  const auto n = static_cast<int>(seq.frames.size());
  auto nearest_fit = [&](int t) {
    int best = -1, best_d = n + 1;
    for (int s = 0; s < n; ++s) {
      if (out.positions[static_cast<std::size_t>(s)].empty()) continue;
      const int d = std::min(std::abs(s - t), n - std::abs(s - t));
      if (d < best_d) {
        best_d = d;
        best = s;
      }
    }
    return best;
  };
  std::map<int, std::vector<int>> by_source;
  for (int t : unfit) by_source[nearest_fit(t)].push_back(t);
  const std::map<int, TriangleMesh> built = own_surfaces(seq, unfit, options.surface);
  const OwnSurface own = [&](int t) -> const TriangleMesh& { return built.at(t); };
  std::map<int, CarriedShape> shapes;  // the carried frames'
  for (const auto& [s, targets] : by_source) {
    std::vector<CarriedFrame> carried = carry_from(seq, out, s, targets, own, options);
    for (std::size_t k = 0; k < targets.size(); ++k) {
      const auto t = static_cast<std::size_t>(targets[k]);
      rep.carry.frames[t] = carried[k].report;
      shapes[targets[k]] = carried[k].shape;
      out.positions[t] = std::move(carried[k].positions);
    }
  }
  recarry_crossing_frames(seq, out, own, options, shapes, rep.carry.frames);
}

// A whole sequence's frames whose triangles cross (a fold the morph or the carry from frame 0 could not undo),
// carried again from a neighbour (recarry_crossing_frames) onto their own surfaces: `surfaces` where the morph
// built them, else built here for those frames.
void recarry_all(const Sequence& seq, MeshSequence& out, const std::vector<TriangleMesh>* surfaces,
                 const Reconstruct4DOptions& options, Reconstruct4DReport& rep) {
  const std::size_t n = out.positions.size();
  std::vector<CarriedShape> all(n);
  tbb::parallel_for(std::size_t{1}, std::max<std::size_t>(1, n),
                    [&](std::size_t t) { all[t] = carried_shape(out.frame(t), true); });
  std::map<int, CarriedShape> shapes;
  std::vector<int> crossing;
  for (std::size_t t = 1; t < n; ++t) {
    shapes[static_cast<int>(t)] = all[t];
    if (all[t].crossings > 0) crossing.push_back(static_cast<int>(t));
  }
  if (crossing.empty()) return;
  rep.carry.frames.resize(n);
  std::map<int, TriangleMesh> built;
  if (!surfaces) built = own_surfaces(seq, crossing, options.surface);
  const OwnSurface own = [&](int t) -> const TriangleMesh& {
    return surfaces ? (*surfaces)[static_cast<std::size_t>(t)] : built.at(t);
  };
  recarry_crossing_frames(seq, out, own, options, shapes, rep.carry.frames);
}

}  // namespace c4d::detail
