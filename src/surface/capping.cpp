// Caps: Lim et al. 2014, "Reconstruction from Segmented Contour Lines": the interior of the
// top-most and bottom-most contours is triangulated to close the surface, and chordal-axis points
// (Prasad 1997) lifted out of the plane give a rounded tip. Our lift is a circular profile of the
// distance to the contour, which peaks on the chordal axis. The interior points come from CGAL's
// 2D Delaunay mesher (Shewchuk's refinement) run once; they are re-triangulated with the loops
// alone so that loop edges are never split and the cap meets the walls edge to edge.
// Our addition (not in the paper): after fairing, ends hold the volume their sections imply — caps
// on ends that keep their size are filled towards the linear trend of the last two section areas
// (as Simpson's discs assume a full half-spacing prism there), and the wall into a closing end
// follows a cubic Hermite section-area curve (docs/algorithms/caps.md).
#include "contour4d/surface/capping.h"

#include "contour4d/core/errors.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Handle_hash_function.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <unordered_set>

namespace c4d {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<CDT>;
using Point = K::Point_2;

// Inserts the loops as constraints; vertex info = running loop point index.
void insert_loops(CDT& cdt, const std::vector<std::vector<Vec2>>& loops) {
  int index = 0;
  for (const auto& loop : loops) {
    std::vector<CDT::Vertex_handle> vh;
    for (const Vec2& p : loop) {
      auto v = cdt.insert(Point(p.x, p.y));
      v->info() = index++;
      vh.push_back(v);
    }
    for (std::size_t k = 0; k < vh.size(); ++k) {
      const auto a = vh[k], b = vh[(k + 1) % vh.size()];
      if (a != b) cdt.insert_constraint(a, b);
    }
  }
}

// Marks faces inside the region (odd nesting level counted by crossed constraints).
void mark_domain(CDT& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->set_in_domain(false);
  std::deque<std::pair<CDT::Face_handle, int>> border{{cdt.infinite_face(), 0}};
  std::unordered_set<CDT::Face_handle, CGAL::Handle_hash_function> seen;  // membership only: any order
  while (!border.empty()) {
    auto [start, level] = border.front();
    border.pop_front();
    if (seen.count(start)) continue;
    std::deque<CDT::Face_handle> queue{start};
    seen.insert(start);
    while (!queue.empty()) {
      auto f = queue.front();
      queue.pop_front();
      f->set_in_domain(level % 2 == 1);
      for (int i = 0; i < 3; ++i) {
        auto n = f->neighbor(i);
        if (seen.count(n)) continue;
        if (cdt.is_constrained(CDT::Edge(f, i))) {
          border.push_back({n, level + 1});
        } else {
          seen.insert(n);
          queue.push_back(n);
        }
      }
    }
  }
}

// Distance from a point to the nearest loop segment, through a grid of cells about one mean segment
// long listing the segments whose bounding boxes meet them: rings of cells are searched outwards from
// the point's cell until no closer segment can be left. The minimum of the same segment_distance values
// as a scan of every segment, so the same bits.
class BoundaryDistance {
 public:
  explicit BoundaryDistance(const std::vector<std::vector<Vec2>>& loops) {
    double length = 0.0;
    for (const auto& loop : loops)
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const Vec2 a = loop[k], b = loop[(k + 1) % loop.size()];
        segments_.push_back({a, b});
        length += norm(b - a);
        lo_ = {std::min({lo_.x, a.x, b.x}), std::min({lo_.y, a.y, b.y})};
        hi_ = {std::max({hi_.x, a.x, b.x}), std::max({hi_.y, a.y, b.y})};
      }
    if (segments_.empty()) return;
    cell_ = std::max(length / static_cast<double>(segments_.size()), 1e-9);
    nx_ = std::clamp(static_cast<int>((hi_.x - lo_.x) / cell_) + 1, 1, 4096);
    ny_ = std::clamp(static_cast<int>((hi_.y - lo_.y) / cell_) + 1, 1, 4096);
    cell_ = std::max({cell_, (hi_.x - lo_.x) / nx_, (hi_.y - lo_.y) / ny_});
    cells_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
    for (std::size_t s = 0; s < segments_.size(); ++s) {
      const auto [a, b] = segments_[s];
      for (int j = cy(std::min(a.y, b.y)); j <= cy(std::max(a.y, b.y)); ++j)
        for (int i = cx(std::min(a.x, b.x)); i <= cx(std::max(a.x, b.x)); ++i) cells_[index(i, j)].push_back(s);
    }
  }

  //! The distance from p to the nearest segment; with a finite `limit`, a value that compares with
  //! `limit` as the distance does, found without searching beyond it.
  double operator()(Vec2 p, double limit = std::numeric_limits<double>::infinity()) const {
    double d = std::numeric_limits<double>::infinity();
    if (segments_.empty()) return d;
    // A point outside the grid (never one of a cap's interior points): the ring bound below does not
    // hold for it, so every segment is scanned.
    if (!(p.x >= lo_.x && p.x <= hi_.x && p.y >= lo_.y && p.y <= hi_.y)) {
      for (const auto& [a, b] : segments_) d = std::min(d, segment_distance(p, a, b));
      return d;
    }
    const int ci = cx(p.x), cj = cy(p.y);
    auto visit = [&](int i, int j) {
      for (std::size_t s : cells_[index(i, j)]) d = std::min(d, segment_distance(p, segments_[s][0], segments_[s][1]));
    };
    for (int r = 0; r <= std::max(nx_, ny_); ++r) {
      // The cells at Chebyshev distance r from the point's cell, within the grid: its top and bottom
      // rows, then the rest of its left and right columns.
      const int i0 = std::max(ci - r, 0), i1 = std::min(ci + r, nx_ - 1);
      if (r == 0) {
        visit(ci, cj);
      } else {
        if (cj - r >= 0)
          for (int i = i0; i <= i1; ++i) visit(i, cj - r);
        if (cj + r < ny_)
          for (int i = i0; i <= i1; ++i) visit(i, cj + r);
        for (int j = std::max(cj - r + 1, 0); j <= std::min(cj + r - 1, ny_ - 1); ++j) {
          if (ci - r >= 0) visit(ci - r, j);
          if (ci + r < nx_) visit(ci + r, j);
        }
      }
      // Cells of ring r + 1 and beyond are at least r cells from a point within its own cell.
      if (d <= r * cell_ || r * cell_ >= limit) break;
    }
    return d;
  }

 private:
  int cx(double x) const { return std::clamp(static_cast<int>((x - lo_.x) / cell_), 0, nx_ - 1); }
  int cy(double y) const { return std::clamp(static_cast<int>((y - lo_.y) / cell_), 0, ny_ - 1); }
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i);
  }

  std::vector<std::array<Vec2, 2>> segments_;
  std::vector<std::vector<std::size_t>> cells_;
  Vec2 lo_{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec2 hi_{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
};

// CGAL's Delaunay_mesh_size_criteria_2 (the same shape test, bound 0.125) with a size bound that grows
// with the distance of a triangle's centroid from the loops: `edge` within `near` edges of them,
// `far` × edge beyond `ramp` edges, linear in between. The fairing solves for every cap point and its
// cost grows faster than the point count on a 2D region (a large basal cap at a uniform bound takes more
// than half of a frame's factorisation flops), while only the rings next to the contour
// shape the surface across it; the final remeshing brings the interior back to `edge`.
class GradedCriteria : public Criteria {
 public:
  GradedCriteria(double edge, double far, double near, double ramp, const BoundaryDistance& distance)
      : Criteria(0.125, edge), far_(far), near_(near), ramp_(ramp), distance_(&distance) {}

  class Is_bad : public Criteria::Is_bad {
   public:
    Is_bad(double aspect, double edge, const Geom_traits& geom, const GradedCriteria* c)
        : Criteria::Is_bad(aspect, edge, geom), aspect_(aspect), edge_(edge), c_(c) {}
    using Criteria::Is_bad::operator();
    CGAL::Mesh_2::Face_badness operator()(const CDT::Face_handle& fh, Quality& q) const {
      const Point& pa = fh->vertex(0)->point();
      const Point& pb = fh->vertex(1)->point();
      const Point& pc = fh->vertex(2)->point();
      std::array<double, 3> sq{CGAL::to_double(CGAL::squared_distance(pb, pc)),
                               CGAL::to_double(CGAL::squared_distance(pc, pa)),
                               CGAL::to_double(CGAL::squared_distance(pa, pb))};
      std::sort(sq.begin(), sq.end());
      const double l1 = sq[2], l2 = sq[1];  // the two longest squared edges
      const Vec2 g{(pa.x() + pb.x() + pc.x()) / 3.0, (pa.y() + pb.y() + pc.y()) / 3.0};
      const double d = (*c_->distance_)(g, c_->ramp_ * edge_);
      const double t = std::clamp((d - c_->near_ * edge_) / std::max((c_->ramp_ - c_->near_) * edge_, 1e-12), 0.0, 1.0);
      const double bound = edge_ * (1.0 + (c_->far_ - 1.0) * t);
      q.second = l1 / (bound * bound);
      if (q.size() > 1) {
        q.first = 1;
        return CGAL::Mesh_2::IMPERATIVELY_BAD;
      }
      const double area = 2 * CGAL::to_double(CGAL::area(pa, pb, pc));
      q.first = (area * area) / (l1 * l2);
      return q.sine() < aspect_ ? CGAL::Mesh_2::BAD : CGAL::Mesh_2::NOT_BAD;
    }

   private:
    double aspect_, edge_;
    const GradedCriteria* c_;
  };
  Is_bad is_bad_object() const { return Is_bad(this->bound(), size_bound(), this->traits, this); }

 private:
  double far_, near_, ramp_;
  const BoundaryDistance* distance_;
};

}  // namespace

CapMesh triangulate_cap(const std::vector<std::vector<Vec2>>& loops, CapStyle style, const CapOptions& options) {
  CapMesh cap;
  for (const auto& loop : loops) cap.points.insert(cap.points.end(), loop.begin(), loop.end());
  const int loop_points = static_cast<int>(cap.points.size());
  if (style == CapStyle::Open || loop_points < 3) return cap;

  // Pass 1: interior points from the Delaunay mesher.
  const BoundaryDistance boundary_distance(loops);
  std::vector<Vec2> interior;
  CDT cdt_loops;  // the loops' triangulation, again the start of pass 2 (a copy: the same faces)
  {
    CDT cdt;
    insert_loops(cdt, loops);
    // Loops that cross or share a point make vertices of their own (or merge two): the cap has no
    // triangulation of the loops as given.
    if (cdt.number_of_vertices() != static_cast<std::size_t>(loop_points))
      throw InvalidInput(ErrorCode::SelfIntersection, Location{},
                         "the contours to close by a cap cross or touch each other",
                         "a contour inside another must not meet it: fix the contours of this slice");
    cdt_loops = cdt;
    for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) v->info() = 0;
    mark_domain(cdt);
    std::unordered_set<CDT::Vertex_handle, CGAL::Handle_hash_function> original;  // membership only
    for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) original.insert(v);
    // A bound below `edge` far from the loops (or none at all: 0 or NaN would refine forever) counts as
    // uniform: CGAL's own criteria, no distances to find.
    const bool graded = std::isfinite(options.far_scale) && options.far_scale > 1.0;
    if (options.edge > 0 && graded)
      CGAL::refine_Delaunay_mesh_2(
          cdt,
          GradedCriteria(options.edge, options.far_scale, options.near_edges, options.ramp_edges, boundary_distance),
          true);
    else if (options.edge > 0)
      CGAL::refine_Delaunay_mesh_2(cdt, Criteria(0.125, options.edge * std::max(1.0, options.uniform_scale)), true);
    for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
      if (original.count(v) || cdt.are_there_incident_constraints(v)) continue;
      const Vec2 p{v->point().x(), v->point().y()};
      if (boundary_distance(p, 0.4 * options.edge) < 0.4 * options.edge) continue;  // would make slivers near the loop
      interior.push_back(p);
    }
    // Keep the order independent of CGAL's vertex storage: sort by position is not rigid-invariant,
    // but the set is what matters; the final CDT is unique up to cocircular ties.
    if (interior.empty() && style == CapStyle::Rounded) {
      // Tiny region: one apex at the centroid of the largest domain face.
      double best = -1.0;
      Vec2 apex{};
      for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
        if (!f->is_in_domain()) continue;
        const Point a = f->vertex(0)->point(), b = f->vertex(1)->point(), c = f->vertex(2)->point();
        const double area = std::abs(CGAL::area(a, b, c));
        if (area > best) {
          best = area;
          apex = {(a.x() + b.x() + c.x()) / 3.0, (a.y() + b.y() + c.y()) / 3.0};
        }
      }
      if (best > 0.0) interior.push_back(apex);
    }
  }

  // Pass 2: loops as constraints plus the interior points.
  CDT& cdt = cdt_loops;
  for (const Vec2& p : interior) {
    const auto before = cdt.number_of_vertices();
    auto v = cdt.insert(Point(p.x, p.y));
    if (cdt.number_of_vertices() == before) continue;  // landed on an existing point (should not happen)
    v->info() = static_cast<int>(cap.points.size());
    cap.points.push_back(p);
  }
  mark_domain(cdt);
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    cap.triangles.push_back({static_cast<std::uint32_t>(f->vertex(0)->info()),
                             static_cast<std::uint32_t>(f->vertex(1)->info()),
                             static_cast<std::uint32_t>(f->vertex(2)->info())});
  }
  std::sort(cap.triangles.begin(), cap.triangles.end());

  cap.height.assign(cap.points.size(), 0.0);
  if (style == CapStyle::Rounded && cap.points.size() > static_cast<std::size_t>(loop_points)) {
    std::vector<double> d(cap.points.size(), 0.0);
    double dmax = 0.0;
    for (std::size_t i = static_cast<std::size_t>(loop_points); i < cap.points.size(); ++i)
      dmax = std::max(dmax, d[i] = boundary_distance(cap.points[i]));
    const double h = std::min(options.height, dmax);
    for (std::size_t i = static_cast<std::size_t>(loop_points); i < cap.points.size(); ++i) {
      const double t = dmax > 0 ? std::min(1.0, d[i] / dmax) : 1.0;
      cap.height[i] = h * std::sqrt(std::max(0.0, 1.0 - (1.0 - t) * (1.0 - t)));
    }
  }
  return cap;
}

namespace {

// Signed area of the triangle's projection on the slice plane (positive counter-clockwise).
double projected_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  return 0.5 * cross(Vec2{b.x - a.x, b.y - a.y}, Vec2{c.x - a.x, c.y - a.y});
}

// The lift of fill_cap: u + c·u²/height. Its derivative at the rim (u = 0) is 1, so the cap leaves the end
// contour with the slope the fairing gave it, the wall's own.
double lifted(double u, double height, double c) { return u + c * u * u / height; }

double cap_height_of(const Vec3& p, const CapFrame& frame) { return std::max(0.0, frame.dir * (p.z - frame.z0)); }

// The vertices a triangle list uses (sorted, unique) and its triangles in indices into that list.
struct LocalTriangles {
  std::vector<std::uint32_t> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

LocalTriangles local_triangles(const std::vector<Triangle>& triangles) {
  LocalTriangles out;
  for (const Triangle& t : triangles) out.vertices.insert(out.vertices.end(), t.begin(), t.end());
  std::sort(out.vertices.begin(), out.vertices.end());
  out.vertices.erase(std::unique(out.vertices.begin(), out.vertices.end()), out.vertices.end());
  for (const Triangle& t : triangles) {
    std::array<std::uint32_t, 3> local{};
    for (std::size_t k = 0; k < 3; ++k)
      local[k] = static_cast<std::uint32_t>(std::lower_bound(out.vertices.begin(), out.vertices.end(), t[k]) -
                                            out.vertices.begin());
    out.triangles.push_back(local);
  }
  return out;
}

// The cap's volume over its plane as a function of the lift's coefficient: the projected areas and the
// vertices' heights are taken once, and each call lifts every vertex once. The sums run in the triangles'
// order, as the direct formula would.
class CapVolume {
 public:
  CapVolume(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles, const CapFrame& frame)
      : height_(frame.height), local_(local_triangles(triangles)) {
    for (std::uint32_t v : local_.vertices) u_.push_back(cap_height_of(positions[v], frame));
    for (const Triangle& t : triangles)
      area_.push_back(projected_area(positions[t[0]], positions[t[1]], positions[t[2]]));
    lifted_.resize(u_.size());
  }

  double operator()(double c) {
    for (std::size_t k = 0; k < u_.size(); ++k) lifted_[k] = lifted(u_[k], height_, c);
    double volume = 0.0;
    for (std::size_t f = 0; f < local_.triangles.size(); ++f) {
      double sum = 0.0;
      for (std::uint32_t k : local_.triangles[f]) sum += lifted_[k];
      volume += area_[f] * sum / 3.0;
    }
    return std::abs(volume);
  }

  const std::vector<std::uint32_t>& vertices() const { return local_.vertices; }

 private:
  double height_;
  LocalTriangles local_;
  std::vector<double> u_, lifted_;  // per vertex: height over the plane, lifted height
  std::vector<double> area_;        // per triangle: projected area
};

}  // namespace

double cap_volume(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles, const CapFrame& frame) {
  if (frame.height <= 0.0) return 0.0;
  return CapVolume(positions, triangles, frame)(0.0);
}

double extrapolated_cap_volume(double area, double neighbour_area, double spacing, double height, double max_fill) {
  if (area <= 0.0 || height <= 0.0) return 0.0;
  const double slope = spacing > 0.0 && std::isfinite(spacing) ? (area - neighbour_area) / spacing : 0.0;
  // Piecewise linear in d: integrate exactly over the pieces where the clamp is inactive.
  double volume = 0.0;
  if (slope >= 0.0) {
    volume = area * height;
  } else {
    const double end = std::min(height, area / -slope);  // where the extrapolated area reaches 0
    volume = area * end + 0.5 * slope * end * end;
  }
  return std::min(volume, std::clamp(max_fill, 0.0, 1.0) * area * height);
}

double fill_cap(std::vector<Vec3>& positions, const std::vector<Triangle>& triangles, const CapFrame& frame,
                double target) {
  if (frame.height <= 0.0 || triangles.empty()) return 0.0;
  CapVolume volume(positions, triangles, frame);
  const double before = volume(0.0);
  if (before >= target) return 0.0;
  // The volume is linear in c (heights over fixed projected areas): one more evaluation gives its slope.
  const double per_c = volume(1.0) - before;
  if (!(per_c > 0.0)) return 0.0;
  const double c = (target - before) / per_c;
  for (std::uint32_t v : volume.vertices()) {
    const double u = frame.dir * (positions[v].z - frame.z0);
    if (u > 0.0) positions[v].z = frame.z0 + frame.dir * lifted(u, frame.height, c);
  }
  return c;
}

namespace {

// The widest a wall may be widened (radius × 1.5 half-way between the slices): a bound against a poor target.
constexpr double kMaxBandWidening = 0.5;

// The widening's profile between the neighbouring slice (t = 0) and the end contour (t = 1): zero with a zero
// slope at both, so the wall keeps its slope across both contours and into the cap.
double band_phi(double t) { return 16.0 * t * t * (1.0 - t) * (1.0 - t); }

Vec3 widened(const Vec3& p, const EndBand& band, double alpha) {
  const double span = band.z_end - band.z_ref;
  const double t = span != 0.0 ? std::clamp((p.z - band.z_ref) / span, 0.0, 1.0) : 0.0;
  const Vec2 c{band.c_ref.x + t * (band.c_end.x - band.c_ref.x), band.c_ref.y + t * (band.c_end.y - band.c_ref.y)};
  const double k = 1.0 + alpha * band_phi(t);
  return {c.x + k * (p.x - c.x), c.y + k * (p.y - c.y), p.z};
}

// The band's volume (∮ (z − z_ref) n_z dA over the wall and the end disk; the neighbouring disk adds 0)
// as a function of the widening α: each call widens every movable vertex once (fill_end_band's bisection
// calls it 50 times). The sums run in the triangles' order, as the direct formula would.
class BandVolume {
 public:
  BandVolume(const std::vector<Vec3>& positions, const EndBand& band, double orientation,
             const std::vector<char>& movable)
      : band_(band), orientation_(orientation), local_(local_triangles(band.triangles)) {
    for (std::uint32_t v : local_.vertices) {
      p_.push_back(positions[v]);
      movable_.push_back(movable[v]);
    }
    q_.resize(p_.size());
  }

  double operator()(double alpha) {
    for (std::size_t k = 0; k < p_.size(); ++k) q_[k] = movable_[k] ? widened(p_[k], band_, alpha) : p_[k];
    double volume = 0.0;
    for (const auto& t : local_.triangles) {
      const Vec3 &a = q_[t[0]], &b = q_[t[1]], &c = q_[t[2]];
      volume += orientation_ * projected_area(a, b, c) * ((a.z + b.z + c.z) / 3.0 - band_.z_ref);
    }
    return volume + std::abs(band_.z_end - band_.z_ref) * band_.area_end;
  }

 private:
  const EndBand& band_;
  double orientation_;
  LocalTriangles local_;
  std::vector<Vec3> p_, q_;  // per vertex of the band: position, widened position
  std::vector<char> movable_;
};

}  // namespace

double end_band_volume(const std::vector<Vec3>& positions, const EndBand& band, double orientation) {
  std::vector<char> none(positions.size(), 0);
  return BandVolume(positions, band, orientation, none)(0.0);
}

double hermite_band_volume(double a0, double a1, double m0, double m1, double h) {
  return h * (a0 + a1) / 2.0 + h * h * (m0 - m1) / 12.0;
}

double fill_end_band(std::vector<Vec3>& positions, const EndBand& band, double target, double orientation) {
  std::vector<char> movable(positions.size(), 0);
  for (std::uint32_t v : band.movable) movable[v] = 1;
  if (band.triangles.empty()) return 0.0;
  BandVolume volume(positions, band, orientation, movable);
  if (volume(0.0) >= target) return 0.0;
  double lo = 0.0, hi = kMaxBandWidening;
  if (volume(hi) <= target) {
    lo = hi;
  } else {
    for (int it = 0; it < 50; ++it) {
      const double mid = 0.5 * (lo + hi);
      (volume(mid) < target ? lo : hi) = mid;
    }
  }
  for (std::uint32_t v : band.movable) positions[v] = widened(positions[v], band, lo);
  return lo;
}

}  // namespace c4d
