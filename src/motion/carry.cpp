// All frames, each on its own (carry.h): Miara et al. §III.D–E (one base mesh, per-frame
// displacements) with Lim et al. 2014's contour matching (Fig. 7) for the chains that keep a partner,
// a thin-plate displacement (Botsch & Sorkine 2008) for the rest, then tangential relaxation and a
// sheet-aware projection onto the frame's own surface.
#include "contour4d/motion/carry.h"

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <numbers>

#include <tbb/parallel_for.h>

#include "contour4d/connect/similarity.h"
#include "contour4d/core/contour.h"
#include "contour4d/core/errors.h"
#include "contour4d/core/normals.h"
#include "contour4d/core/sparse_solve.h"
#include "contour4d/motion/chains.h"
#include "contour4d/metrics/topology.h"
#include "contour4d/motion/contour_matching.h"
#include "contour4d/motion/disc_map.h"
#include "contour4d/surface/angle_repair.h"
#include "contour4d/metrics/surface_projector.h"

namespace c4d {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Rings = std::vector<std::vector<std::uint32_t>>;

// Each vertex's neighbours over the mesh's edges, sorted.
Rings vertex_rings(std::size_t n, const std::vector<Triangle>& tris) {
  Rings r(n);
  for (const Triangle& t : tris)
    for (int k = 0; k < 3; ++k) {
      r[t[static_cast<std::size_t>(k)]].push_back(t[static_cast<std::size_t>((k + 1) % 3)]);
      r[t[static_cast<std::size_t>((k + 1) % 3)]].push_back(t[static_cast<std::size_t>(k)]);
    }
  for (auto& ring : r) {
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  }
  return r;
}

// Q = LᵀL of the uniform ("umbrella") Laplacian (L x)_i = x_i − mean of i's neighbours.
SparseMatrix bilaplacian(const Rings& rings) {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t i = 0; i < rings.size(); ++i) {
    t.emplace_back(static_cast<int>(i), static_cast<int>(i), 1.0);
    for (std::uint32_t j : rings[i])  // (an isolated vertex has no neighbour terms)
      t.emplace_back(static_cast<int>(i), static_cast<int>(j), -1.0 / static_cast<double>(rings[i].size()));
  }
  const auto n = static_cast<int>(rings.size());
  SparseMatrix L(n, n);
  L.setFromTriplets(t.begin(), t.end());
  return SparseMatrix(L.transpose() * L);
}

// A matched chain's size and place in frame 0 and in frame t (centroids in mm, radii of equal area).
struct MatchedLoop {
  double height = 0;  // along the stack normal
  Vec3 c0, ct;
  double r0 = 0, rt = 0;
};

// Where frame t puts frame 0's matched chains: a target per chain vertex (fixed in the thin-plate guess),
// and the contour it slides along afterwards.
struct FrameTargets {
  std::vector<char> fixed;               // per vertex
  std::vector<Vec3> target;              // per vertex (meaningful where fixed)
  std::vector<std::int32_t> line;        // per vertex: index into `lines`, −1 when not on a matched chain
  std::vector<char> orphan;              // per vertex: on a chain whose contour vanished, split or merged
  std::vector<std::vector<Vec3>> lines;  // the matched contours of frame t
  std::vector<const std::vector<std::uint32_t>*> line_loops;  // per line: frame 0's chain on it, in order
  std::vector<MatchedLoop> loops;
  int matched = 0, unmatched = 0;
};

Vec2 centroid(const std::vector<Vec2>& p) {
  Vec2 c{0, 0};
  for (const Vec2& q : p) c = c + q;
  return (1.0 / static_cast<double>(std::max<std::size_t>(1, p.size()))) * c;
}

double equal_area_radius(const std::vector<Vec2>& p) { return std::sqrt(std::abs(signed_area(p)) / std::numbers::pi); }

std::vector<Vec2> flatten(const Plane& pl, const std::vector<Vec3>& pts) {
  std::vector<Vec2> out;
  out.reserve(pts.size());
  for (const Vec3& p : pts) out.push_back(to_plane(pl, p));
  return out;
}

// Per contour of one slice, how many of the others contain it: an even depth bounds material, an
// odd one a hole (a myocardium's cavity). Only contours of the same parity can be partners.
std::vector<int> nesting_depths(const std::vector<std::vector<Vec2>>& polys) {
  std::vector<int> depth(polys.size(), 0);
  for (std::size_t i = 0; i < polys.size(); ++i)
    for (std::size_t j = 0; j < polys.size(); ++j)
      if (i != j && !polys[i].empty() && point_in_polygon(polys[i].front(), polys[j])) ++depth[i];
  return depth;
}

// One slice: frame 0's chains there against frame t's contours there, one-to-one by similarity; each
// matched chain mapped onto its contour by arc length (every k-th vertex where the contour shrank).
void match_slice(const std::vector<const Chain*>& chains, const Slice* slice, const std::vector<Vec3>& x0,
                 const CarryOptions& opt, FrameTargets& out) {
  if (!slice) {
    out.unmatched += static_cast<int>(chains.size());
    for (const Chain* c : chains)
      for (std::uint32_t v : c->loop) out.orphan[v] = 1;
    return;
  }
  const Plane& pl = chains.front()->plane;
  std::vector<std::vector<Vec2>> a, b;
  for (const Chain* c : chains) {
    std::vector<Vec3> pts;
    for (std::uint32_t v : c->loop) pts.push_back(x0[v]);
    a.push_back(flatten(pl, pts));
  }
  for (const Contour& c : slice->contours) b.push_back(flatten(pl, c.points));
  const std::vector<int> da = nesting_depths(a), db = nesting_depths(b);
  std::vector<std::vector<double>> sim(a.size(), std::vector<double>(b.size()));
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j)
      sim[i][j] = (da[i] % 2 == db[j] % 2) ? contour_similarity(a[i], b[j]) : 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const int partner = one_to_one_partner(sim, i, opt.threshold);
    if (partner < 0) {
      ++out.unmatched;
      for (std::uint32_t v : chains[i]->loop) out.orphan[v] = 1;
      continue;
    }
    const ContourMatch m = match_contour(a[i], b[static_cast<std::size_t>(partner)]);
    const std::vector<Vec2>& partner_poly = b[static_cast<std::size_t>(partner)];
    out.loops.push_back({dot(pl.origin, pl.normal), from_plane(pl, centroid(a[i])),
                         from_plane(pl, centroid(partner_poly)), equal_area_radius(a[i]),
                         equal_area_radius(partner_poly)});
    const auto line = static_cast<std::int32_t>(out.lines.size());
    out.lines.push_back(slice->contours[static_cast<std::size_t>(partner)].points);
    out.line_loops.push_back(&chains[i]->loop);
    const std::vector<std::uint32_t>& loop = chains[i]->loop;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      out.fixed[loop[k]] = 1;
      out.target[loop[k]] = from_plane(pl, m.targets[k]);
      out.line[loop[k]] = line;
    }
    ++out.matched;
  }
}

FrameTargets match_frame(const Sequence& seq, const std::map<int, std::vector<const Chain*>>& by_slice,
                         const std::vector<Vec3>& x0, std::size_t t, const CarryOptions& opt) {
  FrameTargets out;
  out.fixed.assign(x0.size(), 0);
  out.target.assign(x0.size(), Vec3{});
  out.line.assign(x0.size(), -1);
  out.orphan.assign(x0.size(), 0);
  const Frame& frame = seq.frames[t];
  for (const auto& [id, chains] : by_slice) {
    const auto it =
        std::find_if(frame.slices.begin(), frame.slices.end(), [id = id](const Slice& s) { return s.id == id; });
    match_slice(chains, it == frame.slices.end() ? nullptr : &*it, x0, opt, out);
  }
  return out;
}

// The thin-plate system of one set of fixed vertices: Q restricted to the free vertices, factored once.
struct ThinPlate {
  std::vector<int> column;  // per vertex: its column among the free vertices, −1 when fixed
  SparseLdlt ldlt;
};

void factor(const SparseMatrix& q, const std::vector<char>& fixed, ThinPlate& tp) {
  tp.column.assign(fixed.size(), -1);
  int nf = 0;
  for (std::size_t v = 0; v < fixed.size(); ++v)
    if (!fixed[v]) tp.column[v] = nf++;
  std::vector<Eigen::Triplet<double>> lower;
  for (int c = 0; c < q.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(q, c); it; ++it) {
      const int i = tp.column[static_cast<std::size_t>(it.row())], j = tp.column[static_cast<std::size_t>(it.col())];
      if (i >= 0 && j >= 0 && i >= j) lower.emplace_back(i, j, it.value());
    }
  // A component with no fixed vertex would make the system singular: a tiny pull to zero displacement.
  for (int i = 0; i < nf; ++i) lower.emplace_back(i, i, 1e-9);
  SparseMatrix a(nf, nf);
  a.setFromTriplets(lower.begin(), lower.end());
  if (nf > 0 && !factor_lower(tp.ldlt, a))
    throw SolverError(ErrorCode::Internal, {}, "carry_frames: the thin-plate system cannot be factored");
}

// Frame 0's positions plus the thin-plate displacement that puts the fixed vertices on their targets.
std::vector<Vec3> thin_plate_guess(const SparseMatrix& q, const ThinPlate& tp, const std::vector<Vec3>& x0,
                                   const FrameTargets& ft) {
  const auto n = static_cast<Eigen::Index>(x0.size());
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n, 3);
  for (Eigen::Index v = 0; v < n; ++v)
    if (ft.fixed[static_cast<std::size_t>(v)]) {
      const Vec3 e = ft.target[static_cast<std::size_t>(v)] - x0[static_cast<std::size_t>(v)];
      d.row(v) << e.x, e.y, e.z;
    }
  std::vector<Vec3> x = x0;
  for (std::size_t v = 0; v < x.size(); ++v)
    if (ft.fixed[v]) x[v] = ft.target[v];
  const Eigen::MatrixXd qd = q * d;
  Eigen::Index nf = 0;
  for (int c : tp.column) nf += c >= 0;
  if (nf == 0) return x;
  Eigen::MatrixXd rhs(nf, 3);
  for (std::size_t v = 0; v < x.size(); ++v)
    if (tp.column[v] >= 0) rhs.row(tp.column[v]) = -qd.row(static_cast<Eigen::Index>(v));
  const Eigen::MatrixXd free = ldlt_solve(tp.ldlt, rhs);
  for (std::size_t v = 0; v < x.size(); ++v)
    if (tp.column[v] >= 0) {
      const auto r = tp.column[v];
      x[v] = x0[v] + Vec3{free(r, 0), free(r, 1), free(r, 2)};
    }
  return x;
}

// Sheet-aware projection of the free vertices onto the frame's surface. A vertex without a hint asks the
// tree for its closest point; where that faces away (another sheet), it walks instead from a neighbour
// that landed, which stays on the neighbour's sheet. Vertices that find no landing keep their place.
// Returns the number of vertices left off the surface.
// `landing` gets, per vertex, the normal of the surface where it landed (its vertex normal where it did not).
std::size_t project_on_sheet(std::vector<Vec3>& x, const std::vector<char>& skip, const Rings& rings,
                             const std::vector<Triangle>& tris, const SurfaceProjector& surface,
                             std::vector<std::int32_t>& hints, double sheet_cos, std::vector<Vec3>& landing,
                             std::vector<double>* moved = nullptr) {
  const std::vector<Vec3> normals = vertex_normals(TriangleMesh{x, tris});
  landing = normals;
  std::vector<char> landed(x.size(), 0);
  std::vector<Vec3> p = x;
  auto try_land = [&](std::size_t v, std::int32_t hint, bool tree) {
    Vec3 nq{};
    const Vec3 q = tree ? surface.closest(x[v], &nq, &hint) : surface.walk(x[v], &nq, &hint);
    if (!(dot(nq, normals[v]) >= sheet_cos)) return false;
    p[v] = q;
    landing[v] = nq;
    hints[v] = hint;
    landed[v] = 1;
    return true;
  };
  for (std::size_t v = 0; v < x.size(); ++v) {
    if (skip[v]) continue;
    if (hints[v] >= 0 ? try_land(v, hints[v], false) : try_land(v, -1, true)) continue;
    hints[v] = -1;
  }
  // Vertices still off: walk from a landed neighbour, spreading over the sheet (bounded passes).
  for (int pass = 0; pass < 8; ++pass) {
    bool any = false;
    for (std::size_t v = 0; v < x.size(); ++v) {
      if (skip[v] || landed[v]) continue;
      for (std::uint32_t u : rings[v])
        if (landed[u] && hints[u] >= 0 && try_land(v, hints[u], false)) {
          any = true;
          break;
        }
    }
    if (!any) break;
  }
  std::size_t off = 0;
  for (std::size_t v = 0; v < x.size(); ++v) {
    if (skip[v]) continue;
    if (moved) (*moved)[v] = norm(p[v] - x[v]);
    off += !landed[v];
  }
  x = std::move(p);
  return off;
}

// One round of tangential smoothing of the free vertices (Jacobi: every vertex from the old positions), in
// the tangent plane of the surface where each vertex landed (a folded mesh's own normals are unreliable).
void relax_tangentially(std::vector<Vec3>& x, const Rings& rings, const std::vector<Vec3>& normals, double step) {
  std::vector<Vec3> out = x;
  for (std::size_t v = 0; v < x.size(); ++v) {
    if (rings[v].empty()) continue;
    Vec3 c{};
    for (std::uint32_t u : rings[v]) c += x[u];
    Vec3 d = c / static_cast<double>(rings[v].size()) - x[v];
    d -= dot(d, normals[v]) * normals[v];
    out[v] = x[v] + step * d;
  }
  x = std::move(out);
}

// Distance along the ray o + s·d (s > 0) to the first triangle of (x, tris) it hits, among the triangles
// `use` accepts whose normal faces the ray's way (`facing` > 0) or against it (< 0); −1 when none
// (Möller–Trumbore over every triangle: a few rays per frame).
template <class Use>
double first_hit(Vec3 o, Vec3 d, const std::vector<Vec3>& x, const std::vector<Triangle>& tris, int facing, Use use) {
  double best = -1;
  for (std::size_t k = 0; k < tris.size(); ++k) {
    if (!use(k)) continue;
    const Triangle& t = tris[k];
    const Vec3 e1 = x[t[1]] - x[t[0]], e2 = x[t[2]] - x[t[0]];
    if ((dot(cross(e1, e2), d) > 0 ? 1 : -1) != facing) continue;
    const Vec3 p = cross(d, e2);
    const double det = dot(e1, p);
    if (std::abs(det) < 1e-12) continue;
    const Vec3 s = o - x[t[0]];
    const double u = dot(s, p) / det;
    if (u < 0 || u > 1) continue;
    const Vec3 q = cross(s, e1);
    const double v = dot(d, q) / det;
    if (v < 0 || u + v > 1) continue;
    const double h = dot(e2, q) / det;
    if (h > 1e-9 && (best < 0 || h < best)) best = h;
  }
  return best;
}

// The retreated region `members` of frame 0's mesh (a disc bounded by the matched chain on `line`) laid onto
// the frame's own dome beyond that contour (disc_map.h): both flattened with their borders by arc length
// along the contour, each member lifted from its place. False (guess untouched) when either is not a disc.
bool map_dome(std::vector<Vec3>& guess, const std::vector<Vec3>& x0, const std::vector<Triangle>& tris,
              const std::vector<std::int32_t>& region, std::int32_t id, const FrameTargets& ft, std::size_t line,
              const TriangleMesh& own, Vec3 dir) {
  const std::vector<Vec3>& contour = ft.lines[line];
  Disc from;
  from.border = *ft.line_loops[line];
  for (const Triangle& t : tris)
    if (region[t[0]] == id || region[t[1]] == id || region[t[2]] == id) from.triangles.push_back(t);
  if (!is_disc(from.triangles)) return false;
  const Disc onto = disc_beyond(own, contour, dir);
  if (onto.triangles.empty()) return false;
  std::vector<Vec3> from_border, onto_border;
  for (std::uint32_t v : from.border) from_border.push_back(ft.target[v]);
  for (std::uint32_t v : onto.border) onto_border.push_back(own.positions[v]);
  const std::vector<Vec2> uv_from = flatten_disc(x0, from, turns_along(contour, from_border));
  const std::vector<Vec2> uv_onto = flatten_disc(own.positions, onto, turns_along(contour, onto_border));
  std::vector<std::uint32_t> members;
  std::vector<Vec2> where;
  for (std::size_t v = 0; v < x0.size(); ++v)
    if (region[v] == id) {
      members.push_back(static_cast<std::uint32_t>(v));
      where.push_back(uv_from[v]);
    }
  const std::vector<Vec3> lifted = lift_from_disc(where, own.positions, onto, uv_onto);
  for (std::size_t k = 0; k < members.size(); ++k) guess[members[k]] = lifted[k];
  return true;
}

// A retreating dome: the vertices off the matched chains that hang from exactly one matched chain and
// hold a chain whose contour vanished (an apex or base, or a myocardium's cavity, that moved back
// through a slice plane). The thin-plate guess only extrapolates there, far off. Frame 0's region is laid
// onto frame t's own dome beyond that chain's contour, one-to-one (map_dome). Where either is not a disc, it
// is scaled onto it about that chain instead: in the plane by the ratio of the chain's and its contour's
// equal-area radii, along the normal by the ratio of the domes' heights at the contour's centroid (the
// first sheet a ray from it meets that faces as frame 0's dome does: a cavity's dome inside an apex faces
// the other way).
void place_retreating_domes(std::vector<Vec3>& guess, const std::vector<Vec3>& x0, const std::vector<Triangle>& tris,
                            const Rings& rings, const FrameTargets& ft, const TriangleMesh& own, Vec3 normal) {
  const std::size_t n = x0.size();
  std::vector<std::int32_t> region(n, -1);
  std::int32_t regions = 0;
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (ft.line[seed] >= 0 || region[seed] >= 0) continue;
    const std::int32_t id = regions++;
    std::vector<std::size_t> members{seed};
    region[seed] = id;
    std::vector<std::int32_t> touching;
    bool retreated = false;
    for (std::size_t k = 0; k < members.size(); ++k) {
      retreated = retreated || ft.orphan[members[k]];
      for (std::uint32_t u : rings[members[k]]) {
        if (ft.line[u] >= 0) {
          if (std::find(touching.begin(), touching.end(), ft.line[u]) == touching.end()) touching.push_back(ft.line[u]);
        } else if (region[u] < 0) {
          region[u] = id;
          members.push_back(u);
        }
      }
    }
    if (touching.size() != 1 || !retreated) continue;
    const MatchedLoop& l = ft.loops[static_cast<std::size_t>(touching.front())];
    double side = 0;
    for (std::size_t v : members) side += dot(x0[v], normal) - l.height;
    const Vec3 dir = side >= 0 ? normal : -normal;
    if (map_dome(guess, x0, tris, region, id, ft, static_cast<std::size_t>(touching.front()), own, dir)) continue;
    auto in_region = [&](std::size_t k) {
      return region[tris[k][0]] == id || region[tris[k][1]] == id || region[tris[k][2]] == id;
    };
    int facing = 0;
    double h0 = -1;
    for (int f : {1, -1}) {
      const double h = first_hit(l.c0, dir, x0, tris, f, in_region);
      if (h > 0 && (h0 < 0 || h < h0)) {
        h0 = h;
        facing = f;
      }
    }
    if (!(h0 > 0) || !(l.r0 > 0)) continue;
    const double ht = first_hit(l.ct, dir, own.positions, own.triangles, facing, [](std::size_t) { return true; });
    if (!(ht > 0)) continue;
    const double sr = l.rt / l.r0, sh = ht / h0;
    for (std::size_t v : members) {
      const Vec3 d = x0[v] - l.c0;
      const double h = dot(d, normal);
      guess[v] = l.ct + sr * (d - h * normal) + sh * h * normal;  // ct lies on the slice's plane
    }
  }
}

// Chain vertices onto the closest point of their contour (each from its last segment).
void slide_on_lines(std::vector<Vec3>& x, const FrameTargets& ft, std::vector<std::int32_t>& line_hints) {
  for (std::size_t v = 0; v < x.size(); ++v)
    if (ft.line[v] >= 0) x[v] = closest_on_loop(ft.lines[static_cast<std::size_t>(ft.line[v])], x[v], line_hints[v]);
}

// Frame t: the thin-plate guess, then relaxation rounds, each ending with the chain vertices on their
// contours and the others on the frame's own surface; last, local untangling and the small-angle repair.
std::vector<Vec3> carry_one(const std::vector<Vec3>& guess, const FrameTargets& ft, const Rings& rings,
                            const std::vector<Triangle>& tris, const TriangleMesh& own, const CarryOptions& opt,
                            CarryFrameReport& fr) {
  std::vector<Vec3> x = guess;
  const SurfaceProjector surface(own);
  std::vector<std::int32_t> hints(x.size(), -1), line_hints(x.size(), -1);
  std::vector<double> moved(x.size(), 0.0);
  std::vector<Vec3> normals;
  std::vector<char> on_line(x.size(), 0);
  for (std::size_t v = 0; v < x.size(); ++v) on_line[v] = ft.line[v] >= 0;
  project_on_sheet(x, on_line, rings, tris, surface, hints, opt.sheet_cos, normals, &moved);
  slide_on_lines(x, ft, line_hints);
  std::size_t free = 0;
  for (std::size_t v = 0; v < x.size(); ++v)
    if (!on_line[v]) {
      ++free;
      fr.projection_mean += moved[v];
      fr.projection_max = std::max(fr.projection_max, moved[v]);
    }
  if (free) fr.projection_mean /= static_cast<double>(free);
  for (int r = 0; r < opt.relax_rounds; ++r) {
    relax_tangentially(x, rings, normals, opt.relax_step);
    slide_on_lines(x, ft, line_hints);
    fr.off_sheet = project_on_sheet(x, on_line, rings, tris, surface, hints, opt.sheet_cos, normals);
  }
  // Folds and small angles left where vertices travelled far (a cavity closing above a slice, a contour that
  // shrank): the local untangling and the small-angle repair of the one-frame surface, moves within the
  // surface (chain vertices along their contours).
  const SurfaceSnap snap = [&](std::uint32_t v, Vec3 p) {
    return on_line[v] ? closest_on_loop(ft.lines[static_cast<std::size_t>(ft.line[v])], p, line_hints[v])
                      : surface.walk(p, nullptr, &hints[v]);
  };
  const std::vector<char> none(x.size(), 0);
  fr.crossings = untangle(x, tris, none, snap, opt.untangle_rounds);
  AngleRepairOptions repair;
  repair.target_deg = opt.angle_target_deg;
  fr.angle_repairs = repair_small_angles(x, tris, none, snap, repair);
  return x;
}

}  // namespace

MeshSequence carry_frames(const Sequence& seq, const TriangleMesh& frame0,
                          const std::function<TriangleMesh(std::size_t)>& surface, const CarryOptions& options,
                          CarryReport* report) {
  const std::size_t n = seq.frames.size();
  CarryReport local;
  CarryReport& rep = report ? *report : local;
  rep.frames.assign(n, {});
  const std::vector<Vec3>& x0 = frame0.positions;
  const Rings rings = vertex_rings(x0.size(), frame0.triangles);
  const SparseMatrix q = bilaplacian(rings);

  // 1. Which chains each frame matches (cheap, in order): frames with the same set share a factorisation.
  const std::vector<Chain> chains = find_chains(seq, frame0);
  std::map<int, std::vector<const Chain*>> by_slice;
  for (const Chain& c : chains) by_slice[c.slice].push_back(&c);
  std::vector<FrameTargets> targets(n);
  tbb::parallel_for(std::size_t{1}, std::max<std::size_t>(1, n),
                    [&](std::size_t t) { targets[t] = match_frame(seq, by_slice, x0, t, options); });
  std::map<std::vector<char>, std::size_t> system_of;
  std::vector<std::size_t> system(n, 0);
  for (std::size_t t = 1; t < n; ++t) system[t] = system_of.emplace(targets[t].fixed, system_of.size()).first->second;
  std::vector<ThinPlate> systems(system_of.size());
  std::vector<const std::vector<char>*> masks(system_of.size());
  for (const auto& [mask, k] : system_of) masks[k] = &mask;
  tbb::parallel_for(std::size_t{0}, systems.size(), [&](std::size_t k) { factor(q, *masks[k], systems[k]); });
  rep.factorisations = systems.size();

  // 2. Every frame on its own: guess, own surface, relaxation and projection.
  MeshSequence out;
  out.triangles = frame0.triangles;
  out.positions.assign(n, {});
  out.times_ms.resize(n);
  for (std::size_t t = 0; t < n; ++t) out.times_ms[t] = seq.frames[t].time_ms;
  if (n > 0) out.positions[0] = x0;
  // A frame that fails is reported after all have run: the lowest one, whatever the scheduling.
  std::vector<std::exception_ptr> errors(n);
  tbb::parallel_for(std::size_t{1}, std::max<std::size_t>(1, n), [&](std::size_t t) {
    try {
      const FrameTargets& ft = targets[t];
      CarryFrameReport& fr = rep.frames[t];
      fr.source = 0;
      fr.matched_contours = ft.matched;
      fr.unmatched_chains = ft.unmatched;
      fr.fixed_vertices = static_cast<std::size_t>(std::count(ft.fixed.begin(), ft.fixed.end(), 1));
      const TriangleMesh own = surface(t);
      std::vector<Vec3> guess = thin_plate_guess(q, systems[system[t]], x0, ft);
      place_retreating_domes(guess, x0, frame0.triangles, rings, ft, own, seq.normal);
      out.positions[t] = carry_one(guess, ft, rings, frame0.triangles, own, options, fr);
    } catch (...) {
      errors[t] = std::current_exception();
    }
  });
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  return out;
}

}  // namespace c4d
