// Breath-hold slice alignment on long-axis curves (slice_alignment.h, align_slices_to_curves). Neither paper
// corrects slice shifts. A study with long-axis contours (biv-me's LAX views) pins every short-axis slice: where
// a long-axis contour of a structure crosses a short-axis plane, that plane's contour of the same structure
// should pass, as cardiac modelling pipelines that correct breath-hold shifts from contour intersections assume.
// Here every crossing of every frame votes for one in-plane move per slice (one breath-hold per slice), found by
// Gauss–Newton on the crossings' distances to the moved contours with Tukey's bisquare weights; the long-axis
// views stay where they are.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "contour4d/core/slice_alignment.h"
#include "slice_alignment_internal.h"

namespace c4d {
namespace {

constexpr int kMinCrossings = 4;           // fewer crossings than this: the slice is not moved
constexpr double kMinTrusted = 3.0;        // nor where their weights add up to less than this
constexpr double kMinConditioning = 0.05;  // smallest / largest eigenvalue of the move's normal matrix
constexpr int kMaxSteps = 50;              // Gauss–Newton steps
constexpr double kGapSteps = 4.0;          // a curve step longer than this many median steps is a gap

// One crossing of a long-axis curve with a slice plane, in the plane's (u, v) coordinates, and the contours of
// the same structure on that slice in the same frame.
struct Crossing {
  Vec2 q;
  const std::vector<std::vector<Vec2>>* contours = nullptr;
};

struct SliceData {
  int id = 0;
  double offset = 0;
  std::map<std::pair<std::size_t, std::string>, std::vector<std::vector<Vec2>>> contours;  // (frame, label)
  std::vector<Crossing> crossings;
};

Vec2 in_plane(const Sequence& seq, Vec3 p) { return {dot(p, seq.u), dot(p, seq.v)}; }

// The labels of `seq` with curves "lax-" + label (only options.label when set), sorted.
std::vector<std::string> labels_with_curves(const Sequence& seq, const std::vector<GuideCurve>& curves,
                                            const std::string& only) {
  std::vector<std::string> out;
  for (const std::string& l : labels(seq)) {
    if (!only.empty() && l != only) continue;
    const bool has =
        std::any_of(curves.begin(), curves.end(), [&](const GuideCurve& c) { return c.label == "lax-" + l; });
    if (has) out.push_back(l);
  }
  return out;
}

// Every slice id with its contours of the chosen labels, per frame, in (u, v).
std::map<int, SliceData> slice_contours(const Sequence& seq, const std::vector<std::string>& chosen) {
  std::map<int, SliceData> out;
  for (std::size_t f = 0; f < seq.frames.size(); ++f)
    for (const Slice& s : seq.frames[f].slices) {
      SliceData& d = out[s.id];
      d.id = s.id;
      d.offset = s.offset;
      for (const Contour& c : s.contours) {
        if (std::find(chosen.begin(), chosen.end(), c.label) == chosen.end() || c.points.size() < 3) continue;
        std::vector<Vec2> poly;
        for (const Vec3& p : c.points) poly.push_back(in_plane(seq, p));
        d.contours[{f, c.label}].push_back(std::move(poly));
      }
    }
  return out;
}

// Where `curve` crosses the plane dot(p, normal) = offset: between consecutive points on either side, unless
// that step is a gap in the drawing.
std::vector<Vec3> plane_crossings(const GuideCurve& curve, Vec3 normal, double offset) {
  std::vector<Vec3> out;
  const std::vector<Vec3>& p = curve.points;
  if (p.size() < 2) return out;
  std::vector<double> steps;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) steps.push_back(distance(p[i], p[i + 1]));
  const double gap = kGapSteps * detail::median(steps);
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double a = dot(p[i], normal) - offset, b = dot(p[i + 1], normal) - offset;
    if ((a < 0) == (b < 0) || a == b || steps[i] > gap) continue;
    out.push_back(p[i] + (p[i + 1] - p[i]) * (a / (a - b)));
  }
  return out;
}

void add_crossings(const Sequence& seq, const std::vector<GuideCurve>& curves, SliceData& d) {
  for (const GuideCurve& c : curves) {
    if (c.label.rfind("lax-", 0) != 0 || c.frame < 0) continue;
    const auto it = d.contours.find({static_cast<std::size_t>(c.frame), c.label.substr(4)});
    if (it == d.contours.end()) continue;
    for (const Vec3& q : plane_crossings(c, seq.normal, d.offset))
      d.crossings.push_back({in_plane(seq, q), &it->second});
  }
}

// The closest point to q on the polygons moved by t.
Vec2 closest_on(const std::vector<std::vector<Vec2>>& polygons, Vec2 t, Vec2 q) {
  double best = std::numeric_limits<double>::infinity();
  Vec2 out = q;
  for (const std::vector<Vec2>& poly : polygons)
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vec2 c = closest_on_segment(poly[i] + t, poly[(i + 1) % poly.size()] + t, q);
      if (const double d = norm(q - c); d < best) best = d, out = c;
    }
  return out;
}

struct SliceMove {
  Vec2 t;
  bool moved = false;
  double weight = 0;
  double residual = 0;
};

// One in-plane move t minimising Σ ρ(|q − closest(contours + t)|) over the slice's crossings (Tukey's ρ):
// Gauss–Newton steps M dt = Σ w m |r|, m the unit residual, reweighted every step.
SliceMove fit_move(const std::vector<Crossing>& crossings, double min_scale) {
  SliceMove out;
  if (static_cast<int>(crossings.size()) < kMinCrossings) return out;
  Vec2 t{0, 0};
  std::vector<double> len(crossings.size());
  std::vector<Vec2> dir(crossings.size());
  for (int step = 0; step < kMaxSteps; ++step) {
    for (std::size_t i = 0; i < crossings.size(); ++i) {
      const Vec2 r = crossings[i].q - closest_on(*crossings[i].contours, t, crossings[i].q);
      len[i] = norm(r);
      dir[i] = len[i] > 0 ? r * (1.0 / len[i]) : Vec2{0, 0};
    }
    const double scale = std::max(min_scale, detail::kMadToSigma * detail::median(len));
    double m00 = 0, m01 = 0, m11 = 0, b0 = 0, b1 = 0, trusted = 0;
    for (std::size_t i = 0; i < crossings.size(); ++i) {
      const double w = detail::tukey_weight(len[i], scale);
      m00 += w * dir[i].x * dir[i].x;
      m01 += w * dir[i].x * dir[i].y;
      m11 += w * dir[i].y * dir[i].y;
      b0 += w * dir[i].x * len[i];
      b1 += w * dir[i].y * len[i];
      trusted += w;
    }
    const double tr = m00 + m11, det = m00 * m11 - m01 * m01;
    const double lmax = 0.5 * (tr + std::sqrt(std::max(0.0, tr * tr - 4 * det)));
    if (trusted < kMinTrusted || lmax <= 0 || det / lmax < kMinConditioning * lmax) return SliceMove{};
    const Vec2 dt{(m11 * b0 - m01 * b1) / det, (m00 * b1 - m01 * b0) / det};
    t = t + dt;
    out.weight = trusted / static_cast<double>(crossings.size());
    if (norm(dt) < 1e-9) break;
  }
  for (std::size_t i = 0; i < crossings.size(); ++i) {
    len[i] = norm(crossings[i].q - closest_on(*crossings[i].contours, t, crossings[i].q));
  }
  out.t = t;
  out.moved = true;
  out.residual = detail::median(len);
  return out;
}

}  // namespace

SliceAlignment align_slices_to_curves(Sequence& seq, const std::vector<GuideCurve>& curves,
                                      const SliceAlignmentOptions& options) {
  const std::vector<std::string> chosen = labels_with_curves(seq, curves, options.label);
  if (chosen.empty()) return align_slices(seq, options);
  SliceAlignment out;
  out.method = "long-axis";
  for (const std::string& l : chosen) out.label += (out.label.empty() ? "" : "+") + l;
  std::map<int, SliceData> slices = slice_contours(seq, chosen);
  std::vector<SliceData*> order;
  for (auto& [id, d] : slices) order.push_back(&d);
  std::sort(order.begin(), order.end(), [](const SliceData* a, const SliceData* b) { return a->offset < b->offset; });
  for (SliceData* d : order) {
    add_crossings(seq, curves, *d);
    const SliceMove m = fit_move(d->crossings, options.min_scale_mm);
    SliceShift s;
    s.slice = d->id;
    s.offset_mm = d->offset;
    s.crossings = static_cast<int>(d->crossings.size());
    s.weight = m.weight;
    s.residual_mm = m.residual;
    if (m.moved) {
      s.shift = seq.u * m.t.x + seq.v * m.t.y;
      s.shift_mm = norm(m.t);
    }
    out.shifts.push_back(s);
  }
  for (const SliceShift& s : out.shifts)
    if (s.shift_mm > 0) detail::move_slice(seq, s.slice, s.shift);
  return out;
}

}  // namespace c4d
