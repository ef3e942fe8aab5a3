// Repairing drawn contours before validation (contour_repair.h). The stack model of Lim et al. 2014
// ("Model Definition", eqs. 1–4) needs closed simple polygons, one plane per slice id; clinical tools
// export open arcs, loops, spikes and re-acquired slices. Each flaw gets one defined repair, recorded.
#include "contour4d/core/contour_repair.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <tuple>

#include <fmt/format.h>

#include "contour4d/core/contour.h"
#include "contour4d/core/plane.h"

namespace c4d {

namespace {

constexpr int kMaxSplits = 32;                // loop splits per contour: bounds the work on pathological tracing
constexpr std::size_t kMaxLoopPoints = 2000;  // larger self-crossing contours are left to validation to refuse
                                              // (the split is quadratic; drawn contours have a few hundred points)
constexpr std::size_t kMaxRounds = 64;        // rounds of duplicate and spike removal

// A contour's points with their coordinates in the contour's own plane.
struct Flat {
  std::vector<Vec3> p3;
  std::vector<Vec2> p2;
};

Flat flatten(const std::vector<Vec3>& pts) {
  Vec3 c{};
  for (const Vec3& p : pts) c += p;
  c = c / static_cast<double>(std::max<std::size_t>(1, pts.size()));
  Vec3 n{};
  for (std::size_t i = 0; i < pts.size(); ++i) n += cross(pts[i] - c, pts[(i + 1) % pts.size()] - c);
  if (!(norm(n) > 0)) n = {0, 0, 1};
  const Plane pl = make_plane(c, n / norm(n));
  Flat f;
  f.p3 = pts;
  for (const Vec3& p : pts) f.p2.push_back(to_plane(pl, p));
  return f;
}

double median_spacing(const std::vector<Vec3>& p) {
  std::vector<double> d;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) d.push_back(distance(p[i], p[i + 1]));
  if (d.empty()) return 0;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

// Consecutive points closer than `tol` (and a last point on the first) merged; returns how many went.
std::size_t drop_duplicates(std::vector<Vec3>& p, double tol) {
  const std::size_t before = p.size();
  std::vector<Vec3> out;
  for (const Vec3& q : p)
    if (out.empty() || distance(out.back(), q) >= tol) out.push_back(q);
  while (out.size() > 1 && distance(out.back(), out.front()) < tol) out.pop_back();
  p = std::move(out);
  return before - p.size();
}

// Points where the tracing turns back by more than `deg` removed, until none is left; returns the
// largest distance from a removed point to its neighbours' chord.
// One pass, linear: a spike whose neighbour was just removed waits for the next pass.
double drop_spikes(std::vector<Vec3>& p, double deg, std::size_t& removed) {
  const double cos_limit = std::cos((180.0 - deg) * std::numbers::pi / 180.0);
  double moved = 0;
  std::vector<Vec3> out;
  out.reserve(p.size());
  bool previous_removed = false;
  std::size_t gone = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3 a = p[(i + p.size() - 1) % p.size()], b = p[i], c = p[(i + 1) % p.size()];
    const Vec3 u = b - a, v = c - b;
    const double nu = norm(u), nv = norm(v);
    const bool spike =
        !previous_removed && nu > 0 && nv > 0 && dot(u, v) / (nu * nv) <= -cos_limit && p.size() - (gone + 1) >= 3;
    previous_removed = spike;
    if (!spike) {
      out.push_back(b);
      continue;
    }
    const Vec3 e = c - a;
    const double t = dot(e, e) > 0 ? std::clamp(dot(b - a, e) / dot(e, e), 0.0, 1.0) : 0.0;
    moved = std::max(moved, distance(b, a + t * e));
    ++gone;
  }
  removed += gone;
  p = std::move(out);
  return moved;
}

// Where segments (a, b) and (c, d) cross properly: the parameter along (a, b); −1 when they do not.
double crossing(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const Vec2 r = b - a, s = d - c;
  const double den = cross(r, s);
  if (std::abs(den) < 1e-15) return -1;
  const double t = cross(c - a, s) / den, u = cross(c - a, r) / den;
  return (t > 0 && t < 1 && u > 0 && u < 1) ? t : -1;
}

// The simple loops a self-crossing polygon splits into at its crossings.
std::vector<Flat> simple_loops(const Flat& poly) {
  std::vector<Flat> todo{poly}, out;
  for (int splits = 0; !todo.empty();) {
    Flat f = std::move(todo.back());
    todo.pop_back();
    const std::size_t n = f.p2.size();
    bool split = false;
    for (std::size_t i = 0; i < n && !split && splits < kMaxSplits; ++i)
      for (std::size_t j = i + 2; j < n && !split; ++j) {
        if (i == 0 && j == n - 1) continue;  // neighbours through the closing edge
        const double t = crossing(f.p2[i], f.p2[i + 1], f.p2[j], f.p2[(j + 1) % n]);
        if (t < 0) continue;
        const Vec3 x3 = f.p3[i] + t * (f.p3[i + 1] - f.p3[i]);
        const Vec2 x2 = f.p2[i] + t * (f.p2[i + 1] - f.p2[i]);
        Flat a, b;
        a.p3.push_back(x3);
        a.p2.push_back(x2);
        for (std::size_t k = i + 1; k <= j; ++k) {
          a.p3.push_back(f.p3[k]);
          a.p2.push_back(f.p2[k]);
        }
        for (std::size_t k = j + 1; k < n; ++k) {
          b.p3.push_back(f.p3[k]);
          b.p2.push_back(f.p2[k]);
        }
        for (std::size_t k = 0; k <= i; ++k) {
          b.p3.push_back(f.p3[k]);
          b.p2.push_back(f.p2[k]);
        }
        b.p3.push_back(x3);
        b.p2.push_back(x2);
        if (a.p2.size() >= 3) todo.push_back(std::move(a));
        if (b.p2.size() >= 3) todo.push_back(std::move(b));
        split = true;
        ++splits;
      }
    if (!split) out.push_back(std::move(f));
  }
  return out;
}

// Points closing an open arc from its last point to its first along a cubic Hermite curve that leaves and
// arrives with the arc's own end tangents (the gap's missing stretch continues the arc's curvature), about
// `spacing` apart; the ends themselves are not repeated.
std::vector<Vec3> hermite_gap(const std::vector<Vec3>& p, double spacing) {
  const Vec3 a = p.back(), b = p.front();
  const double gap = distance(a, b);
  auto unit = [](Vec3 v) { return norm(v) > 0 ? v / norm(v) : v; };
  const Vec3 ta = gap * unit(p[p.size() - 1] - p[p.size() - 2]), tb = gap * unit(p[1] - p[0]);
  const int n = std::max(1, static_cast<int>(std::ceil(gap / std::max(spacing, 1e-6))));
  std::vector<Vec3> out;
  for (int k = 1; k < n; ++k) {
    const double t = static_cast<double>(k) / n, t2 = t * t, t3 = t2 * t;
    out.push_back((2 * t3 - 3 * t2 + 1) * a + (t3 - 2 * t2 + t) * ta + (-2 * t3 + 3 * t2) * b + (t3 - t2) * tb);
  }
  return out;
}

ContourRepair repair_of(const RawContour& rc, const std::string& kind, const std::string& detail, double moved) {
  return {rc.frame, rc.contour.slice, rc.index, kind, detail, moved};
}

// One contour: false when it is dropped.
bool repair_one(RawContour& rc, const RepairOptions& opt, std::vector<ContourRepair>& log) {
  std::vector<Vec3>& p = rc.contour.points;
  for (const Vec3& q : p)
    if (!is_finite(q)) return true;  // corruption: build_sequence refuses it with its own code
  // Repeated points and spikes, until none is left: removing the tip of a doubled-back stretch makes its
  // next points repeated, then a spike again, so the whole stretch peels off.
  const double tol = std::max(opt.duplicate_mm, opt.duplicate_fraction * median_spacing(p));
  std::size_t repeated = 0, spikes = 0;
  double moved = 0;
  for (std::size_t round = 0, before = 0; round < kMaxRounds && before != p.size() && p.size() > 3; ++round) {
    before = p.size();
    repeated += drop_duplicates(p, tol);
    if (p.size() > 3) moved = std::max(moved, drop_spikes(p, opt.spike_deg, spikes));
  }
  if (repeated > 0 && p.size() >= 3)
    log.push_back(repair_of(rc, "duplicate-points", fmt::format("{} repeated point(s) removed", repeated), 0.0));
  if (spikes > 0)
    log.push_back(repair_of(rc, "spike", fmt::format("{} spike or doubled-back point(s) removed", spikes), moved));
  if (p.size() < 3) {
    log.push_back(repair_of(rc, "too-few-points",
                            fmt::format("dropped: {} distinct point(s), a contour needs 3", p.size()), 0.0));
    return false;
  }
  const Flat flat = flatten(p);
  const double area = std::abs(signed_area(flat.p2));
  if (!(area > 1e-6 * perimeter(p) * perimeter(p))) {
    log.push_back(repair_of(rc, "no-area", "dropped: its points are (nearly) collinear", 0.0));
    return false;
  }
  const double gap = distance(p.back(), p.front());
  const double spacing = median_spacing(p);
  if (gap > opt.open_gap_factor * spacing) {
    // An open arc: closed along the gap by a curve that continues its ends, else by the straight chord.
    std::vector<Vec3> closed = p;
    const std::vector<Vec3> fill = hermite_gap(p, spacing);
    closed.insert(closed.end(), fill.begin(), fill.end());
    if (!is_self_intersecting(flatten(closed).p2)) {
      log.push_back(repair_of(rc, "open-arc-closed",
                              fmt::format("an open arc: closed along its {:.1f} mm gap by a curve continuing its ends "
                                          "({} points added)",
                                          gap, fill.size()),
                              0.0));
      p = std::move(closed);
      return true;
    }
    if (!is_self_intersecting(flat.p2)) {
      log.push_back(
          repair_of(rc, "open-arc-closed", fmt::format("an open arc: closed along its {:.1f} mm gap", gap), 0.0));
      return true;
    }
    log.push_back(repair_of(rc, "open-arc-dropped",
                            fmt::format("dropped: an open arc (closing gap {:.1f} mm) whose closing crosses it", gap),
                            0.0));
    return false;
  }
  if (!is_self_intersecting(flat.p2)) return true;
  if (p.size() > kMaxLoopPoints) return true;  // left to validation (SelfIntersection)
  std::vector<Flat> loops = simple_loops(flat);
  const auto best = std::max_element(loops.begin(), loops.end(), [](const Flat& a, const Flat& b) {
    return std::abs(signed_area(a.p2)) < std::abs(signed_area(b.p2));
  });
  if (best == loops.end() || is_self_intersecting(best->p2)) {
    log.push_back(repair_of(rc, "loop-removed", "dropped: no simple loop could be kept", 0.0));
    return false;
  }
  double loop_moved = 0;
  for (const Vec2& q : flat.p2) loop_moved = std::max(loop_moved, polyline_distance(q, best->p2));
  log.push_back(
      repair_of(rc, "loop-removed",
                fmt::format("crossed itself: its largest simple loop kept ({} of {} points, {} loop(s) removed)",
                            best->p3.size(), p.size(), loops.size() - 1),
                loop_moved));
  p = best->p3;
  return true;
}

// The stack normal as build_sequence derives it (area-weighted contour normals, one hemisphere).
Vec3 stack_normal(const std::vector<RawContour>& contours) {
  std::vector<Vec3> areas;
  for (const RawContour& rc : contours) {
    const std::vector<Vec3>& p = rc.contour.points;
    Vec3 c{}, n{};
    for (const Vec3& q : p) c += q;
    c = c / static_cast<double>(std::max<std::size_t>(1, p.size()));
    for (std::size_t i = 0; i < p.size(); ++i) n += cross(p[i] - c, p[(i + 1) % p.size()] - c);
    areas.push_back(n);
  }
  if (areas.empty()) return {0, 0, 1};
  const Vec3 ref = *std::max_element(areas.begin(), areas.end(), [](Vec3 a, Vec3 b) { return norm(a) < norm(b); });
  Vec3 sum{};
  for (const Vec3& a : areas) sum += dot(a, ref) < 0 ? -a : a;
  return norm(sum) > 0 ? sum / norm(sum) : Vec3{0, 0, 1};
}

// Slice ids on one plane merged into the later (larger) id.
void merge_planes(std::vector<RawContour>& contours, const RepairOptions& opt, std::vector<ContourRepair>& log) {
  const Vec3 n = stack_normal(contours);
  std::map<int, std::pair<double, std::size_t>> sum;  // id -> (Σ offsets, count)
  for (const RawContour& rc : contours)
    for (const Vec3& p : rc.contour.points) {
      auto& s = sum[rc.contour.slice];
      s.first += dot(p, n);
      ++s.second;
    }
  std::vector<std::pair<double, int>> order;
  for (const auto& [id, s] : sum) order.emplace_back(s.first / static_cast<double>(s.second), id);
  std::sort(order.begin(), order.end());
  std::map<int, int> into;  // id -> the id it merges into
  for (std::size_t k = 0; k < order.size();) {
    std::size_t e = k + 1;
    while (e < order.size() && order[e].first - order[e - 1].first < opt.min_plane_gap) ++e;
    int keep = order[k].second;
    for (std::size_t m = k; m < e; ++m) keep = std::max(keep, order[m].second);
    for (std::size_t m = k; m < e; ++m)
      if (order[m].second != keep) into[order[m].second] = keep;
    k = e;
  }
  if (into.empty()) return;
  std::set<std::tuple<int, int, std::string>> kept;  // (frame, slice, label) held by the id kept
  for (const RawContour& rc : contours)
    if (!into.count(rc.contour.slice)) kept.emplace(rc.frame, rc.contour.slice, rc.contour.label);
  std::vector<RawContour> out;
  std::map<std::pair<int, int>, int> renamed;  // (from, to) -> contours moved
  for (RawContour& rc : contours) {
    const auto it = into.find(rc.contour.slice);
    if (it == into.end()) {
      out.push_back(std::move(rc));
      continue;
    }
    const int from = rc.contour.slice, to = it->second;
    if (kept.count({rc.frame, to, rc.contour.label})) {
      log.push_back(
          {rc.frame, from, rc.index, "slices-merged",
           fmt::format("slice {} lies on the plane of slice {}: dropped, slice {}'s contour kept", from, to, to), 0.0});
      continue;
    }
    ++renamed[{from, to}];
    rc.contour.slice = to;
    out.push_back(std::move(rc));
  }
  for (const auto& [ids, count] : renamed)
    log.push_back({-1, ids.second, -1, "slices-merged",
                   fmt::format("slice {} lies on the plane of slice {}: merged into it ({} contour(s) moved)",
                               ids.first, ids.second, count),
                   0.0});
  contours = std::move(out);
}

}  // namespace

std::vector<ContourRepair> repair_contours(std::vector<RawContour>& contours, const RepairOptions& options) {
  std::vector<ContourRepair> log;
  std::vector<RawContour> kept;
  kept.reserve(contours.size());
  for (RawContour& rc : contours)
    if (repair_one(rc, options, log)) kept.push_back(std::move(rc));
  contours = std::move(kept);
  merge_planes(contours, options, log);
  return log;
}

}  // namespace c4d
