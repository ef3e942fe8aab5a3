// Surface between two slices: Lim et al. 2014 (PLOS ONE), section "Reconstruction from Segmented
// Contour Lines", improvised from Barequet & Sharir 1996 ("Piecewise-linear interpolation between
// polygonal slices"). The contours of both slices are projected onto one plane; the region where
// the two slices' interiors do not overlap (their symmetric difference) gets a constrained Delaunay
// triangulation whose constraints are all contour edges (CGAL CDT+, exact constructions so that
// crossing constraints are split exactly); lifting every vertex back to its slice gives the band.
// Triangles with all three vertices on one slice would lie flat, and with a flat triangle on the
// other side of the contour they form the paper's collapsed pair: chordal-axis points (Prasad 1997,
// "Morphological analysis of shapes", CAT) are injected as lifting points until none is left.
//
// Where the paper is vague (docs/algorithms/delaunay_tiling.md):
// - Points where lower and upper contours meet in projection (crossings, a vertex on the other
//   slice's edge or vertex, overlapping edges) are lifted to crossing_height · gap; a contour edge
//   split by such points is closed by a vertical fan, so the contour stays exactly as given.
// - Inside/outside comes from nesting parity (a flood fill over the triangulation toggling at each
//   constraint), not from the polygons' orientation; the band faces A\B keep their counter-clockwise
//   order (they face up and out), B\A faces are reversed (down and out).
// - CAT heights interpolate the distances to the two slices' contours.
#include "contour4d/surface/delaunay_tiling.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "contour4d/core/errors.h"

namespace c4d {

namespace {

struct VertexInfo {
  int id = -1;         // our own id, in order of creation (deterministic, never a pointer)
  int lower = -1;      // output id of the lower polygon vertex here
  int upper = -1;      // output id of the upper polygon vertex here
  int lower_hits = 0;  // lower vertices and lower edge interiors through this point
  int upper_hits = 0;
  bool cat = false;     // a CAT lifting point
  double height = 0.0;  // height of a CAT point (mm)
  Vec2 xy;              // coordinates in double
  bool on_lower() const { return lower_hits > 0; }
  bool on_upper() const { return upper_hits > 0; }
  bool shared() const { return on_lower() && on_upper(); }
};

struct FaceInfo {
  bool visited = false;
  bool in_lower = false;  // inside the lower slice's region (odd nesting)
  bool in_upper = false;
};

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, Kernel>;
using Fb0 = CGAL::Constrained_triangulation_face_base_2<Kernel>;
using Fb = CGAL::Triangulation_face_base_with_info_2<FaceInfo, Kernel, Fb0>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_intersections_tag>;
using Cdtp = CGAL::Constrained_triangulation_plus_2<Cdt>;
using Point = Kernel::Point_2;
using VertexHandle = Cdtp::Vertex_handle;
using FaceHandle = Cdtp::Face_handle;

// One polygon edge a→b as given, and the triangulation vertices along it.
struct InputEdge {
  int slice = 0;  // 0 lower, 1 upper
  int polygon = 0;
  std::uint32_t a = 0, b = 0;  // output ids
  Cdtp::Constraint_id cid;
  std::vector<VertexHandle> chain;
};

// How many lower and upper edges run along one constrained sub-edge.
struct SubEdge {
  int lower = 0;
  int upper = 0;
};

using EdgeKey = std::pair<int, int>;
EdgeKey edge_key(VertexHandle a, VertexHandle b) {
  const int i = a->info().id, j = b->info().id;
  return i < j ? EdgeKey{i, j} : EdgeKey{j, i};
}

void validate(const std::vector<std::vector<Vec2>>& polygons, const char* side) {
  if (polygons.empty())
    throw InvalidInput(ErrorCode::EmptyFrame, {},
                       fmt::format("tile_slices_delaunay: the {} slice has no polygon", side),
                       "pass at least one closed contour on each slice");
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    Location where;
    where.contour = static_cast<int>(p);
    if (polygons[p].size() < 3)
      throw InvalidInput(ErrorCode::DegenerateContour, where,
                         fmt::format("tile_slices_delaunay: {} polygon {} has {} points", side, p, polygons[p].size()),
                         "a closed contour needs at least 3 distinct points");
    for (std::size_t i = 0; i < polygons[p].size(); ++i)
      if (!std::isfinite(polygons[p][i].x) || !std::isfinite(polygons[p][i].y))
        throw InvalidInput(ErrorCode::NonFinite, where,
                           fmt::format("tile_slices_delaunay: {} polygon {} point {} is not finite", side, p, i),
                           "remove NaN or infinite coordinates from the contour");
  }
}

[[noreturn]] void throw_same_slice(const char* side, const InputEdge& e, const char* what) {
  Location where;
  where.contour = e.polygon;
  throw InvalidInput(ErrorCode::SelfIntersection, where,
                     fmt::format("tile_slices_delaunay: {} polygons {} (edge of polygon {})", side, what, e.polygon),
                     "the contours of one slice must not cross or touch: clean the contours first");
}

using Polygons = std::vector<std::vector<Vec2>>;

// The triangulation of both slices' contours, with what is known about its points and edges.
struct BandCdt {
  Cdtp cdt;
  std::vector<VertexHandle> by_id;  // our vertex id → handle
  std::vector<InputEdge> edges;
  std::uint32_t n_poly_vertices = 0;
  std::vector<std::vector<VertexHandle>> handles;  // per polygon (lower first), per vertex
  std::map<EdgeKey, SubEdge> sub_edges;            // per constrained sub-edge: the contours along it
};

// The band's heights (mm) and the CAT heights' margin (fraction of the gap).
struct Heights {
  double gap = 0.0;
  double crossing_h = 0.0;
  double margin = 0.0;
};

// Inserts every polygon vertex, lower slice first; throws on a point repeated within one slice.
void insert_vertices(BandCdt& t, const Polygons& lower, const Polygons& upper) {
  for (int slice = 0; slice < 2; ++slice) {
    const auto& polygons = slice == 0 ? lower : upper;
    for (std::size_t p = 0; p < polygons.size(); ++p) {
      std::vector<VertexHandle> hs;
      for (std::size_t i = 0; i < polygons[p].size(); ++i) {
        const Vec2 q = polygons[p][i];
        VertexHandle v = t.cdt.insert(Point(q.x, q.y));
        VertexInfo& info = v->info();
        if (info.id < 0) {
          info.id = static_cast<int>(t.by_id.size());
          info.xy = q;
          t.by_id.push_back(v);
        }
        int& own = slice == 0 ? info.lower : info.upper;
        if (own >= 0) {
          Location where;
          where.contour = static_cast<int>(p);
          throw InvalidInput(
              ErrorCode::DegenerateContour, where,
              fmt::format("tile_slices_delaunay: {} polygon {} point {} ({}, {}) repeats a point of the same slice",
                          slice == 0 ? "lower" : "upper", p, i, q.x, q.y),
              "remove repeated points (also the repeated closing point) from the contours");
        }
        own = static_cast<int>(t.n_poly_vertices++);
        (slice == 0 ? info.lower_hits : info.upper_hits) += 1;
        hs.push_back(v);
      }
      t.handles.push_back(std::move(hs));
    }
  }
}

// Inserts every polygon edge as a constraint (after all vertices), in input order.
void insert_edges(BandCdt& t, const Polygons& lower, const Polygons& upper) {
  std::size_t poly = 0;
  std::uint32_t first = 0;
  for (int slice = 0; slice < 2; ++slice) {
    const auto& polygons = slice == 0 ? lower : upper;
    for (std::size_t p = 0; p < polygons.size(); ++p, ++poly) {
      const std::size_t n = polygons[p].size();
      for (std::size_t i = 0; i < n; ++i) {
        InputEdge e;
        e.slice = slice;
        e.polygon = static_cast<int>(p);
        e.a = first + static_cast<std::uint32_t>(i);
        e.b = first + static_cast<std::uint32_t>((i + 1) % n);
        e.cid = t.cdt.insert_constraint(t.handles[poly][i], t.handles[poly][(i + 1) % n]);
        e.chain = {t.handles[poly][i], t.handles[poly][(i + 1) % n]};
        t.edges.push_back(std::move(e));
      }
      first += static_cast<std::uint32_t>(n);
    }
  }
}

// Replaces each edge's chain by its triangulation vertices a→b; new points get ids in this order,
// every point and sub-edge learns which slices' contours pass through it.
void walk_edge_chains(BandCdt& t) {
  for (InputEdge& e : t.edges) {
    const VertexHandle va = e.chain.front(), vb = e.chain.back();
    std::vector<VertexHandle> chain(t.cdt.vertices_in_constraint_begin(e.cid), t.cdt.vertices_in_constraint_end(e.cid));
    if (!chain.empty() && chain.front() != va) std::reverse(chain.begin(), chain.end());
    if (chain.size() < 2 || chain.front() != va || chain.back() != vb)
      throw InvalidInput(ErrorCode::Internal, {}, "tile_slices_delaunay: a contour edge was lost by the triangulation",
                         "please report this input");
    e.chain = std::move(chain);
    for (std::size_t k = 1; k + 1 < e.chain.size(); ++k) {
      VertexHandle v = e.chain[k];
      VertexInfo& info = v->info();
      if (info.id < 0) {
        info.id = static_cast<int>(t.by_id.size());
        info.xy = {CGAL::to_double(v->point().x()), CGAL::to_double(v->point().y())};
        t.by_id.push_back(v);
      }
      (e.slice == 0 ? info.lower_hits : info.upper_hits) += 1;
    }
    for (std::size_t k = 0; k + 1 < e.chain.size(); ++k) {
      SubEdge& s = t.sub_edges[edge_key(e.chain[k], e.chain[k + 1])];
      (e.slice == 0 ? s.lower : s.upper) += 1;
    }
  }
}

// Throws where two contours of one slice cross, touch or overlap.
void check_slices_clean(const BandCdt& t) {
  for (const InputEdge& e : t.edges)
    for (const VertexHandle& v : e.chain) {
      const int hits = e.slice == 0 ? v->info().lower_hits : v->info().upper_hits;
      if (hits > 1) throw_same_slice(e.slice == 0 ? "lower" : "upper", e, "cross or touch");
    }
  for (const auto& [key, s] : t.sub_edges)
    if (s.lower > 1 || s.upper > 1)
      throw InvalidInput(ErrorCode::SelfIntersection, {}, "tile_slices_delaunay: two contours of one slice overlap",
                         "the contours of one slice must not cross or touch: clean the contours first");
}

// The lifted height of a triangulation vertex (mm above the lower slice).
double vertex_height(VertexHandle v, const Heights& h) {
  const VertexInfo& info = v->info();
  if (info.cat) return info.height;
  if (info.shared()) return h.crossing_h;
  return info.on_lower() ? 0.0 : h.gap;
}

// Nesting parity by flood fill from the outside: crossing a constrained sub-edge toggles the
// slices whose contours run along it (both for overlapping edges). Returns true when inconsistent.
bool classify_faces(BandCdt& t) {
  bool inconsistent = false;
  for (FaceHandle f : t.cdt.all_face_handles()) f->info() = FaceInfo{};
  std::deque<FaceHandle> queue;
  FaceHandle start = t.cdt.infinite_face();
  start->info().visited = true;
  queue.push_back(start);
  while (!queue.empty()) {
    FaceHandle f = queue.front();
    queue.pop_front();
    for (int i = 0; i < 3; ++i) {
      FaceHandle g = f->neighbor(i);
      FaceInfo want{true, f->info().in_lower, f->info().in_upper};
      if (f->is_constrained(i)) {
        auto it = t.sub_edges.find(edge_key(f->vertex(Cdtp::cw(i)), f->vertex(Cdtp::ccw(i))));
        if (it != t.sub_edges.end()) {
          want.in_lower ^= (it->second.lower % 2) == 1;
          want.in_upper ^= (it->second.upper % 2) == 1;
        }
      }
      if (!g->info().visited) {
        g->info() = want;
        queue.push_back(g);
      } else if (g->info().in_lower != want.in_lower || g->info().in_upper != want.in_upper) {
        inconsistent = true;
      }
    }
  }
  return inconsistent;
}

// A finite face inside exactly one slice's region.
bool is_band(BandCdt& t, FaceHandle f) { return !t.cdt.is_infinite(f) && f->info().in_lower != f->info().in_upper; }

// The height of a CAT point at p: the distances to both slices' contours, mapped into the margins.
double cat_height(const BandCdt& t, Vec2 p, const Heights& h) {
  double dl = std::numeric_limits<double>::infinity(), du = dl;
  for (const InputEdge& e : t.edges) {
    const Vec2 a = e.chain.front()->info().xy, b = e.chain.back()->info().xy;
    double& d = e.slice == 0 ? dl : du;
    d = std::min(d, segment_distance(p, a, b));
  }
  const double s = dl + du > 0.0 ? dl / (dl + du) : 0.5;
  // An affine map, not a clamp: clamped heights would tie and make new flat triangles.
  return (h.margin + (1.0 - 2.0 * h.margin) * s) * h.gap;
}

// The band faces, keyed and sorted by their sorted vertex ids.
std::vector<std::pair<std::array<int, 3>, FaceHandle>> sorted_band_faces(BandCdt& t) {
  std::vector<std::pair<std::array<int, 3>, FaceHandle>> faces;
  for (FaceHandle f : t.cdt.finite_face_handles())
    if (is_band(t, f)) {
      std::array<int, 3> key{f->vertex(0)->info().id, f->vertex(1)->info().id, f->vertex(2)->info().id};
      std::sort(key.begin(), key.end());
      faces.emplace_back(key, f);
    }
  std::sort(faces.begin(), faces.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  return faces;
}

// One CAT round's survey of the band: flat faces, inner edges on a cap, and the lifting points wanted.
struct CatSurvey {
  std::map<std::array<int, 3>, Vec2> candidates;  // (i, j, -1): midpoint of edge i–j; (i, j, k): centroid
  std::size_t flat_faces = 0;
  std::set<EdgeKey> flat_edges;  // inner edges lying on a cap
};

// Surveys the band faces for one CAT round (chordal axis: midpoints of inner edges, centroids of
// junction faces and of faces without inner edge).
CatSurvey survey_flat_faces(BandCdt& t, const Heights& h, const DelaunayTilingOptions& options) {
  CatSurvey s;
  for (const auto& [key, f] : sorted_band_faces(t)) {
    const double h0 = vertex_height(f->vertex(0), h), h1 = vertex_height(f->vertex(1), h),
                 h2 = vertex_height(f->vertex(2), h);
    const bool flat = h0 == h1 && h1 == h2;
    int inner = 0;
    for (int i = 0; i < 3; ++i) {
      if (f->is_constrained(i)) continue;
      ++inner;
      VertexHandle a = f->vertex(Cdtp::cw(i)), b = f->vertex(Cdtp::ccw(i));
      const double ha = vertex_height(a, h), hb = vertex_height(b, h);
      const bool flat_edge = ha == hb && (ha == 0.0 || ha == h.gap);
      if (flat_edge && (f->info().in_lower ? ha == 0.0 : ha == h.gap)) s.flat_edges.insert(edge_key(a, b));
      if (flat || (options.split_flat_edges && flat_edge)) {
        const EdgeKey k = edge_key(a, b);
        s.candidates[{k.first, k.second, -1}] = 0.5 * (a->info().xy + b->info().xy);
      }
    }
    if (flat) {
      ++s.flat_faces;
      if (inner == 0 || inner == 3)
        s.candidates[key] = (1.0 / 3.0) * (f->vertex(0)->info().xy + f->vertex(1)->info().xy + f->vertex(2)->info().xy);
    }
  }
  return s;
}

// Inserts the candidate CAT points that land inside the band; returns how many were inserted.
int insert_cat_points(BandCdt& t, const std::map<std::array<int, 3>, Vec2>& candidates, const Heights& h) {
  int added = 0;
  for (const auto& [key, p] : candidates) {
    const Point q(p.x, p.y);
    Cdtp::Locate_type lt;
    int li = 0;
    FaceHandle f = t.cdt.locate(q, lt, li);
    // Rounding may move a midpoint off its edge: never onto a contour, a vertex or another region.
    if (lt != Cdtp::FACE && lt != Cdtp::EDGE) continue;
    if (!is_band(t, f)) continue;
    if (lt == Cdtp::EDGE && (f->is_constrained(li) || !is_band(t, f->neighbor(li)))) continue;
    const FaceInfo region = f->info();
    VertexHandle v = t.cdt.insert(q, lt, f, li);
    VertexInfo& info = v->info();
    info.id = static_cast<int>(t.by_id.size());
    info.xy = p;
    info.cat = true;
    info.height = cat_height(t, p, h);
    t.by_id.push_back(v);
    auto fc = t.cdt.incident_faces(v), done = fc;
    do {
      fc->info() = region;
    } while (++fc != done);
    ++added;
  }
  return added;
}

// What the CAT rounds leave: the last survey's flat faces and cap edges, and the parity check.
struct CatOutcome {
  std::size_t flat_faces = 0;
  std::set<EdgeKey> flat_edges;
  bool inconsistent = false;
};

// CAT lifting points: inserting a point only creates faces around it, so each round removes the
// flat faces it targets. Sets out.cat_rounds; the faces are classified as the rounds leave them.
CatOutcome run_cat_rounds(BandCdt& t, const Heights& h, const DelaunayTilingOptions& options, DelaunayTiling& out) {
  CatOutcome r;
  for (int round = 0;; ++round) {
    if (classify_faces(t)) r.inconsistent = true;
    CatSurvey s = survey_flat_faces(t, h, options);
    r.flat_faces = s.flat_faces;
    r.flat_edges = std::move(s.flat_edges);
    if (s.candidates.empty() || round >= options.max_cat_rounds) break;
    const int added = insert_cat_points(t, s.candidates, h);
    if (added == 0) break;
    out.cat_rounds = round + 1;
  }
  return r;
}

// Output ids per our id: polygon vertices keep theirs; meeting points and CAT points follow in id
// order, appended to out.points.
std::vector<std::uint32_t> output_ids(const BandCdt& t, const Heights& h, DelaunayTiling& out) {
  std::vector<std::uint32_t> out_id(t.by_id.size());
  for (std::size_t id = 0; id < t.by_id.size(); ++id) {
    const VertexInfo& info = t.by_id[id]->info();
    if (info.shared() || info.cat) {
      out_id[id] = t.n_poly_vertices + static_cast<std::uint32_t>(out.points.size());
      out.points.push_back({info.xy.x, info.xy.y, vertex_height(t.by_id[id], h)});
      if (!info.cat) ++out.crossing_points;
    } else if (info.lower >= 0) {
      out_id[id] = static_cast<std::uint32_t>(info.lower);
    } else if (info.upper >= 0) {
      out_id[id] = static_cast<std::uint32_t>(info.upper);
    } else {
      throw InvalidInput(ErrorCode::Internal, {}, "tile_slices_delaunay: a triangulation point belongs to no contour",
                         "please report this input");
    }
  }
  return out_id;
}

// The output id of a triangulation vertex.
std::uint32_t oid(const std::vector<std::uint32_t>& out_id, VertexHandle v) {
  return out_id[static_cast<std::size_t>(v->info().id)];
}

// Band faces: A\B faces face up and out (counter-clockwise kept), B\A faces down and out.
void emit_band_faces(BandCdt& t, const std::vector<std::uint32_t>& out_id, DelaunayTiling& out) {
  for (FaceHandle f : t.cdt.finite_face_handles()) {
    if (!is_band(t, f)) continue;
    const std::uint32_t a = oid(out_id, f->vertex(0)), b = oid(out_id, f->vertex(1)), c = oid(out_id, f->vertex(2));
    if (f->info().in_lower)
      out.triangles.push_back({a, b, c});
    else
      out.triangles.push_back({a, c, b});
  }
}

// Per polygon (lower first): whether some edge has its own region on its left (kept) or right (reversed).
struct PolygonSides {
  std::vector<char> reversed, kept;
};

// Contour edges split by meeting points (or ending at one): a vertical fan between the edge on
// its slice and the chain of lifted meeting points, oriented by which side is inside.
PolygonSides emit_vertical_fans(BandCdt& t, const std::vector<std::uint32_t>& out_id, std::size_t n_lower_polygons,
                                DelaunayTiling& out) {
  PolygonSides sides{std::vector<char>(t.handles.size(), 0), std::vector<char>(t.handles.size(), 0)};
  for (const InputEdge& e : t.edges) {
    FaceHandle f;
    int i = 0;
    if (!t.cdt.is_edge(e.chain[0], e.chain[1], f, i)) {
      throw InvalidInput(ErrorCode::Internal, {}, "tile_slices_delaunay: a contour sub-edge is missing",
                         "please report this input");
    }
    const FaceHandle left = f->vertex(Cdtp::ccw(i)) == e.chain[0] ? f : f->neighbor(i);
    const bool own = e.slice == 0 ? left->info().in_lower : left->info().in_upper;
    const std::size_t poly = (e.slice == 0 ? 0 : n_lower_polygons) + static_cast<std::size_t>(e.polygon);
    (own ? sides.kept : sides.reversed)[poly] = 1;
    std::vector<std::uint32_t> c;
    for (const VertexHandle& v : e.chain) c.push_back(oid(out_id, v));
    std::uint32_t s = e.a, u = e.b;  // s→u has its own slice's region on the left
    if (!own) {
      std::swap(s, u);
      std::reverse(c.begin(), c.end());
    }
    if (c.size() == 2 && c.front() == s && c.back() == u) continue;  // a band face uses the edge itself
    std::vector<std::uint32_t> fan;
    if (e.slice == 0) {
      fan = {s, u};
      for (std::size_t k = c.size(); k-- > 0;)
        if (c[k] != s && c[k] != u) fan.push_back(c[k]);
    } else {
      fan = {u, s};
      for (std::size_t k = 0; k < c.size(); ++k)
        if (c[k] != s && c[k] != u) fan.push_back(c[k]);
    }
    for (std::size_t k = 1; k + 1 < fan.size(); ++k) out.triangles.push_back({fan[0], fan[k], fan[k + 1]});
  }
  return sides;
}

// Deterministic order: each triangle starts at its smallest id (orientation kept), then sorted.
void sort_triangles(std::vector<Triangle>& triangles) {
  for (Triangle& tri : triangles) std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
  std::sort(triangles.begin(), triangles.end());
}

// Warnings about the polygons' orientation against the nesting found along them.
void report_polygon_sides(const PolygonSides& sides, std::size_t n_lower_polygons, DelaunayTiling& out) {
  for (std::size_t p = 0; p < sides.reversed.size(); ++p) {
    const bool is_lower = p < n_lower_polygons;
    const std::size_t index = is_lower ? p : p - n_lower_polygons;
    if (sides.reversed[p] && sides.kept[p])
      out.warnings.push_back(fmt::format("{} polygon {}: inside and outside disagree along the contour",
                                         is_lower ? "lower" : "upper", index));
    else if (sides.reversed[p])
      out.warnings.push_back(
          fmt::format("{} polygon {} runs against the convention (outer counter-clockwise, holes clockwise); "
                      "the band follows its nesting",
                      is_lower ? "lower" : "upper", index));
  }
}

// Safety net: edges that break "contour edges once, every other edge twice with opposite directions".
std::size_t count_nonmanifold_edges(const std::vector<Triangle>& triangles, const std::vector<InputEdge>& edges) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<int, int>> uses;  // (min, max) → (forward, backward)
  for (const Triangle& tri : triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
      auto& u = uses[{std::min(a, b), std::max(a, b)}];
      (a < b ? u.first : u.second) += 1;
    }
  std::size_t bad = 0;
  for (const InputEdge& e : edges) {
    auto it = uses.find({std::min(e.a, e.b), std::max(e.a, e.b)});
    if (it == uses.end() || it->second.first + it->second.second != 1) ++bad;
    if (it != uses.end()) it->second = {-1, -1};
  }
  for (const auto& [key, u] : uses)
    if (u.first >= 0 && (u.first != 1 || u.second != 1)) ++bad;
  return bad;
}

// Reports what is not perfect, in out.flat_triangles and out.warnings.
void report_warnings(BandCdt& t, const CatOutcome& cat, const PolygonSides& sides, std::size_t n_lower_polygons,
                     const DelaunayTilingOptions& options, DelaunayTiling& out) {
  out.flat_triangles = cat.flat_faces;
  if (cat.flat_faces > 0)
    out.warnings.push_back(
        fmt::format("{} flat triangles left after {} CAT rounds", cat.flat_faces, options.max_cat_rounds));
  if (options.split_flat_edges && !cat.flat_edges.empty())
    out.warnings.push_back(
        fmt::format("{} inner edges lie on a cap after {} CAT rounds", cat.flat_edges.size(), options.max_cat_rounds));
  if (cat.inconsistent) out.warnings.push_back("nesting parity is inconsistent: the contours are not closed polygons");
  report_polygon_sides(sides, n_lower_polygons, out);
  bool overlap = false;
  for (FaceHandle f : t.cdt.finite_face_handles()) overlap = overlap || (f->info().in_lower && f->info().in_upper);
  if (!overlap)
    out.warnings.push_back("the projections of the two slices do not overlap: the band is two separate domes");
  const std::size_t bad = count_nonmanifold_edges(out.triangles, t.edges);
  if (bad > 0)
    out.warnings.push_back(
        fmt::format("the band is not a 2-manifold at {} edges (contours touching from outside?)", bad));
}

}  // namespace

DelaunayTiling tile_slices_delaunay(const std::vector<std::vector<Vec2>>& lower,
                                    const std::vector<std::vector<Vec2>>& upper, double gap,
                                    const DelaunayTilingOptions& options) {
  validate(lower, "lower");
  validate(upper, "upper");
  if (!(gap > 0.0) || !std::isfinite(gap))
    throw InvalidInput(ErrorCode::DuplicatePlane, {}, fmt::format("tile_slices_delaunay: gap {} is not > 0", gap),
                       "the upper slice must lie above the lower slice (positive, finite distance)");
  Heights h;
  h.gap = gap;
  h.crossing_h = std::clamp(options.crossing_height, 0.01, 0.99) * gap;
  h.margin = std::clamp(options.height_margin, 0.0, 0.49);

  DelaunayTiling out;
  BandCdt t;
  // Vertices first, then the edges as constraints: a vertex that lies on another slice's edge
  // splits that constraint where CDT+ records it.
  insert_vertices(t, lower, upper);
  insert_edges(t, lower, upper);
  walk_edge_chains(t);
  check_slices_clean(t);

  const CatOutcome cat = run_cat_rounds(t, h, options, out);
  const std::vector<std::uint32_t> out_id = output_ids(t, h, out);
  emit_band_faces(t, out_id, out);
  const std::size_t n_lower_polygons = lower.size();
  const PolygonSides sides = emit_vertical_fans(t, out_id, n_lower_polygons, out);
  sort_triangles(out.triangles);
  report_warnings(t, cat, sides, n_lower_polygons, options, out);
  return out;
}

}  // namespace c4d
