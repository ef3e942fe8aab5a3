// Stack validation: loose contours -> a Sequence of parallel slices over time.
// Lim et al. 2014, "Model Definition" (eqs. 1-4): a contour is a closed planar polygon, a slice the
// contours of one plane, a frame the slices of one time step, a sequence the frames. The paper
// assumes parallel slices; here the stack normal is derived from the data (Newell's area vector of
// each polygon, area-weighted) and every assumption is checked, so later stages can rely on it.
#include "contour4d/core/stack.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

#include "contour4d/core/errors.h"

namespace c4d {

namespace {

//! Per-contour measures computed once.
struct ContourInfo {
  std::vector<Vec3> points;  // cleaned: closing duplicate and repeated consecutive points dropped
  Vec3 area_vector;          // Newell: normal * area (mm²)
  Vec3 centroid;             // vertex mean
  double radius = 0.0;       // max distance of a vertex from the centroid (mm)
};

Location where_of(const RawContour& rc, const std::string& source) {
  Location w;
  w.file = source;
  if (rc.line > 0) w.line = rc.line;
  w.frame = rc.frame;
  w.slice = rc.contour.slice;
  w.contour = rc.index;
  return w;
}

std::string mm(double d) {
  std::ostringstream os;
  os.precision(4);
  os << d << " mm";
  return os.str();
}

//! Newell's method about the centroid: for a planar polygon the result is normal × area.
Vec3 newell(const std::vector<Vec3>& p, Vec3 c) {
  Vec3 n;
  for (std::size_t i = 0; i < p.size(); ++i) n += cross(p[i] - c, p[(i + 1) % p.size()] - c);
  return 0.5 * n;
}

//! Deterministic sign for a direction with no other cue: its largest component positive.
Vec3 canonical_sign(Vec3 n) {
  const double ax = std::abs(n.x), ay = std::abs(n.y), az = std::abs(n.z);
  const double big = (ax >= ay && ax >= az) ? n.x : (ay >= az ? n.y : n.z);
  return big < 0 ? -n : n;
}

ContourInfo measure(const RawContour& rc, const std::string& source, const StackOptions& opt) {
  const Location where = where_of(rc, source);
  const std::vector<Vec3>& in = rc.contour.points;
  for (std::size_t i = 0; i < in.size(); ++i)
    if (!is_finite(in[i]))
      throw InvalidInput(ErrorCode::NonFinite, where,
                         "point " + std::to_string(i) + " has a NaN or infinite coordinate",
                         "coordinates must be finite numbers (mm)");
  ContourInfo info;
  info.points.reserve(in.size());
  for (const Vec3& p : in)
    if (info.points.empty() || !(info.points.back() == p)) info.points.push_back(p);
  while (info.points.size() > 1 && info.points.back() == info.points.front()) info.points.pop_back();

  std::vector<Vec3> distinct = info.points;
  std::sort(distinct.begin(), distinct.end(),
            [](Vec3 a, Vec3 b) { return a.x != b.x ? a.x < b.x : (a.y != b.y ? a.y < b.y : a.z < b.z); });
  const auto n_distinct = std::unique(distinct.begin(), distinct.end()) - distinct.begin();
  if (n_distinct < 3)
    throw InvalidInput(ErrorCode::DegenerateContour, where,
                       "contour has " + std::to_string(n_distinct) + " distinct point(s), a polygon needs at least 3",
                       "remove the contour or draw it with more points");

  for (const Vec3& p : info.points) info.centroid += p;
  info.centroid = info.centroid / static_cast<double>(info.points.size());
  for (const Vec3& p : info.points) info.radius = std::max(info.radius, distance(p, info.centroid));
  info.area_vector = newell(info.points, info.centroid);
  const double area = norm(info.area_vector);
  const double per = perimeter(info.points);
  // A sliver (area tiny against the squared perimeter) has no reliable normal either.
  if (area < opt.min_area || area < 1e-6 * per * per)
    throw InvalidInput(ErrorCode::DegenerateContour, where,
                       "contour encloses no area (" + mm(area) + "² for a perimeter of " + mm(per) +
                           "): its points are (nearly) collinear",
                       "remove the contour or fix its points");
  return info;
}

// 2. Stack normal: area-weighted mean of the contour normals, each flipped into the hemisphere of
//    the largest contour (input orientation is free); +z when there is no contour.
Vec3 stack_normal(const std::vector<ContourInfo>& info) {
  Vec3 normal;
  if (!info.empty()) {
    std::size_t ref = 0;
    for (std::size_t i = 1; i < info.size(); ++i)
      if (norm(info[i].area_vector) > norm(info[ref].area_vector)) ref = i;
    const Vec3 r = info[ref].area_vector;
    for (const ContourInfo& ci : info) normal += dot(ci.area_vector, r) < 0 ? -ci.area_vector : ci.area_vector;
    normal = canonical_sign(normalized(normal));
  } else {
    normal = {0, 0, 1};
  }
  return normal;
}

// 3. Throws for a contour not parallel to the stack. A small contour may tilt by more than the
//    angle tolerance while staying within plane_tolerance of its plane; only a tilt that moves its
//    points off the plane is an error, and the coplanarity check catches the rest.
void check_parallel(const std::vector<RawContour>& contours, const std::vector<ContourInfo>& info, Vec3 normal,
                    const std::string& source, const StackOptions& options) {
  const double cos_tol = std::cos(options.parallel_tolerance_deg * std::numbers::pi / 180.0);
  for (std::size_t i = 0; i < contours.size(); ++i) {
    const Vec3 n = normalized(info[i].area_vector);
    const double c = std::min(1.0, std::abs(dot(n, normal)));
    const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
    if (c < cos_tol && info[i].radius * s > options.plane_tolerance) {
      const double deg = std::acos(c) * 180.0 / std::numbers::pi;
      std::ostringstream os;
      os.precision(3);
      os << "contour plane is tilted " << deg << " degrees from the stack normal (" << normal.x << ", " << normal.y
         << ", " << normal.z << "); tolerance " << options.parallel_tolerance_deg << " degrees";
      throw InvalidInput(ErrorCode::NotParallel, where_of(contours[i], source), os.str(),
                         "all slices must be parallel planes: drop long-axis or oblique slices (e.g. select "
                         "short-axis contour types)");
    }
  }
}

// 4. Throws for a contour that is not a simple polygon, tested in the shared in-plane frame.
void check_simple(const std::vector<RawContour>& contours, const std::vector<ContourInfo>& info, Vec3 normal,
                  const std::string& source) {
  const Plane axes = make_plane({0, 0, 0}, normal);
  for (std::size_t i = 0; i < contours.size(); ++i) {
    std::vector<Vec2> q;
    q.reserve(info[i].points.size());
    for (const Vec3& p : info[i].points) q.push_back(to_plane(axes, p));
    if (is_self_intersecting(q))
      throw InvalidInput(ErrorCode::SelfIntersection, where_of(contours[i], source), "contour crosses itself",
                         "fix the contour so its edges do not cross or touch");
  }
}

//! The range of offsets along the stack normal (mm).
struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double d) {
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  double mid() const { return 0.5 * (lo + hi); }
};

//! The offsets of each slice's points, over all frames and per frame.
struct SliceRanges {
  std::map<int, Range> slice_range;                  // over all frames
  std::map<std::pair<int, int>, Range> frame_range;  // (slice, frame)
};

// The offset ranges of every slice id, over all frames and per frame.
SliceRanges slice_ranges(const std::vector<RawContour>& contours, const std::vector<ContourInfo>& info, Vec3 normal) {
  SliceRanges r;
  for (std::size_t i = 0; i < contours.size(); ++i) {
    const int id = contours[i].contour.slice;
    for (const Vec3& p : info[i].points) {
      const double d = dot(p, normal);
      r.slice_range[id].add(d);
      r.frame_range[{id, contours[i].frame}].add(d);
    }
  }
  return r;
}

// The contour of slice `id` (in `frame`, any frame when < 0) with the point farthest from offset mid.
std::size_t worst_contour(const std::vector<RawContour>& contours, const std::vector<ContourInfo>& info, Vec3 normal,
                          int id, int frame, double mid) {
  std::size_t worst = 0;
  double dev = -1;
  for (std::size_t i = 0; i < contours.size(); ++i) {
    if (contours[i].contour.slice != id || (frame >= 0 && contours[i].frame != frame)) continue;
    for (const Vec3& p : info[i].points)
      if (std::abs(dot(p, normal) - mid) > dev) {
        dev = std::abs(dot(p, normal) - mid);
        worst = i;
      }
  }
  return worst;
}

// 5. Throws unless each slice id is one plane in every frame: all points within plane_tolerance of one offset.
void check_slice_planes(const std::vector<RawContour>& contours, const std::vector<ContourInfo>& info, Vec3 normal,
                        const SliceRanges& ranges, const Location& file_loc, const StackOptions& options) {
  const std::string& source = file_loc.file;
  for (const auto& [key, r] : ranges.frame_range) {
    if (r.hi - r.lo > 2 * options.plane_tolerance) {
      const std::size_t w = worst_contour(contours, info, normal, key.first, key.second, r.mid());
      throw InvalidInput(ErrorCode::NotCoplanar, where_of(contours[w], source),
                         "the points of slice " + std::to_string(key.first) + " spread " + mm(r.hi - r.lo) +
                             " along the stack normal (tolerance " + mm(2 * options.plane_tolerance) +
                             "): its contours are not on one plane",
                         "each slice id must name one plane; give contours of different planes different slice ids");
    }
  }
  for (const auto& [id, r] : ranges.slice_range) {
    if (r.hi - r.lo > 2 * options.plane_tolerance) {
      // Within each frame the slice is planar, so the plane moves from frame to frame.
      int f_lo = -1, f_hi = -1;
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const auto& [key, fr] : ranges.frame_range) {
        if (key.first != id) continue;
        if (fr.mid() < lo) {
          lo = fr.mid();
          f_lo = key.second;
        }
        if (fr.mid() > hi) {
          hi = fr.mid();
          f_hi = key.second;
        }
      }
      Location where = file_loc;
      where.slice = id;
      where.frame = f_hi;
      throw InvalidInput(ErrorCode::NotCoplanar, where,
                         "slice " + std::to_string(id) + " moves between frames: at " + mm(lo) + " in frame " +
                             std::to_string(f_lo) + " and " + mm(hi) + " in frame " + std::to_string(f_hi) +
                             " along the stack normal",
                         "a slice id must name the same plane in every frame");
    }
  }
}

// 6. Sign of the normal: slice offsets increase with slice id (the first and last ids decide);
//    flips `normal` and the ranges when they do not. Returns (offset, id) sorted by offset and
//    throws where two slice ids lie on one plane.
std::vector<std::pair<double, int>> order_slices(Vec3& normal, std::map<int, Range>& slice_range,
                                                 const Location& file_loc, const StackOptions& options) {
  if (slice_range.size() >= 2 && slice_range.rbegin()->second.mid() < slice_range.begin()->second.mid()) {
    normal = -normal;
    for (auto& [id, r] : slice_range) r = {-r.hi, -r.lo};
  }
  std::vector<std::pair<double, int>> order;  // (offset, id)
  for (const auto& [id, r] : slice_range) order.emplace_back(r.mid(), id);
  std::sort(order.begin(), order.end());
  for (std::size_t k = 1; k < order.size(); ++k) {
    if (order[k].first - order[k - 1].first < options.min_plane_gap) {
      Location where = file_loc;
      where.slice = order[k].second;
      throw InvalidInput(ErrorCode::DuplicatePlane, where,
                         "slice ids " + std::to_string(order[k - 1].second) + " and " +
                             std::to_string(order[k].second) + " lie on one plane (offsets " + mm(order[k - 1].first) +
                             " and " + mm(order[k].first) + ", closer than " + mm(options.min_plane_gap) + ")",
                         "give contours of one plane the same slice id");
    }
  }
  return order;
}

// 7. Assembles the frames (contours take their cleaned points from info); throws for a frame
//    without contours. Slices are sorted by offset within each frame.
Sequence assemble_frames(const std::vector<RawContour>& contours, std::vector<ContourInfo>& info, int frame_count,
                         const std::vector<double>& times_ms, const Location& file_loc, Vec3 normal,
                         const std::vector<std::pair<double, int>>& order) {
  Sequence seq;
  seq.source = file_loc.file;
  const Plane final_axes = make_plane({0, 0, 0}, normal);
  seq.normal = final_axes.normal;
  seq.u = final_axes.u;
  seq.v = final_axes.v;
  seq.frames.resize(static_cast<std::size_t>(frame_count));
  std::map<int, double> offset_of;
  for (const auto& [off, id] : order) offset_of[id] = off;
  std::vector<std::map<int, std::size_t>> slot(seq.frames.size());  // per frame: slice id -> index
  for (std::size_t f = 0; f < seq.frames.size(); ++f)
    seq.frames[f].time_ms = times_ms.empty() ? static_cast<double>(f) : times_ms[f];
  for (std::size_t i = 0; i < contours.size(); ++i) {
    const auto f = static_cast<std::size_t>(contours[i].frame);
    const int id = contours[i].contour.slice;
    Frame& fr = seq.frames[f];
    auto [it, added] = slot[f].emplace(id, fr.slices.size());
    if (added) {
      Slice s;
      s.id = id;
      s.offset = offset_of[id];
      fr.slices.push_back(std::move(s));
    }
    Contour c = contours[i].contour;
    c.points = std::move(info[i].points);
    fr.slices[it->second].contours.push_back(std::move(c));
  }
  for (std::size_t f = 0; f < seq.frames.size(); ++f) {
    Frame& fr = seq.frames[f];
    if (fr.slices.empty()) {
      Location where = file_loc;
      where.frame = static_cast<int>(f);
      throw InvalidInput(ErrorCode::EmptyFrame, where, "frame has no contours",
                         "every frame needs at least one contour; remove the frame or add its contours");
    }
    std::stable_sort(fr.slices.begin(), fr.slices.end(),
                     [](const Slice& a, const Slice& b) { return a.offset < b.offset; });
  }
  return seq;
}

}  // namespace

Plane slice_plane(const Sequence& seq, const Slice& s) {
  Plane pl;
  pl.origin = s.offset * seq.normal;
  pl.normal = seq.normal;
  pl.u = seq.u;
  pl.v = seq.v;
  return pl;
}

Sequence build_sequence(const std::vector<RawContour>& contours, int frame_count, const std::vector<double>& times_ms,
                        const std::string& source, const StackOptions& options) {
  Location file_loc;
  file_loc.file = source;
  if (frame_count <= 0)
    throw InvalidInput(ErrorCode::EmptyFrame, file_loc, "the input has no frames",
                       "give at least one frame of contours");
  if (!times_ms.empty() && times_ms.size() != static_cast<std::size_t>(frame_count))
    throw InvalidInput(ErrorCode::Internal, file_loc, "build_sequence: times_ms does not match frame_count");
  for (const RawContour& rc : contours)
    if (rc.frame < 0 || rc.frame >= frame_count)
      throw InvalidInput(ErrorCode::Internal, where_of(rc, source), "build_sequence: frame index out of range");

  // 1. Each contour on its own: finite, a real polygon.
  std::vector<ContourInfo> info;
  info.reserve(contours.size());
  for (const RawContour& rc : contours) info.push_back(measure(rc, source, options));

  Vec3 normal = stack_normal(info);
  check_parallel(contours, info, normal, source, options);
  check_simple(contours, info, normal, source);
  SliceRanges ranges = slice_ranges(contours, info, normal);
  check_slice_planes(contours, info, normal, ranges, file_loc, options);
  const std::vector<std::pair<double, int>> order = order_slices(normal, ranges.slice_range, file_loc, options);
  return assemble_frames(contours, info, frame_count, times_ms, file_loc, normal, order);
}

std::vector<std::string> labels(const Sequence& seq) {
  std::set<std::string> all;
  for (const Frame& f : seq.frames)
    for (const Slice& s : f.slices)
      for (const Contour& c : s.contours) all.insert(c.label);
  return {all.begin(), all.end()};
}

Sequence select_label(const Sequence& seq, const std::string& label) {
  Sequence out = seq;
  bool any = false;
  for (Frame& f : out.frames) {
    for (Slice& s : f.slices) {
      std::erase_if(s.contours, [&](const Contour& c) { return c.label != label; });
      any = any || !s.contours.empty();
    }
    std::erase_if(f.slices, [](const Slice& s) { return s.contours.empty(); });
  }
  Location where;
  where.file = seq.source;
  if (!any) {
    std::string present;
    for (const std::string& l : labels(seq))
      present += (present.empty() ? "" : ", ") + (l.empty() ? "(no label)" : "\"" + l + "\"");
    throw InvalidInput(ErrorCode::UnknownLabel, where, "no contour has the label \"" + label + "\"",
                       "labels present: " + present);
  }
  for (std::size_t f = 0; f < out.frames.size(); ++f) {
    if (out.frames[f].slices.empty()) {
      where.frame = static_cast<int>(f);
      throw InvalidInput(ErrorCode::EmptyFrame, where, "frame has no contour labelled \"" + label + "\"",
                         "every frame needs at least one contour of the chosen label");
    }
  }
  return out;
}

}  // namespace c4d
