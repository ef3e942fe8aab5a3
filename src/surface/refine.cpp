// Remeshing for triangle quality: Lim et al. 2014, "Surface Smoothing and Refinement" refines the
// coarse surface; we use CGAL's isotropic remeshing (Botsch & Kobbelt 2004, "A remeshing approach
// to multiresolution modeling") with the input contours as constrained polylines, so they remain
// chains of mesh edges (split only, never moved) and conformity stays exact.
#include "contour4d/surface/refine.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "contour4d/surface/angle_repair.h"
#include "contour4d/surface/isotropic_remesh.h"

namespace c4d {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

}  // namespace

void remesh_isotropic(TriangleMesh& mesh, std::vector<std::array<std::uint32_t, 2>>& constrained,
                      std::vector<char>& fixed, const RemeshOptions& options) {
  if (options.engine == RemeshEngine::Fast && !options.split_constraints &&
      remesh_isotropic_fast(mesh, constrained, fixed, options.edge, options.iterations))
    return;
  Mesh sm;
  std::vector<Mesh::Vertex_index> vid;
  vid.reserve(mesh.positions.size());
  for (const Vec3& p : mesh.positions) vid.push_back(sm.add_vertex(K::Point_3(p.x, p.y, p.z)));
  for (const Triangle& t : mesh.triangles)
    if (sm.add_face(vid[t[0]], vid[t[1]], vid[t[2]]) == Mesh::null_face()) return;  // not manifold: leave as is
  auto ecm = sm.add_property_map<Mesh::Edge_index, bool>("e:c4d_constrained", false).first;
  auto vcm = sm.add_property_map<Mesh::Vertex_index, bool>("v:c4d_fixed", false).first;
  for (const auto& e : constrained) {
    const auto h = sm.halfedge(vid[e[0]], vid[e[1]]);
    if (h != Mesh::null_halfedge()) ecm[sm.edge(h)] = true;
  }
  fixed.resize(mesh.positions.size(), 0);
  for (std::size_t i = 0; i < fixed.size(); ++i)
    if (fixed[i]) vcm[vid[i]] = true;
  PMP::isotropic_remeshing(faces(sm), options.edge, sm,
                           CGAL::parameters::number_of_iterations(static_cast<unsigned>(options.iterations))
                               .edge_is_constrained_map(ecm)
                               .vertex_is_constrained_map(vcm)
                               .protect_constraints(!options.split_constraints)
                               .collapse_constraints(false)
                               .relax_constraints(false));
  sm.collect_garbage();
  // Back to plain arrays; vertices in Surface_mesh order (old ones keep their relative order).
  TriangleMesh out;
  std::vector<std::uint32_t> index(sm.number_of_vertices() + sm.number_of_removed_vertices(), 0);
  std::vector<char> out_fixed;
  for (auto v : sm.vertices()) {
    index[v] = static_cast<std::uint32_t>(out.positions.size());
    const auto& p = sm.point(v);
    out.positions.push_back({p.x(), p.y(), p.z()});
    out_fixed.push_back(vcm[v] ? 1 : 0);
  }
  for (auto f : sm.faces()) {
    Triangle t{};
    int k = 0;
    for (auto v : vertices_around_face(sm.halfedge(f), sm)) t[k++] = index[v];
    out.triangles.push_back(t);
  }
  constrained.clear();
  for (auto e : sm.edges()) {
    if (!ecm[e]) continue;
    const std::uint32_t a = index[sm.vertex(e, 0)], b = index[sm.vertex(e, 1)];
    constrained.push_back({std::min(a, b), std::max(a, b)});
    out_fixed[a] = out_fixed[b] = 1;  // split points of contour edges lie on the contour: keep them
  }
  std::sort(constrained.begin(), constrained.end());
  mesh = std::move(out);
  fixed = std::move(out_fixed);
}

namespace {

double angle_at(const Vec3& p, const Vec3& q, const Vec3& r) {
  const Vec3 u = q - p, w = r - p;
  return std::atan2(norm(cross(u, w)), dot(u, w));
}

using Edge = std::pair<std::uint32_t, std::uint32_t>;
constexpr std::size_t kNone = static_cast<std::size_t>(-1);

// Directed edge a→b → triangle holding it, per vertex a: a few entries each, scanned in order (a
// linear scan beats a hash). All vertices' lists lie in one array, each with room for its first
// degree and some more (a flip adds one edge at each of its two far vertices); a list that outgrows
// its room has the whole array laid out again with more, the entries kept in their order.
struct Owner {
  std::uint32_t to;
  std::size_t tri;
};
struct OwnerTable {
  std::size_t nv = 0;
  std::uint32_t slack = 4;
  std::vector<std::uint32_t> first, count;  // per vertex: its list's start and length
  std::vector<Owner> owners;
};

// Lays the lists out again with `slack` free entries each, the entries kept in their order.
void lay_out(OwnerTable& o, std::uint32_t slack) {
  std::vector<std::uint32_t> new_first(o.nv + 1, 0);
  for (std::size_t v = 0; v < o.nv; ++v) new_first[v + 1] = new_first[v] + o.count[v] + slack;
  std::vector<Owner> moved(new_first[o.nv]);
  if (!o.owners.empty())
    for (std::size_t v = 0; v < o.nv; ++v)
      std::copy_n(o.owners.begin() + o.first[v], o.count[v], moved.begin() + new_first[v]);
  o.first.swap(new_first);
  o.owners.swap(moved);
}

// The triangle holding directed edge a→b, or kNone.
std::size_t owner_of(const OwnerTable& o, std::uint32_t a, std::uint32_t b) {
  for (std::uint32_t k = o.first[a], e = o.first[a] + o.count[a]; k < e; ++k)
    if (o.owners[k].to == b) return o.owners[k].tri;
  return kNone;
}

// Records triangle t as holding directed edge a→b (growing the lists when a's is full).
void set_owner(OwnerTable& o, std::uint32_t a, std::uint32_t b, std::size_t t) {
  for (std::uint32_t k = o.first[a], e = o.first[a] + o.count[a]; k < e; ++k)
    if (o.owners[k].to == b) {
      o.owners[k].tri = t;
      return;
    }
  if (o.first[a] + o.count[a] == o.first[a + 1]) {
    o.slack *= 2;
    lay_out(o, o.slack);
  }
  o.owners[o.first[a] + o.count[a]++] = {b, t};
}

// Forgets directed edge a→b.
void erase_owner(OwnerTable& o, std::uint32_t a, std::uint32_t b) {
  for (std::uint32_t k = o.first[a], e = o.first[a] + o.count[a]; k < e; ++k)
    if (o.owners[k].to == b) {
      std::copy(o.owners.begin() + k + 1, o.owners.begin() + e, o.owners.begin() + k);
      --o.count[a];
      return;
    }
}

// The owner table of the triangles. `plain` (in: whether acute edges may skip the full test) is
// cleared unless every directed edge lies in one triangle and every triangle has three distinct vertices.
OwnerTable owner_table(const std::vector<Triangle>& tris, std::size_t nv, bool& plain) {
  OwnerTable o;
  o.nv = nv;
  o.first.assign(nv + 1, 0);
  o.count.assign(nv, 0);
  for (const Triangle& t : tris)
    for (std::uint32_t v : t) ++o.count[v];
  lay_out(o, o.slack);
  std::fill(o.count.begin(), o.count.end(), 0);
  for (std::size_t t = 0; t < tris.size(); ++t) {
    const Triangle& tri = tris[t];
    plain = plain && tri[0] != tri[1] && tri[1] != tri[2] && tri[2] != tri[0];
    for (int k = 0; k < 3; ++k) {
      plain = plain && owner_of(o, tri[k], tri[(k + 1) % 3]) == kNone;
      set_owner(o, tri[k], tri[(k + 1) % 3], t);
    }
  }
  return o;
}

// Contour edges, per lower vertex (one array, vertex by vertex, in the listed order).
struct FixedEdges {
  std::vector<std::uint32_t> first, to;
};

// The contour edges bucketed by their lower vertex.
FixedEdges fixed_edges(const std::vector<std::array<std::uint32_t, 2>>& constrained, std::size_t nv) {
  FixedEdges f{std::vector<std::uint32_t>(nv + 1, 0), std::vector<std::uint32_t>(constrained.size())};
  for (const auto& e : constrained) ++f.first[std::min(e[0], e[1]) + 1];
  for (std::size_t v = 0; v < nv; ++v) f.first[v + 1] += f.first[v];
  std::vector<std::uint32_t> fill(f.first.begin(), f.first.end() - 1);
  for (const auto& e : constrained) f.to[fill[std::min(e[0], e[1])]++] = std::max(e[0], e[1]);
  return f;
}

// Whether a-b (a < b) is a contour edge.
bool is_fixed(const FixedEdges& f, std::uint32_t a, std::uint32_t b) {
  const auto from = f.to.begin() + f.first[a], to = f.to.begin() + f.first[a + 1];
  return std::find(from, to, b) != to;
}

// The vertex of triangle t other than a and b (a when there is none).
std::uint32_t third(const Triangle& t, std::uint32_t a, std::uint32_t b) {
  for (std::uint32_t v : t)
    if (v != a && v != b) return v;
  return a;
}

// A round's edges: undirected, sorted by their vertex ids (bucketed by the lower one, each bucket
// of a few sorted by the other); bucket[v] ends vertex v's edges.
struct RoundEdges {
  std::vector<std::uint32_t> bucket;
  std::vector<Edge> edges;
};

// The mesh's undirected edges in sorted order, for one round.
RoundEdges sorted_edges(const std::vector<Triangle>& tris, std::size_t nv) {
  RoundEdges r;
  r.bucket.assign(nv + 1, 0);
  for (const auto& tri : tris)
    for (int k = 0; k < 3; ++k)
      if (tri[k] < tri[(k + 1) % 3]) ++r.bucket[tri[k] + 1];
  for (std::size_t v = 0; v < nv; ++v) r.bucket[v + 1] += r.bucket[v];
  r.edges.resize(r.bucket[nv]);
  for (const auto& tri : tris)
    for (int k = 0; k < 3; ++k)
      if (tri[k] < tri[(k + 1) % 3]) r.edges[r.bucket[tri[k]]++] = {tri[k], tri[(k + 1) % 3]};
  for (std::size_t v = 0, from = 0; v < nv; ++v) {  // bucket[v] now ends vertex v's edges
    std::sort(r.edges.begin() + static_cast<std::ptrdiff_t>(from),
              r.edges.begin() + static_cast<std::ptrdiff_t>(r.bucket[v]));
    from = r.bucket[v];
  }
  return r;
}

// Marks edge u-w for the full test at its positions from `from_position` on.
void mark(const RoundEdges& r, std::vector<char>& candidate, std::uint32_t u, std::uint32_t w,
          std::size_t from_position) {
  const Edge key{std::min(u, w), std::max(u, w)};
  const std::size_t first = key.first == 0 ? std::size_t{0} : static_cast<std::size_t>(r.bucket[key.first - 1]);
  const auto from = r.edges.begin() + static_cast<std::ptrdiff_t>(first);
  const auto to = r.edges.begin() + static_cast<std::ptrdiff_t>(r.bucket[key.first]);
  const auto [lo, hi] = std::equal_range(from, to, key);
  for (auto it = lo; it != hi; ++it) {
    const auto at = static_cast<std::size_t>(it - r.edges.begin());
    if (at >= from_position) candidate[at] = 1;
  }
}

// Edge a-b between triangles t1 = (a, b, c) and t2 = (b, a, d) flipped into (c, a, d), (c, d, b).
void flip(std::vector<Triangle>& tris, OwnerTable& o, std::size_t t1, std::size_t t2, std::uint32_t a, std::uint32_t b,
          std::uint32_t c, std::uint32_t d) {
  erase_owner(o, a, b);
  erase_owner(o, b, a);
  tris[t1] = {c, a, d};
  tris[t2] = {c, d, b};
  for (std::size_t t : {t1, t2})
    for (int k = 0; k < 3; ++k) set_owner(o, tris[t][k], tris[t][(k + 1) % 3], t);
}

// The smallest angle of the pair (a, b, c), (b, a, d) and of the flipped pair (c, a, d), (c, d, b).
std::pair<double, double> pair_min_angles(const std::vector<Vec3>& x, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                                          std::uint32_t d) {
  return {std::min(min_angle_deg(x[a], x[b], x[c]), min_angle_deg(x[b], x[a], x[d])),
          std::min(min_angle_deg(x[c], x[a], x[d]), min_angle_deg(x[c], x[d], x[b]))};
}

// Whether the flipped triangles (c, a, d) and (c, d, b) both face along `n` (no fold).
bool flipped_pair_faces(const std::vector<Vec3>& x, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d,
                        Vec3 n) {
  const Vec3 m1 = cross(x[a] - x[c], x[d] - x[c]), m2 = cross(x[d] - x[c], x[b] - x[c]);
  return !(dot(m1, n) <= 0 || dot(m2, n) <= 0);
}

// Whether edge a-b between triangles (a, b, c) and (b, a, d) is flipped into (c, a, d), (c, d, b):
// not Delaunay, the new edge c-d not there yet, the pair nearly coplanar (or one near-flat) and no fold.
bool wants_flip(const OwnerTable& o, const std::vector<Vec3>& x, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                std::uint32_t d, const FlipOptions& options, double cos_dihedral) {
  // Both opposite angles acute: their sum is at most π (each atan2 below returns at most π/2), so
  // the edge is Delaunay; most are, and this spares their two atan2.
  if (dot(x[a] - x[c], x[b] - x[c]) > 0 && dot(x[b] - x[d], x[a] - x[d]) > 0) return false;
  if (c == d || owner_of(o, c, d) != kNone || owner_of(o, d, c) != kNone) return false;
  if (angle_at(x[c], x[a], x[b]) + angle_at(x[d], x[b], x[a]) <= std::numbers::pi + 1e-9) return false;
  if (options.only_below_deg > 0) {
    const auto [before, after] = pair_min_angles(x, a, b, c, d);
    if (before >= options.only_below_deg || after <= before) return false;
  }
  const Vec3 n1 = cross(x[b] - x[a], x[c] - x[a]), n2 = cross(x[a] - x[b], x[d] - x[b]);
  const double l1 = norm(n1), l2 = norm(n2);
  // Near-flat triangles (normal undefined: twice the area below 2 % of the squared edge, about a
  // 1° angle) always qualify; others only where the pair is nearly coplanar.
  const double ab2 = dot(x[b] - x[a], x[b] - x[a]);
  const bool flat1 = l1 <= 0.02 * ab2, flat2 = l2 <= 0.02 * ab2;
  if (!flat1 && !flat2 && dot(n1, n2) < cos_dihedral * l1 * l2) return false;
  if (flat1 && flat2) return false;
  const Vec3 n = flat1 ? n2 / l2 : flat2 ? n1 / l1 : n1 / l1 + n2 / l2;
  // New triangles (c,a,d) and (c,d,b) must face the same way as the pair did (no fold).
  return flipped_pair_faces(x, a, b, c, d, n);
}

// One round over every edge in sorted order, flipping where wanted; returns the number of flips.
std::size_t flip_round(TriangleMesh& mesh, OwnerTable& o, const FixedEdges& fixed, bool plain,
                       const FlipOptions& options, double cos_dihedral) {
  auto& tris = mesh.triangles;
  const auto& x = mesh.positions;
  std::size_t flipped_now = 0;
  const RoundEdges r = sorted_edges(tris, mesh.positions.size());
  // The test ends at once for an edge whose two opposite angles are acute, and everything it reads
  // before that only decides between other ends at once. So an edge needs the test only where a
  // triangle beside it at the round's start has a right or obtuse angle opposite it, or where a flip
  // earlier in this round changed a triangle beside it: the others are skipped with the same
  // outcome, and the flips are those of testing every edge.
  std::vector<char> candidate(r.edges.size(), plain ? 0 : 1);
  if (plain)
    for (const Triangle& tri : tris)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t c = tri[k], p = tri[(k + 1) % 3], q = tri[(k + 2) % 3];
        if (!(dot(x[p] - x[c], x[q] - x[c]) > 0)) mark(r, candidate, p, q, 0);
      }
  for (std::size_t i = 0; i < r.edges.size(); ++i) {
    if (!candidate[i]) continue;
    const auto [a, b] = r.edges[i];
    if (is_fixed(fixed, a, b)) continue;
    const std::size_t t1 = owner_of(o, a, b), t2 = owner_of(o, b, a);
    if (t1 == kNone || t2 == kNone) continue;  // boundary or already flipped away
    const std::uint32_t c = third(tris[t1], a, b), d = third(tris[t2], a, b);
    if (!wants_flip(o, x, a, b, c, d, options, cos_dihedral)) continue;
    flip(tris, o, t1, t2, a, b, c, d);
    // The edges whose triangles changed get the full test where they come later in this round.
    if (plain)
      for (const auto& [u, w] : {Edge{a, b}, Edge{b, c}, Edge{c, a}, Edge{a, d}, Edge{d, b}, Edge{c, d}})
        mark(r, candidate, u, w, i + 1);
    ++flipped_now;
  }
  return flipped_now;
}

// Whether the chord a-b of ear (a, b, c) (c the middle contour vertex) is flipped into (c, a, d), (c, d, b):
// d off every contour, the edge c-d not there yet, the new pair facing as the old one (no fold) and its smallest
// angle at least kEarFloorDeg or larger than the old pair's.
constexpr double kEarFloorDeg = 15.0;

bool wants_ear_flip(const OwnerTable& o, const std::vector<Vec3>& x, const std::vector<char>& on_contour,
                    std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  if (on_contour[d] || c == d || owner_of(o, c, d) != kNone || owner_of(o, d, c) != kNone) return false;
  const Vec3 n1 = cross(x[b] - x[a], x[c] - x[a]), n2 = cross(x[a] - x[b], x[d] - x[b]);
  const double l1 = norm(n1), l2 = norm(n2);
  if (!(l2 > 0.0)) return false;
  const Vec3 n = l1 > 0.02 * dot(x[b] - x[a], x[b] - x[a]) ? n1 / l1 + n2 / l2 : n2 / l2;
  if (!flipped_pair_faces(x, a, b, c, d, n)) return false;
  const auto [before, after] = pair_min_angles(x, a, b, c, d);
  return after >= kEarFloorDeg || after > before;
}

}  // namespace

std::size_t flip_edges_delaunay(TriangleMesh& mesh, const std::vector<std::array<std::uint32_t, 2>>& constrained,
                                const FlipOptions& options) {
  const std::size_t nv = mesh.positions.size();
  // Edges that skip the full test need every directed edge in one triangle and triangles of three
  // distinct vertices; otherwise every edge gets the full test.
  bool plain = options.skip_acute;
  OwnerTable owners = owner_table(mesh.triangles, nv, plain);
  const FixedEdges fixed = fixed_edges(constrained, nv);
  const double cos_dihedral = std::cos(options.max_dihedral_deg * std::numbers::pi / 180.0);
  std::size_t flips = 0;
  for (int round = 0; round < options.max_rounds; ++round) {
    const std::size_t flipped_now = flip_round(mesh, owners, fixed, plain, options, cos_dihedral);
    flips += flipped_now;
    if (flipped_now == 0) break;
  }
  return flips;
}

std::size_t flip_ears(TriangleMesh& mesh, const std::vector<std::array<std::uint32_t, 2>>& constrained) {
  const std::size_t nv = mesh.positions.size();
  bool plain = false;
  OwnerTable owners = owner_table(mesh.triangles, nv, plain);
  const FixedEdges fixed = fixed_edges(constrained, nv);
  std::vector<char> on_contour(nv, 0);
  for (const auto& e : constrained) on_contour[e[0]] = on_contour[e[1]] = 1;
  auto contour_edge = [&](std::uint32_t u, std::uint32_t w) { return is_fixed(fixed, std::min(u, w), std::max(u, w)); };
  auto& tris = mesh.triangles;
  std::size_t flips = 0;
  for (std::size_t t1 = 0; t1 < tris.size(); ++t1)
    for (int k = 0; k < 3; ++k) {
      // Ear: the edges at c are contour edges, the chord a-b is not.
      const std::uint32_t a = tris[t1][k], b = tris[t1][(k + 1) % 3], c = tris[t1][(k + 2) % 3];
      if (!contour_edge(b, c) || !contour_edge(c, a) || contour_edge(a, b)) continue;
      const std::size_t t2 = owner_of(owners, b, a);
      if (t2 == kNone || owner_of(owners, a, b) != t1) continue;
      const std::uint32_t d = third(tris[t2], a, b);
      if (!wants_ear_flip(owners, mesh.positions, on_contour, a, b, c, d)) continue;
      flip(tris, owners, t1, t2, a, b, c, d);
      ++flips;
      break;
    }
  return flips;
}

}  // namespace c4d
