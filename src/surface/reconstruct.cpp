// The one-frame surface: Lim et al. 2014 (PLOS ONE 9(4): e93747), "Constructing a 3D model of the
// First Cardiac Frame": tree-based connectivity decides which contours are joined ("we only need to
// form surfaces between contours that have connections"), each connected pair of slices is tiled
// (1→1 bands; 1→n and n→1 through bridges, Meyers et al. 1992), ends get rounded caps, and the
// result is refined and smoothed ("Surface Smoothing and Refinement"). Instead of tiling each band as
// one strip and remeshing (slow), 1→1 bands are tiled directly with interpolated rows of well-shaped
// triangles; only branching bands go through CGAL's isotropic remeshing. Instead of λ|μ|ε smoothing
// and Bézier upsampling, one thin-plate solve (fairing.h) with the contours fixed makes the surface
// smooth across every contour while it interpolates them exactly; then caps and the walls into
// closing ends are filled to the volume their sections imply (capping.h).
#include "contour4d/surface/reconstruct.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <limits>
#include <map>
#include <set>
#include <tuple>
#include <string>

#include "contour4d/connect/similarity.h"
#include "contour4d/core/contour.h"
#include "contour4d/core/errors.h"
#include "contour4d/core/union_find.h"
#include "contour4d/surface/delaunay_tiling.h"
#include "contour4d/surface/fairing.h"
#include "contour4d/surface/refine.h"
#include "contour4d/surface/resample.h"
#include "contour4d/metrics/surface_projector.h"
#include "contour4d/metrics/surface_walk.h"
#include "contour4d/metrics/topology.h"
#include "contour4d/surface/surface_plan.h"
#include "contour4d/surface/tiling.h"
#include "surface_tuning_internal.h"

namespace c4d {
namespace {

// The checks of the surface's own meshes on the way: counts, no self-intersection test.
constexpr TopologyOptions kCountsOnly{.self_intersections = false, .counts_only = true};

// Bridges of a 1→n branching rise this fraction of the gap from the several contours' slice; both sides
// branching (n→m): two bridges meet in the band, each rises less.
constexpr double kBridgeRise = 0.75;
constexpr double kBridgeRiseBoth = 0.35;
// CGAL's size bound, in edges, of the uniform interior of ring caps with walls (their fairing terms
// scale-aware) and of the other caps that are not filled (lone contours and holes, rings without walls;
// their rows scaled by its inverse).
constexpr double kRingCapScale = 2.0;
const double kUniformCapScale = std::sqrt(2.0);
// A hole opens towards the neighbouring slice (join_opening_holes) where at least this share of its outline
// lies outside the material of its ring's partner there...
constexpr double kOpeningShare = 0.25;
// ... and the partner's material covers at most this share of the hole's area.
constexpr double kCoveredShare = 0.25;
// The bridge across an opening rises between these shares of the gap (opening_rise).
constexpr double kOpeningRise[2] = {0.2, 0.8};
// A bridge's cost is its length × (1 + kMisplacedCost × the share of it, over kBridgeSamples points, that
// crosses where the material between the slices ends): bridges follow the material.
constexpr double kMisplacedCost = 4.0;
constexpr int kBridgeSamples = 8;

// One contour of the frame, in canonical form.
struct Node {
  int slice = 0;                     // index into the sorted slices
  int input_index = 0;               // index in the input Slice::contours
  int depth = 0;                     // nesting depth within its slice
  std::vector<Vec2> poly;            // resampled, canonical (CCW for even depth, CW for odd)
  std::vector<std::uint32_t> chain;  // global vertex ids of poly
  bool linked_up = false, linked_down = false;
};

struct SliceInfo {
  const Slice* slice = nullptr;
  Plane plane;
  std::vector<int> nodes;  // canonical order
};

struct Builder {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::uint32_t add(Vec3 p) {
    positions.push_back(p);
    return static_cast<std::uint32_t>(positions.size() - 1);
  }
};

// Centre and principal axis (in the stack's u, v coordinates) of all contour points of a frame,
// weighted by the contour length each point stands for, so that sampling density does not matter.
struct CanonicalFrame {
  Vec2 centre;
  Vec2 axis{1, 0};
};

CanonicalFrame canonical_frame(const Sequence& sub) {
  std::vector<std::pair<Vec2, double>> pts;
  for (const Slice& s : sub.frames[0].slices) {
    const Plane pl = slice_plane(sub, s);
    for (const Contour& c : s.contours) {
      const std::size_t n = c.points.size();
      for (std::size_t k = 0; k < n; ++k) {
        const double w =
            0.5 * (distance(c.points[k], c.points[(k + 1) % n]) + distance(c.points[k], c.points[(k + n - 1) % n]));
        pts.push_back({to_plane(pl, c.points[k]), w});
      }
    }
  }
  CanonicalFrame f;
  double W = 0;
  for (const auto& [p, w] : pts) {
    f.centre = f.centre + w * p;
    W += w;
  }
  if (W <= 0) return f;
  f.centre = (1.0 / W) * f.centre;
  double sxx = 0, sxy = 0, syy = 0;
  for (const auto& [p, w] : pts) {
    const Vec2 d = p - f.centre;
    sxx += w * d.x * d.x;
    sxy += w * d.x * d.y;
    syy += w * d.y * d.y;
  }
  const double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);
  f.axis = {std::cos(angle), std::sin(angle)};
  double third = 0;
  for (const auto& [p, w] : pts) third += w * std::pow(dot(p - f.centre, f.axis), 3);
  if (third < 0) f.axis = -1.0 * f.axis;
  return f;
}

// Rounds to a 2^-30 mm grid (about 1e-9 mm): rounding noise from the input's placement vanishes.
double snap(double x) { return std::ldexp(std::nearbyint(std::ldexp(x, 30)), -30); }
Vec2 snap(Vec2 p) { return {snap(p.x), snap(p.y)}; }

// Contours of one slice that touch or nearly touch (a section through a saddle: two contours meeting
// at one point) are moved apart to `gap`: each point closer than `gap` to another contour moves by
// half the shortfall, away from it (from a shared point: along its own normal, into its region for
// two outer contours or two holes, out of it for a hole against its outer contour). Distinct
// vertices at one position would otherwise be merged into a non-manifold vertex. Returns the number
// of points moved.
std::size_t separate_touching(std::vector<Node>& nodes, const std::vector<int>& slice_nodes, double gap) {
  if (gap <= 0) return 0;
  std::size_t moved = 0;
  for (std::size_t i = 0; i < slice_nodes.size(); ++i)
    for (std::size_t j = i + 1; j < slice_nodes.size(); ++j) {
      Node& a = nodes[static_cast<std::size_t>(slice_nodes[i])];
      Node& b = nodes[static_cast<std::size_t>(slice_nodes[j])];
      auto box = [](const std::vector<Vec2>& poly) {
        std::array<double, 4> r{poly[0].x, poly[0].y, poly[0].x, poly[0].y};
        for (const Vec2& p : poly)
          r = {std::min(r[0], p.x), std::min(r[1], p.y), std::max(r[2], p.x), std::max(r[3], p.y)};
        return r;
      };
      const auto ba = box(a.poly), bb = box(b.poly);
      if (ba[0] > bb[2] + gap || bb[0] > ba[2] + gap || ba[1] > bb[3] + gap || bb[1] > ba[3] + gap) continue;
      // Same parity: both bound material on their left (canonical orientation), so "into the region" is left.
      const double side = (a.depth % 2 == b.depth % 2) ? 1.0 : -1.0;
      auto shifts = [&](const Node& self, const Node& other) {
        std::vector<Vec2> out(self.poly.size(), Vec2{0, 0});
        const std::size_t n = self.poly.size();
        for (std::size_t k = 0; k < n; ++k) {
          const Vec2 p = self.poly[k], q = closest_on_polyline(p, other.poly);
          const double d = norm(p - q);
          if (d >= gap) continue;
          Vec2 dir = d > 1e-9 ? (1.0 / d) * (p - q) : Vec2{0, 0};
          if (d <= 1e-9) {
            const Vec2 t = self.poly[(k + 1) % n] - self.poly[(k + n - 1) % n];
            const double lt = norm(t);
            if (lt > 0) dir = (side / lt) * Vec2{-t.y, t.x};
          }
          out[k] = (0.5 * (gap - d)) * dir;
        }
        return out;
      };
      auto apply = [&](Node& self, const std::vector<Vec2>& by) {
        for (std::size_t k = 0; k < by.size(); ++k)
          if (by[k].x != 0 || by[k].y != 0) {
            self.poly[k] = snap(self.poly[k] + by[k]);
            ++moved;
          }
      };
      const std::vector<Vec2> sa = shifts(a, b), sb = shifts(b, a);  // both from the positions before
      apply(a, sa);
      apply(b, sb);
    }
  return moved;
}

// True where p lies in the material of the contours `region` (even–odd over their polygons).
bool in_material(Vec2 p, const std::vector<const std::vector<Vec2>*>& region) {
  bool inside = false;
  for (const auto* poly : region) inside = inside != point_in_polygon(p, *poly);
  return inside;
}

// The other slice of a branching, for placing its bridges: the material of its contours, and whether the
// contours merged on this slice are a ring and its hole (an opening, join_opening_holes).
struct BridgeSide {
  std::vector<const std::vector<Vec2>*> other_material;
  bool opening = false;
};

// Where a ring opens between two slices, the share of the gap at which its material ends: the ring is
// w = |q − p| wide across the bridge p–q on its slice, and the other slice's material leaves an opening
// about twice the distance from the bridge's middle to it; the width, falling linearly from w to minus
// the opening, reaches zero at w / (w + opening) of the gap.
double opening_rise(Vec2 p, Vec2 q, const BridgeSide& side) {
  const Vec2 mid = 0.5 * (p + q);
  double opening = std::numeric_limits<double>::infinity();
  for (const auto* poly : side.other_material) opening = std::min(opening, 2.0 * polyline_distance(mid, *poly));
  const double w = norm(q - p);
  return std::clamp(w / (w + opening), kOpeningRise[0], kOpeningRise[1]);
}

// Merges the chains of `members` (same slice) into one through bridges lifted by up to `lift` mm
// along the normal (signed). Each bridge joins the pair of points of least length × (1 + kMisplacedCost ×
// the share of the bridge that crosses where the material between the slices ends): outside the other
// slice's material where contours merge, inside it where a ring opens. Without `side`, the closest pair.
// Across an opening `lift` is the whole gap, of which the bridge rises the share opening_rise gives.
// Returns the merged chain.
std::vector<std::uint32_t> merge_with_bridges(const std::vector<int>& members, std::vector<Node>& nodes,
                                              const Plane& plane, double lift, double edge, Builder& b,
                                              const BridgeSide& side = {}) {
  // The share of the segment p–q (samples at its interior) lying where the material ends between the slices.
  auto misplaced = [&](Vec2 p, Vec2 q) {
    if (side.other_material.empty()) return 0.0;
    int wrong = 0;
    for (int k = 0; k < kBridgeSamples; ++k) {
      const double t = (k + 0.5) / kBridgeSamples;
      wrong += in_material(p + t * (q - p), side.other_material) == side.opening ? 1 : 0;
    }
    return static_cast<double>(wrong) / kBridgeSamples;
  };
  std::vector<std::uint32_t> merged = nodes[members[0]].chain;
  std::vector<Vec2> merged_2d = nodes[members[0]].poly;  // 2D position per chain entry
  std::vector<char> is_bridge(merged.size(), 0);
  std::vector<char> done(members.size(), 0);
  done[0] = 1;
  for (std::size_t round = 1; round < members.size(); ++round) {
    double best = std::numeric_limits<double>::infinity(), best_length = best;
    std::size_t bm = 0, bx = 0, by = 0;
    for (std::size_t m = 0; m < members.size(); ++m) {
      if (done[m]) continue;
      const auto& poly = nodes[members[m]].poly;
      for (std::size_t x = 0; x < merged.size(); ++x) {
        if (is_bridge[x]) continue;
        for (std::size_t y = 0; y < poly.size(); ++y) {
          const double d = norm(poly[y] - merged_2d[x]);
          if (d >= best - 1e-12) continue;  // the cost is at least the length
          const double cost = d * (1.0 + kMisplacedCost * misplaced(merged_2d[x], poly[y]));
          if (cost < best - 1e-12) {
            best = cost;
            best_length = d;
            bm = m;
            bx = x;
            by = y;
          }
        }
      }
    }
    done[bm] = 1;
    const Node& other = nodes[members[bm]];
    const Vec2 p = merged_2d[bx], q = other.poly[by];
    const int pieces = std::max(1, static_cast<int>(std::ceil(best_length / edge - 1e-9)));
    const double rise = side.opening ? lift * opening_rise(p, q, side) : lift;
    std::vector<std::uint32_t> bridge;
    std::vector<Vec2> bridge_2d;
    for (int k = 1; k < pieces; ++k) {
      const double t = static_cast<double>(k) / pieces;
      const Vec2 r = p + t * (q - p);
      bridge.push_back(b.add(from_plane(plane, r, rise * std::sin(std::numbers::pi * t))));
      bridge_2d.push_back(r);
    }
    std::vector<Vec2> other_2d = other.poly;
    // Same splice on the 2D shadow and on the bridge flags.
    std::vector<std::uint32_t> idx_a(merged.size()), idx_b(other.chain.size()), idx_br(bridge.size());
    std::iota(idx_a.begin(), idx_a.end(), 0u);
    std::iota(idx_b.begin(), idx_b.end(), static_cast<std::uint32_t>(merged.size()));
    std::iota(idx_br.begin(), idx_br.end(), static_cast<std::uint32_t>(merged.size() + other.chain.size()));
    const auto order = bridge_chains(idx_a, bx, idx_b, by, idx_br);
    std::vector<std::uint32_t> ids = merged;
    ids.insert(ids.end(), other.chain.begin(), other.chain.end());
    ids.insert(ids.end(), bridge.begin(), bridge.end());
    std::vector<Vec2> pos = merged_2d;
    pos.insert(pos.end(), other_2d.begin(), other_2d.end());
    pos.insert(pos.end(), bridge_2d.begin(), bridge_2d.end());
    std::vector<char> flag = is_bridge;
    flag.resize(merged.size() + other.chain.size(), 0);
    flag.resize(ids.size(), 1);
    merged.clear();
    merged_2d.clear();
    is_bridge.clear();
    for (std::uint32_t k : order) {
      merged.push_back(ids[k]);
      merged_2d.push_back(pos[k]);
      is_bridge.push_back(flag[k]);
    }
  }
  return merged;
}

// Contour links between slice s and s + 1: (lower node, upper node).
using PairLinks = std::vector<std::vector<std::pair<int, int>>>;

// A Rounded cap on walls, for the volume fill after fairing: its triangles, frame and target.
struct CapFill {
  std::vector<Triangle> triangles;
  CapFrame frame;
  double target = 0.0;
  int end = -1;  // the end contour under the cap (one contour, no holes)
  std::size_t slice = 0;
  bool top = true;
};

// Area enclosed by a node's contour, negative for holes.
double node_area(const Node& n) { return (n.depth % 2 == 1 ? -1.0 : 1.0) * std::abs(signed_area(n.poly)); }

// The share of the neighbouring slice's area (below when `top`, else above) that continues into node
// n across the walls: each partner's area split among the contours it connects to on n's slice, by
// their areas.
double neighbour_share(const std::vector<Node>& nodes, const PairLinks& pair_links, int n, std::size_t s, bool top) {
  if (top ? s == 0 : s + 1 >= pair_links.size()) return 0.0;
  const auto& pl = pair_links[top ? s - 1 : s];
  double share = 0.0;
  for (auto [lower, upper] : pl) {
    const int mine = top ? upper : lower, other = top ? lower : upper;
    if (mine != n) continue;
    double split = 0.0;
    for (auto [l2, u2] : pl)
      if ((top ? l2 : u2) == other) split += node_area(nodes[top ? u2 : l2]);
    if (split > 0.0) share += node_area(nodes[other]) * node_area(nodes[n]) / split;
  }
  return share;
}

// Near a closing end the faired wall from a large to a small contour is cone-like, thinner than the
// smooth section-area curve through the slices: each cap's wall (one end contour, partners joined to
// nothing else) is widened (never narrowed) to that curve's volume (capping.h, fill_end_band).
void fill_end_bands(TriangleMesh& m, const std::vector<CapFill>& caps, const std::vector<Node>& nodes,
                    const std::vector<SliceInfo>& slices, const PairLinks& pair_links, const std::vector<char>& fixed) {
  auto key = [](std::uint32_t a, std::uint32_t c) {
    return (static_cast<std::uint64_t>(std::min(a, c)) << 32) | std::max(a, c);
  };
  std::vector<std::uint64_t> contour_edges;  // sorted keys
  std::vector<int> vertex_node(m.positions.size(), -1);
  for (std::size_t n = 0; n < nodes.size(); ++n)
    for (std::size_t k = 0; k < nodes[n].chain.size(); ++k) {
      vertex_node[nodes[n].chain[k]] = static_cast<int>(n);
      contour_edges.push_back(key(nodes[n].chain[k], nodes[n].chain[(k + 1) % nodes[n].chain.size()]));
    }
  std::sort(contour_edges.begin(), contour_edges.end());
  auto on_contour = [&](std::uint64_t e) { return std::binary_search(contour_edges.begin(), contour_edges.end(), e); };
  // The triangles of each edge in increasing order: per lower vertex, (upper vertex, triangle) entries
  // filled in triangle order.
  const std::size_t nv = m.positions.size();
  std::vector<std::uint32_t> first(nv + 1, 0);
  for (const Triangle& tr : m.triangles)
    for (int k = 0; k < 3; ++k) ++first[std::min(tr[k], tr[(k + 1) % 3]) + 1];
  for (std::size_t v = 0; v < nv; ++v) first[v + 1] += first[v];
  std::vector<std::array<std::uint32_t, 2>> incident(first[nv]);
  {
    std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      const Triangle& tr = m.triangles[t];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = tr[k], c = tr[(k + 1) % 3];
        incident[fill[std::min(a, c)]++] = {std::max(a, c), static_cast<std::uint32_t>(t)};
      }
    }
  }
  auto edge_triangles = [&](std::uint64_t e, auto&& f) {
    const auto a = static_cast<std::uint32_t>(e >> 32), c = static_cast<std::uint32_t>(e & 0xffffffffu);
    for (std::uint32_t k = first[a]; k < first[a + 1]; ++k)
      if (incident[k][0] == c) f(incident[k][1]);
  };
  const double orientation = signed_volume(m) >= 0.0 ? 1.0 : -1.0;
  auto centroid = [&](const std::vector<int>& ns) {
    double w = 0.0;
    Vec2 c{0.0, 0.0};
    for (int n : ns) {
      const auto& poly = nodes[n].poly;
      for (std::size_t k = 0; k < poly.size(); ++k) {
        const Vec2 p = poly[k], q = poly[(k + 1) % poly.size()];
        const double cr = p.x * q.y - q.x * p.y;
        w += cr;
        c.x += (p.x + q.x) * cr;
        c.y += (p.y + q.y) * cr;
      }
    }
    return w != 0.0 ? Vec2{c.x / (3.0 * w), c.y / (3.0 * w)} : Vec2{0.0, 0.0};
  };
  for (const CapFill& cf : caps) {
    const int end = cf.end;
    const std::size_t s = cf.slice;
    if (cf.top ? s == 0 : s + 1 >= slices.size()) continue;
    const std::size_t ns = cf.top ? s - 1 : s + 1;
    const auto& pl = pair_links[cf.top ? s - 1 : s];
    std::vector<int> partners;
    bool simple = true;
    for (auto [lower, upper] : pl) {
      const int mine = cf.top ? upper : lower, other = cf.top ? lower : upper;
      if (mine == end) partners.push_back(other);
    }
    for (auto [lower, upper] : pl) {
      const int mine = cf.top ? upper : lower, other = cf.top ? lower : upper;
      if (mine != end && std::find(partners.begin(), partners.end(), other) != partners.end()) simple = false;
    }
    for (int p : partners) simple = simple && nodes[p].depth % 2 == 0;
    if (partners.empty() || !simple) continue;
    // The wall: triangles reached from the end contour's edges, not crossing any contour edge.
    std::set<Triangle> cap_set(cf.triangles.begin(), cf.triangles.end());
    std::vector<char> seen(m.triangles.size(), 0);
    std::vector<std::uint32_t> stack;
    const auto& chain = nodes[end].chain;
    for (std::size_t k = 0; k < chain.size(); ++k)
      edge_triangles(key(chain[k], chain[(k + 1) % chain.size()]), [&](std::uint32_t t) {
        if (!seen[t] && !cap_set.count(m.triangles[t])) {
          seen[t] = 1;
          stack.push_back(t);
        }
      });
    EndBand band;
    while (!stack.empty() && simple) {
      const std::uint32_t t = stack.back();
      stack.pop_back();
      const Triangle& tr = m.triangles[t];
      band.triangles.push_back(tr);
      for (int k = 0; k < 3; ++k) {
        const int vn = vertex_node[tr[k]];
        if (vn >= 0 && vn != end && std::find(partners.begin(), partners.end(), vn) == partners.end()) simple = false;
        const std::uint64_t e = key(tr[k], tr[(k + 1) % 3]);
        if (on_contour(e)) continue;
        edge_triangles(e, [&](std::uint32_t u) {
          if (!seen[u]) {
            seen[u] = 1;
            stack.push_back(u);
          }
        });
      }
    }
    if (!simple || band.triangles.empty()) continue;
    for (const Triangle& tr : band.triangles)
      for (std::uint32_t v : tr)
        if (!fixed[v]) band.movable.push_back(v);
    std::sort(band.movable.begin(), band.movable.end());
    band.movable.erase(std::unique(band.movable.begin(), band.movable.end()), band.movable.end());
    band.z_end = slices[s].plane.origin.z;
    band.z_ref = slices[ns].plane.origin.z;
    band.c_end = centroid({end});
    band.c_ref = centroid(partners);
    band.area_end = node_area(nodes[end]);
    double area_ref = 0.0, area_far = 0.0;
    bool far = true;
    for (int p : partners) {
      area_ref += node_area(nodes[p]);
      area_far += neighbour_share(nodes, pair_links, p, ns, cf.top);
      far = far && (cf.top ? nodes[p].linked_down : nodes[p].linked_up);
    }
    const double h = std::abs(band.z_end - band.z_ref);
    const double m1 = (band.area_end - area_ref) / h;
    double m0 = m1;
    if (far && (cf.top ? ns > 0 : ns + 1 < slices.size())) {
      const std::size_t fs = cf.top ? ns - 1 : ns + 1;
      m0 = (band.area_end - area_far) / std::abs(band.z_end - slices[fs].plane.origin.z);
    }
    fill_end_band(m.positions, band, hermite_band_volume(area_ref, band.area_end, m0, m1, h), orientation);
  }
}

// triangulate_cap, its failures named with the frame and slice.
CapMesh cap_of_slice(const std::vector<std::vector<Vec2>>& loops, CapStyle style, const CapOptions& options,
                     Location loc, int slice) {
  try {
    return triangulate_cap(loops, style, options);
  } catch (const Error& e) {
    loc.slice = slice;
    throw InvalidInput(e.code(), loc, e.what());
  }
}

// The state of one frame's construction, filled step by step by reconstruct_frame's steps below.
struct FrameWork {
  explicit FrameWork(const detail::SurfaceParams& options) : opt(options) {}
  const detail::SurfaceParams& opt;
  Location loc;  // the file and frame, for messages
  SurfaceReport rep;
  Sequence sub;                                  // the chosen structure's contours as a one-frame sequence
  Frame ff;                                      // those contours, slices by increasing offset
  std::vector<std::vector<int>> original_index;  // per sorted slice: filtered index -> input index
  std::vector<Connection> links;                 // the connectivity tree's links between slices
  CanonicalFrame frame2d;                        // centre and principal axis (rigid invariance)
  Builder b;                                     // vertices and triangles made so far
  Plane world;                                   // canonical frame of the first slice in world space
  std::vector<Node> nodes;                       // one per resampled contour
  std::vector<SliceInfo> slices;
  std::vector<std::vector<int>> node_of;  // per slice: filtered index -> node
  std::uint32_t contour_vertices = 0;     // vertices [0, this) are contour vertices
  PairLinks pair_links;                   // per slice pair: linked node pairs
  std::vector<Triangle> to_remesh;        // band triangles left for remeshing (branchings)
  RemeshEngine engine = RemeshEngine::Cgal;
  std::vector<char> fixed;              // per vertex: kept in place by fairing and remeshing
  std::vector<char> keep_shape;         // per vertex: a dome vertex that keeps its shape
  std::vector<double> row_scale;        // per vertex: the fairing row's scale (coarse caps)
  std::vector<char> scale_aware;        // per vertex: its fairing term is scale-aware (ring caps)
  std::vector<CapFill> fills;           // the Rounded caps to fill towards the sections' trend
  SurfacePlan* record = nullptr;        // filled with this frame's decisions (plan_surface)
  const SurfacePlan* replay = nullptr;  // the decisions to follow instead (reconstruct_frame_on_plan)
  std::size_t next_band = 0, next_cap = 0;
  bool delaunay_branchings = false;  // branching groups tiled the paper's way (the retry of a failed frame)
};

// A frame whose contours do not fit the plan it is built on (another topology).
struct PlanMismatch {
  std::string why;
};

// A cap in the plan: its interior points as mean-value coordinates over its loops, heights as shares of
// the cap's height `height`.
PlanCap plan_cap(const CapMesh& cap, const std::vector<std::vector<Vec2>>& loops, double height) {
  PlanCap pc;
  for (const auto& l : loops) pc.loop_points += l.size();
  for (std::size_t k = pc.loop_points; k < cap.points.size(); ++k) {
    pc.weights.push_back(mean_value_weights(cap.points[k], loops));
    pc.height.push_back(height > 0 ? cap.height[k] / height : 0.0);
  }
  pc.triangles = cap.triangles;
  return pc;
}

// The plan's next cap on this frame's loops.
CapMesh cap_on_plan(FrameWork& fw, const std::vector<std::vector<Vec2>>& loops, double height) {
  if (fw.next_cap >= fw.replay->caps.size()) throw PlanMismatch{"more caps than the plan's frame"};
  const PlanCap& pc = fw.replay->caps[fw.next_cap++];
  CapMesh cap;
  for (const auto& l : loops) cap.points.insert(cap.points.end(), l.begin(), l.end());
  if (cap.points.size() != pc.loop_points) throw PlanMismatch{"a cap's loops differ from the plan's frame"};
  cap.height.assign(cap.points.size(), 0.0);
  for (std::size_t k = 0; k < pc.weights.size(); ++k) {
    Vec2 p;
    for (std::size_t i = 0; i < pc.loop_points; ++i) p = p + pc.weights[k][i] * cap.points[i];
    cap.points.push_back(p);
    cap.height.push_back(pc.height[k] * height);
  }
  cap.triangles = pc.triangles;
  return cap;
}

// The plan's matching of one slice's contours: for each plan node of slice s (in order), the index of the
// frame's contour (same nesting depth, nearest centroids first).
std::vector<int> match_to_plan(const SurfacePlan& plan, int s, const std::vector<std::vector<Vec2>>& canon,
                               const std::vector<int>& depth) {
  std::vector<int> plan_nodes;
  for (std::size_t k = 0; k < plan.nodes.size(); ++k)
    if (plan.nodes[k].slice == s) plan_nodes.push_back(static_cast<int>(k));
  if (plan_nodes.size() != canon.size())
    throw PlanMismatch{fmt::format("slice {}: {} contours, the plan's frame has {}", plan.slice_ids[s], canon.size(),
                                   plan_nodes.size())};
  std::vector<std::tuple<double, int, int>> pairs;  // distance, plan position, contour
  for (std::size_t a = 0; a < plan_nodes.size(); ++a)
    for (std::size_t c = 0; c < canon.size(); ++c) {
      const PlanNode& pn = plan.nodes[static_cast<std::size_t>(plan_nodes[a])];
      if (pn.depth != depth[c]) continue;
      pairs.emplace_back(norm(mean_point(canon[c]) - pn.centroid), static_cast<int>(a), static_cast<int>(c));
    }
  std::sort(pairs.begin(), pairs.end());
  std::vector<int> out(plan_nodes.size(), -1);
  std::vector<char> used(canon.size(), 0);
  for (const auto& [d, a, c] : pairs)
    if (out[static_cast<std::size_t>(a)] < 0 && !used[static_cast<std::size_t>(c)]) {
      out[static_cast<std::size_t>(a)] = c;
      used[static_cast<std::size_t>(c)] = 1;
    }
  for (int c : out)
    if (c < 0)
      throw PlanMismatch{
          fmt::format("slice {}: the contours' nesting differs from the plan's frame", plan.slice_ids[s])};
  return out;
}

// Step 1: the structure to build (SurfaceOptions::label, or the only one present).
std::string choose_label(const Frame& f, const detail::SurfaceParams& opt, const Location& loc) {
  std::set<std::string> present;
  for (const Slice& s : f.slices)
    for (const Contour& c : s.contours) present.insert(c.label);
  std::string label = opt.label;
  if (label.empty()) {
    if (present.size() > 1) {
      std::string list;
      for (const auto& l : present) list += (list.empty() ? "" : ", ") + (l.empty() ? std::string("(none)") : l);
      throw InvalidInput(ErrorCode::UnknownLabel, loc, "frame holds several structures: " + list,
                         "choose one with --label");
    }
    if (!present.empty()) label = *present.begin();
  } else if (!present.count(label)) {
    throw InvalidInput(ErrorCode::UnknownLabel, loc, "no contour labelled '" + label + "' in this frame",
                       "check the labels with `contour4d info`");
  }

  return label;
}

// Step 2: the structure's contours by slice offset, the connectivity tree's links and the canonical frame.
void filter_frame(FrameWork& fw, const Sequence& seq, const Frame& f, const std::string& label) {
  const detail::SurfaceParams& opt = fw.opt;
  auto& loc = fw.loc;
  auto& sub = fw.sub;
  auto& ff = fw.ff;
  auto& original_index = fw.original_index;
  sub.normal = seq.normal;
  sub.u = seq.u;
  sub.v = seq.v;
  sub.source = seq.source;
  std::vector<const Slice*> sorted;
  for (const Slice& s : f.slices) sorted.push_back(&s);
  std::stable_sort(sorted.begin(), sorted.end(), [](const Slice* a, const Slice* b) { return a->offset < b->offset; });
  for (const Slice* s : sorted) {
    Slice fs;
    fs.id = s->id;
    fs.offset = s->offset;
    original_index.emplace_back();
    for (std::size_t c = 0; c < s->contours.size(); ++c)
      if (s->contours[c].label == label && s->contours[c].points.size() >= 3) {
        fs.contours.push_back(s->contours[c]);
        original_index.back().push_back(static_cast<int>(c));
      }
    if (fs.contours.empty())
      original_index.pop_back();
    else
      ff.slices.push_back(std::move(fs));
  }
  if (ff.slices.empty())
    throw InvalidInput(ErrorCode::EmptyFrame, loc, "frame has no contour to build a surface from",
                       "check the input holds closed contours for this frame and label");
  sub.frames.push_back(ff);
  ConnectivityOptions copt;
  copt.threshold = opt.threshold;
  fw.links = intra_frame_connections(sub, 0, copt);

  fw.frame2d = canonical_frame(sub);
  if (fw.replay) {  // the plan's in-plane frame: the same local coordinates in every frame
    fw.frame2d.centre = fw.replay->centre;
    fw.frame2d.axis = fw.replay->axis;
    std::vector<int> ids;
    for (const Slice& sl : ff.slices) ids.push_back(sl.id);
    if (ids != fw.replay->slice_ids) throw PlanMismatch{"the structure's slices differ from the plan's frame"};
  }
  if (fw.record) {
    fw.record->centre = fw.frame2d.centre;
    fw.record->axis = fw.frame2d.axis;
    for (const Slice& sl : ff.slices) fw.record->slice_ids.push_back(sl.id);
  }
}

// Step 3: canonical, resampled contours and their vertices, in a local frame.
void canonical_contours(FrameWork& fw) {
  const detail::SurfaceParams& opt = fw.opt;
  auto& rep = fw.rep;
  auto& sub = fw.sub;
  auto& ff = fw.ff;
  auto& original_index = fw.original_index;
  auto& frame2d = fw.frame2d;
  auto& b = fw.b;
  auto& world = fw.world;
  auto& nodes = fw.nodes;
  auto& slices = fw.slices;
  auto& node_of = fw.node_of;
  slices.resize(ff.slices.size());
  node_of.resize(ff.slices.size());  // filtered index -> node
  ResampleOptions ropt;
  ropt.edge = opt.edge;
  ropt.corner_angle_deg = opt.corner_angle_deg;
  ropt.tolerance = opt.contour_tolerance;
  for (std::size_t s = 0; s < ff.slices.size(); ++s) {
    SliceInfo& si = slices[s];
    si.slice = &ff.slices[s];
    si.plane = slice_plane(sub, ff.slices[s]);
    // Canonical in-plane frame (rigid invariance): origin on the frame's centroid axis, u along its
    // principal axis.
    si.plane.origin = si.plane.origin + frame2d.centre.x * sub.u + frame2d.centre.y * sub.v;
    si.plane.u = frame2d.axis.x * sub.u + frame2d.axis.y * sub.v;
    si.plane.v = cross(si.plane.normal, si.plane.u);
    if (s == 0) world = si.plane;
    std::vector<std::vector<Vec2>> raw;
    for (const Contour& c : ff.slices[s].contours) {
      raw.emplace_back();
      for (const Vec3& p : c.points) raw.back().push_back(snap(to_plane(si.plane, p)));
    }
    // The work is done in a local frame (x, y in the canonical plane axes, z above the first slice)
    // with snapped coordinates, so rigid motions of the input give bit-identical work.
    si.plane = Plane{{0, 0, snap(ff.slices[s].offset - ff.slices[0].offset)}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<int> depth = nesting_depths(raw);
    std::vector<int> order(raw.size());
    std::iota(order.begin(), order.end(), 0);
    std::vector<double> area(raw.size());
    for (std::size_t c = 0; c < raw.size(); ++c) area[c] = std::abs(signed_area(raw[c]));
    std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return area[x] > area[y]; });
    node_of[s].assign(raw.size(), -1);
    std::vector<std::vector<Vec2>> canon;
    for (std::size_t c = 0; c < raw.size(); ++c) canon.push_back(canonical_polygon(raw[c], depth[c] % 2 == 0));
    if (fw.replay) order = match_to_plan(*fw.replay, static_cast<int>(s), canon, depth);  // the plan's order
    for (std::size_t o = 0; o < order.size(); ++o) {
      const int c = order[o];
      Node n;
      n.slice = static_cast<int>(s);
      n.input_index = original_index[s][c];
      n.depth = depth[c];
      if (fw.replay)
        n.poly = aligned_samples(canon[c], fw.replay->nodes[nodes.size()].reference);
      else
        n.poly = resample_closed(canon[c], ropt);
      for (Vec2& q : n.poly) q = snap(q);
      if (fw.record && n.poly.size() >= 3) {
        PlanNode pn;
        pn.slice = static_cast<int>(s);
        pn.depth = n.depth;
        pn.centroid = mean_point(canon[c]);
        pn.reference = resample_count(canon[c], n.poly.size());
        fw.record->nodes.push_back(std::move(pn));
      }
      if (n.poly.size() < 3) {
        if (fw.replay) throw PlanMismatch{fmt::format("slice {}: a contour too small to sample", si.slice->id)};
        rep.warnings.push_back("slice " + std::to_string(si.slice->id) + " contour " + std::to_string(n.input_index) +
                               ": fewer than 3 distinct points, skipped");
        continue;
      }
      node_of[s][c] = static_cast<int>(nodes.size());
      si.nodes.push_back(static_cast<int>(nodes.size()));
      nodes.push_back(std::move(n));
    }
    if (const std::size_t moved = separate_touching(nodes, si.nodes, opt.min_contour_gap); moved > 0)
      rep.warnings.push_back(
          fmt::format("slice {}: contours touch or come closer than {} mm; {} points moved apart "
                      "by at most half that",
                      si.slice->id, opt.min_contour_gap, moved));
    for (int id : si.nodes)
      for (const Vec2& p : nodes[static_cast<std::size_t>(id)].poly)
        nodes[static_cast<std::size_t>(id)].chain.push_back(b.add(from_plane(si.plane, p)));
  }
  rep.contours = static_cast<int>(nodes.size());
  fw.contour_vertices = static_cast<std::uint32_t>(b.positions.size());
}

// The holes of node n's slice directly inside n (depth one more), as polygons: with n, its material.
std::vector<const std::vector<Vec2>*> material_of(const FrameWork& fw, int n) {
  const Node& nd = fw.nodes[n];
  std::vector<const std::vector<Vec2>*> region{&nd.poly};
  for (int h : fw.slices[nd.slice].nodes) {
    const Node& hd = fw.nodes[h];
    if (hd.depth == nd.depth + 1 && point_in_polygon(hd.poly[0], nd.poly)) region.push_back(&hd.poly);
  }
  return region;
}

// The share of the area inside `poly` that lies in `material`, sampled on a 32 × 32 grid over its bounds.
double covered_share(const std::vector<Vec2>& poly, const std::vector<const std::vector<Vec2>*>& material) {
  Vec2 lo = poly[0], hi = poly[0];
  for (const Vec2& p : poly) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  constexpr int kGrid = 32;
  int inside = 0, covered = 0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const Vec2 p{lo.x + (hi.x - lo.x) * (i + 0.5) / kGrid, lo.y + (hi.y - lo.y) * (j + 0.5) / kGrid};
      if (!point_in_polygon(p, poly)) continue;
      ++inside;
      covered += in_material(p, material) ? 1 : 0;
    }
  return inside > 0 ? static_cast<double>(covered) / inside : 0.0;
}

// Step 4 (end): holes that open between slices. The tree links contours of equal parity only, so a hole
// with no partner towards a neighbouring slice would be capped there. Where its ring opens between
// the slices (the ring's only partner there is one contour whose material leaves a share of the
// hole's outline outside: a C-shaped section under a ring, as a tilted torus gives), the hole is
// linked to that contour instead: the ring, its hole and the contour are then one group of the walls
// (tile_walls: the projected symmetric difference, or a bridge across the opening), which gives the
// genus the contours imply. A hole over material keeps its cap, a dome into the material.
void join_opening_holes(FrameWork& fw) {
  auto& nodes = fw.nodes;
  auto& slices = fw.slices;
  auto& pair_links = fw.pair_links;
  for (std::size_t s = 0; s < slices.size(); ++s)
    for (int h : slices[s].nodes) {
      if (nodes[h].depth % 2 == 0) continue;
      int ring = -1;  // the contour around the hole
      for (int o : slices[s].nodes)
        if (nodes[o].depth == nodes[h].depth - 1 && point_in_polygon(nodes[h].poly[0], nodes[o].poly)) ring = o;
      if (ring < 0) continue;
      for (bool up : {false, true}) {
        if ((up ? nodes[h].linked_up : nodes[h].linked_down) || (up ? s + 1 >= slices.size() : s == 0)) continue;
        auto& links = pair_links[up ? s : s - 1];
        // (node on slice s, node across) per link of the pair.
        auto across = [&](std::pair<int, int> l) { return up ? l : std::make_pair(l.second, l.first); };
        std::vector<int> partners;
        for (auto l : links)
          if (across(l).first == ring) partners.push_back(across(l).second);
        if (partners.size() != 1) continue;
        const int c = partners[0];
        bool only_ring = true;  // c joins nothing on slice s but the ring and its holes
        for (auto l : links) {
          const auto [mine, other] = across(l);
          only_ring = only_ring && (other != c || mine == ring || nodes[mine].depth == nodes[h].depth);
        }
        if (!only_ring) continue;
        // The hole opens where its outline leaves the partner's material, which lies over the ring (a C-shaped
        // section), not where the partner covers the hole (a wall closing over its cavity, as at an apex).
        const auto material = material_of(fw, c);
        std::size_t outside = 0;
        for (const Vec2& p : nodes[h].poly) outside += in_material(p, material) ? 0 : 1;
        if (static_cast<double>(outside) < kOpeningShare * static_cast<double>(nodes[h].poly.size()) ||
            covered_share(nodes[h].poly, material) > kCoveredShare)
          continue;
        links.push_back(up ? std::make_pair(h, c) : std::make_pair(c, h));
        (up ? nodes[h].linked_up : nodes[h].linked_down) = true;
        ++fw.rep.opening_holes;
      }
    }
}

// Step 4: the links as node pairs, per slice pair (and in the report).
void link_nodes(FrameWork& fw, int frame) {
  auto& rep = fw.rep;
  auto& ff = fw.ff;
  auto& original_index = fw.original_index;
  auto& links = fw.links;
  auto& nodes = fw.nodes;
  auto& node_of = fw.node_of;
  auto& pair_links = fw.pair_links;
  auto slice_index = [&](int id) {
    for (std::size_t s = 0; s < ff.slices.size(); ++s)
      if (ff.slices[s].id == id) return static_cast<int>(s);
    return -1;
  };
  pair_links.resize(ff.slices.size());
  for (const Connection& c : links) {
    const int sa = slice_index(c.slice_a), sb = slice_index(c.slice_b);
    const int na = node_of[sa][c.contour_a], nb = node_of[sb][c.contour_b];
    Connection out = c;
    out.frame_a = out.frame_b = frame;
    out.contour_a = original_index[sa][c.contour_a];
    out.contour_b = original_index[sb][c.contour_b];
    rep.connections.push_back(out);
    if (na < 0 || nb < 0) continue;
    const int lo = std::min(sa, sb);
    pair_links[lo].push_back(sa < sb ? std::make_pair(na, nb) : std::make_pair(nb, na));
    nodes[sa < sb ? na : nb].linked_up = true;
    nodes[sa < sb ? nb : na].linked_down = true;
  }
  join_opening_holes(fw);
  if (fw.replay) {  // the same links as the plan's frame, in its order
    auto sorted = [](PairLinks p) {
      for (auto& v : p) std::sort(v.begin(), v.end());
      return p;
    };
    if (sorted(pair_links) != sorted(fw.replay->links))
      throw PlanMismatch{"the connectivity between slices differs from the plan's frame"};
    pair_links = fw.replay->links;
  }
  if (fw.record) fw.record->links = pair_links;
}

// Step 5a: the paper's tiling of one linked group of a slice pair: the constrained Delaunay triangulation of
// the projected symmetric difference with chordal-axis lifting points. False (with a warning) where it fails;
// the band tiling is used there.
bool tile_delaunay(FrameWork& fw, std::size_t s, const std::vector<int>& lower, const std::vector<int>& upper,
                   double gap, std::vector<Triangle>& dest) {
  auto& rep = fw.rep;
  auto& ff = fw.ff;
  auto& b = fw.b;
  auto& nodes = fw.nodes;
  auto& slices = fw.slices;
  bool tiled = false;
  // Both slices' contours projected on the lower plane; ids lists their vertices in the
  // tiling's order (lower polygons, then upper, then the new points).
  std::vector<std::uint32_t> ids;
  auto project = [&](const std::vector<int>& side) {
    std::vector<std::vector<Vec2>> polys;
    for (int n : side) {
      polys.emplace_back();
      for (std::uint32_t v : nodes[n].chain) {
        polys.back().push_back(to_plane(slices[s].plane, b.positions[v]));
        ids.push_back(v);
      }
    }
    return polys;
  };
  const auto lp = project(lower);
  const auto up = project(upper);
  std::string problem;
  try {
    const DelaunayTiling dt = tile_slices_delaunay(lp, up, gap);
    if (dt.flat_triangles > 0) problem = std::to_string(dt.flat_triangles) + " flat triangles left";
    for (const std::string& w : dt.warnings)
      if (w.find("manifold") != std::string::npos) problem = w;
    if (problem.empty()) {
      for (const Vec3& p : dt.points) ids.push_back(b.add(from_plane(slices[s].plane, {p.x, p.y}, p.z)));
      // The tiling tells inside from outside by nesting parity within the pair; when the
      // outermost contours of this pair are holes (hole↔hole links), the solid is outside them.
      int shallowest = std::numeric_limits<int>::max();
      for (int n : lower) shallowest = std::min(shallowest, nodes[n].depth);
      for (int n : upper) shallowest = std::min(shallowest, nodes[n].depth);
      const bool flip = shallowest % 2 == 1;
      for (const Triangle& t : dt.triangles)
        dest.push_back(flip ? Triangle{ids[t[0]], ids[t[2]], ids[t[1]]} : Triangle{ids[t[0]], ids[t[1]], ids[t[2]]});
      tiled = true;
    }
  } catch (const Error& e) {
    problem = e.what();
  }
  if (!tiled)
    rep.warnings.push_back("slices " + std::to_string(ff.slices[s].id) + "-" + std::to_string(ff.slices[s + 1].id) +
                           ": Delaunay tiling not possible (" + problem + "); band tiling used");
  return tiled;
}

// Step 5b: at a 1→n or n→1 branching, each vertex of the single contour may only be joined to the contour of
// the other side it is nearest to (in the plane) or to a bridge, so the band cannot fold across a bridge: the
// group of every vertex of the lower chain `lc` and the upper chain `uc` (-1: a bridge).
void branch_groups(const std::vector<Node>& nodes, const std::vector<int>& lower, const std::vector<int>& upper,
                   const std::vector<std::uint32_t>& lc, const std::vector<std::uint32_t>& uc, std::vector<int>& lg,
                   std::vector<int>& ug) {
  const std::vector<int>& many = lower.size() > 1 ? lower : upper;
  const int single = lower.size() > 1 ? upper[0] : lower[0];
  const auto& merged = lower.size() > 1 ? lc : uc;
  std::map<std::uint32_t, int> member;
  for (std::size_t k = 0; k < many.size(); ++k)
    for (std::uint32_t v : nodes[many[k]].chain) member[v] = static_cast<int>(k);
  std::vector<int> mg, sg;
  for (std::uint32_t v : merged) {
    const auto it = member.find(v);
    mg.push_back(it == member.end() ? -1 : it->second);
  }
  for (const Vec2& p : nodes[single].poly) {
    double best = std::numeric_limits<double>::infinity();
    int g = -1;
    for (std::size_t k = 0; k < many.size(); ++k) {
      const double d = polyline_distance(p, nodes[many[k]].poly);
      if (d < best) {
        best = d;
        g = static_cast<int>(k);
      }
    }
    sg.push_back(g);
  }
  lg = lower.size() > 1 ? mg : sg;
  ug = lower.size() > 1 ? sg : mg;
}

// True where `members` (one slice of a group) mix a ring and its hole: an opening hole (join_opening_holes).
bool mixes_parity(const FrameWork& fw, const std::vector<int>& members) {
  for (int m : members)
    if (fw.nodes[m].depth % 2 != fw.nodes[members[0]].depth % 2) return true;
  return false;
}

// The other side of a branching for merge_with_bridges: its material, and whether `members` are an opening.
BridgeSide bridge_side(const FrameWork& fw, const std::vector<int>& members, const std::vector<int>& other) {
  BridgeSide side;
  side.opening = mixes_parity(fw, members);
  for (int o : other)
    for (const auto* poly : material_of(fw, o))  // each polygon once: `other` may hold a ring and its hole
      if (std::find(side.other_material.begin(), side.other_material.end(), poly) == side.other_material.end())
        side.other_material.push_back(poly);
  return side;
}

// Step 5: the walls between connected contours: rows, bands, bridges at branchings, or the paper's
// Delaunay tiling.
void tile_walls(FrameWork& fw) {
  const detail::SurfaceParams& opt = fw.opt;
  auto& rep = fw.rep;
  auto& ff = fw.ff;
  auto& b = fw.b;
  auto& nodes = fw.nodes;
  auto& slices = fw.slices;
  auto& pair_links = fw.pair_links;
  auto& to_remesh = fw.to_remesh;
  fw.engine = opt.rows ? opt.rows_remesher : opt.remesher;
  for (std::size_t s = 0; s + 1 < slices.size(); ++s) {
    if (pair_links[s].empty()) continue;
    // The linked contours of the slice pair in groups (connected through links), each tiled as one band.
    UnionFind groups(nodes.size());
    for (auto [x, y] : pair_links[s]) groups.unite(static_cast<std::size_t>(x), static_cast<std::size_t>(y));
    std::set<std::size_t> roots;
    for (auto [x, y] : pair_links[s]) roots.insert(groups.find(static_cast<std::size_t>(x)));
    const double gap = ff.slices[s + 1].offset - ff.slices[s].offset;
    for (std::size_t r : roots) {
      std::vector<int> lower, upper;
      for (int n : slices[s].nodes)
        if (nodes[n].linked_up && groups.find(static_cast<std::size_t>(n)) == r) lower.push_back(n);
      for (int n : slices[s + 1].nodes)
        if (nodes[n].linked_down && groups.find(static_cast<std::size_t>(n)) == r) upper.push_back(n);
      if (lower.empty() || upper.empty()) continue;
      const bool both = lower.size() > 1 && upper.size() > 1;
      if (lower.size() > 1 || upper.size() > 1) ++rep.branchings;
      if (both)
        rep.warnings.push_back("slices " + std::to_string(ff.slices[s].id) + "-" + std::to_string(ff.slices[s + 1].id) +
                               ": " + std::to_string(lower.size()) + "→" + std::to_string(upper.size()) +
                               " branching joined through bridges on both slices; check the surface there");
      // The paper's tiling: CDT of the projected symmetric difference with CAT lifting points.
      auto& dest = opt.remesh ? to_remesh : b.triangles;
      const bool opening = mixes_parity(fw, lower) || mixes_parity(fw, upper);
      const bool tiled = (opt.tiling == Tiling::Delaunay || opening || fw.delaunay_branchings) &&
                         !(opt.rows && lower.size() == 1 && upper.size() == 1) &&
                         tile_delaunay(fw, s, lower, upper, gap, dest);
      if (tiled) continue;
      // Bridge height above the slice of the several contours: the saddle where they join lies near
      // the single contour's slice (kBridgeRise of the gap puts the faired saddle closer to analytic
      // saddles than half the gap does; docs/algorithms/one_frame_surface.md).
      const double rise = (both ? kBridgeRiseBoth : kBridgeRise) * gap;
      auto merged = [&](const std::vector<int>& side, const std::vector<int>& other, const Plane& plane, double sign) {
        if (side.size() == 1) return nodes[side[0]].chain;
        const BridgeSide bs = bridge_side(fw, side, other);
        return merge_with_bridges(side, nodes, plane, sign * (bs.opening ? gap : rise), opt.edge, b, bs);
      };
      const auto lc = merged(lower, upper, slices[s].plane, 1.0);
      const auto uc = merged(upper, lower, slices[s + 1].plane, -1.0);
      if (opt.rows && lower.size() == 1 && upper.size() == 1) {
        // Rows between the two contours, tiled pairwise: well-shaped triangles without remeshing.
        const double spacing = opt.row_spacing > 0 ? opt.row_spacing : opt.edge;
        RowPlan row_plan;
        if (fw.replay) {
          if (fw.next_band >= fw.replay->bands.size()) throw PlanMismatch{"more bands than the plan's frame"};
          row_plan = fw.replay->bands[fw.next_band++];
        } else {
          row_plan = plan_rows(lc, uc, b.positions, spacing);
        }
        if (fw.record) fw.record->bands.push_back(row_plan);
        const auto rows = rows_on_plan(row_plan, lc, uc, b.positions);
        if (!rows.empty()) {
          std::vector<std::uint32_t> prev = lc;
          for (std::size_t row = 0; row <= rows.size(); ++row) {
            std::vector<std::uint32_t> next;
            if (row < rows.size())
              for (const Vec3& p : rows[row]) next.push_back(b.add(p));
            else
              next = uc;
            if (!fw.replay) {  // a replay takes the plan's triangles
              const auto tris = tile_chains(prev, next, b.positions);
              b.triangles.insert(b.triangles.end(), tris.begin(), tris.end());
            }
            prev = std::move(next);
          }
          continue;
        }
      }
      std::vector<int> lg, ug;
      if (!both && (lower.size() > 1 || upper.size() > 1)) branch_groups(nodes, lower, upper, lc, uc, lg, ug);
      const auto tris = tile_chains(lc, uc, b.positions, lg, ug);
      dest.insert(dest.end(), tris.begin(), tris.end());
    }
  }
}

// Step 6: bands without rows (branchings) remeshed on their own; their borders are contours, which
// stay fixed and unsplit, so the caps and the neighbouring bands still meet them edge to edge.
void remesh_branch_bands(FrameWork& fw) {
  const detail::SurfaceParams& opt = fw.opt;
  auto& b = fw.b;
  auto& nodes = fw.nodes;
  auto& contour_vertices = fw.contour_vertices;
  auto& to_remesh = fw.to_remesh;
  auto& engine = fw.engine;
  if (!to_remesh.empty()) {
    TriangleMesh part;
    std::map<std::uint32_t, std::uint32_t> local;
    std::vector<std::uint32_t> global;
    for (const Triangle& t : to_remesh) {
      Triangle lt{};
      for (int k = 0; k < 3; ++k) {
        const auto [it, fresh] = local.emplace(t[k], static_cast<std::uint32_t>(global.size()));
        if (fresh) {
          global.push_back(t[k]);
          part.positions.push_back(b.positions[t[k]]);
        }
        lt[k] = it->second;
      }
      part.triangles.push_back(lt);
    }
    std::vector<char> part_fixed(global.size(), 0);
    std::map<std::tuple<double, double, double>, std::uint32_t> fixed_at;
    for (std::size_t k = 0; k < global.size(); ++k)
      if (global[k] < contour_vertices) {
        part_fixed[k] = 1;
        fixed_at[{part.positions[k].x, part.positions[k].y, part.positions[k].z}] = global[k];
      }
    std::vector<std::array<std::uint32_t, 2>> constrained;
    for (const Node& n : nodes)
      for (std::size_t k = 0; k < n.chain.size(); ++k) {
        const auto a = local.find(n.chain[k]), c = local.find(n.chain[(k + 1) % n.chain.size()]);
        if (a != local.end() && c != local.end())
          constrained.push_back({std::min(a->second, c->second), std::max(a->second, c->second)});
      }
    const TopologyReport pc = check_topology(part, kCountsOnly);
    if (pc.nonmanifold_edges == 0 && pc.nonmanifold_vertices == 0 && pc.misoriented_edges == 0) {
      RemeshOptions mo;
      mo.edge = opt.edge;
      mo.iterations = engine == RemeshEngine::Fast ? opt.fast_remesh_iterations : opt.remesh_iterations;
      mo.engine = engine;
      mo.split_constraints = false;
      remesh_isotropic(part, constrained, part_fixed, mo);
    }
    std::vector<std::uint32_t> to_global(part.positions.size());
    for (std::size_t k = 0; k < part.positions.size(); ++k) {
      const Vec3 p = part.positions[k];
      const auto it = fixed_at.find({p.x, p.y, p.z});
      to_global[k] = it != fixed_at.end() ? it->second : b.add(p);
    }
    for (const Triangle& t : part.triangles) b.triangles.push_back({to_global[t[0]], to_global[t[1]], to_global[t[2]]});
  }
}

// Step 7: caps on contours without a partner above (top) or below (bottom).
void add_caps(FrameWork& fw) {
  const detail::SurfaceParams& opt = fw.opt;
  auto& loc = fw.loc;
  auto& rep = fw.rep;
  auto& ff = fw.ff;
  auto& b = fw.b;
  auto& nodes = fw.nodes;
  auto& slices = fw.slices;
  auto& contour_vertices = fw.contour_vertices;
  auto& pair_links = fw.pair_links;
  auto& fixed = fw.fixed;
  auto& keep_shape = fw.keep_shape;
  auto& row_scale = fw.row_scale;
  auto& scale_aware = fw.scale_aware;
  auto& fills = fw.fills;
  auto spacing = [&](std::size_t s, bool top) {
    if (top && s + 1 < ff.slices.size()) return ff.slices[s + 1].offset - ff.slices[s].offset;
    if (!top && s > 0) return ff.slices[s].offset - ff.slices[s - 1].offset;
    if (s + 1 < ff.slices.size()) return ff.slices[s + 1].offset - ff.slices[s].offset;
    if (s > 0) return ff.slices[s].offset - ff.slices[s - 1].offset;
    return std::numeric_limits<double>::infinity();  // single slice: the dome is limited by the region's width
  };
  fixed.assign(b.positions.size(), 0);
  std::fill(fixed.begin(), fixed.begin() + contour_vertices, 1);
  for (std::size_t s = 0; s < slices.size(); ++s)
    for (bool top : {false, true}) {
      std::vector<char> consumed(nodes.size(), 0);
      for (int n : slices[s].nodes) {
        Node& nd = nodes[n];
        if (consumed[n] || (top ? nd.linked_up : nd.linked_down)) continue;
        std::vector<int> group{n};
        consumed[n] = 1;
        const bool lone_hole = nd.depth % 2 == 1;
        if (!lone_hole)
          for (int h : slices[s].nodes) {
            const Node& hd = nodes[h];
            if (consumed[h] || hd.depth != nd.depth + 1 || (top ? hd.linked_up : hd.linked_down)) continue;
            if (point_in_polygon(hd.poly[0], nd.poly)) {
              group.push_back(h);
              consumed[h] = 1;
            }
          }
        if (opt.caps == CapStyle::Open) continue;
        std::vector<std::vector<Vec2>> loops;
        for (int g : group) loops.push_back(nodes[g].poly);
        CapOptions cop;
        cop.edge = opt.edge;
        cop.height = std::clamp(opt.cap_height, 0.0, 0.5) * spacing(s, top);
        bool lone = true;
        for (int g : group) lone = lone && !nodes[g].linked_up && !nodes[g].linked_down;
        // Rings (a contour with holes) keep their faired dome: its height is bound by the ring's width,
        // and a straight extrapolation of the ring's area overshoots.
        // Other Rounded caps are filled to the volume the sections' trend extrapolates (fill_cap).
        const bool fillable =
            opt.caps == CapStyle::Rounded && !lone && opt.cap_max_fill > 0 && group.size() == 1 && !lone_hole;
        // A coarser interior far from the contour: fewer unknowns for the fairing (CapOptions::far_scale).
        // Only on filled caps, whose volume the fill sets: a faired dome over a graded mesh comes out
        // lower (the umbrella Laplacian weighs a coarse region's curvature more).
        // The others get a uniform interior. Rings with walls: CGAL's bound 2 edges (mean edge about 1.4 edges; the
        // final remeshing brings it back to `edge`) and scale-aware fairing terms (below): about a quarter of
        // the points of bound 1, the frame faster (docs/algorithms/caps.md). Lone contours and holes, and rings without walls (their domes keep
        // their shape): bound √2 (mean edge about `edge`; bound 1 gave 0.7 edge) and their rows scaled by
        // 1/√2 (below).
        const bool ring = group.size() > 1 && !lone;
        if (!fillable) {
          cop.far_scale = 1.0;
          cop.uniform_scale = ring ? kRingCapScale : kUniformCapScale;
        }
        const CapMesh cap = fw.replay ? cap_on_plan(fw, loops, cop.height)
                                      : cap_of_slice(loops, opt.caps, cop, loc, slices[s].slice->id);
        if (fw.record) fw.record->caps.push_back(plan_cap(cap, loops, cop.height));
        std::vector<std::uint32_t> id;
        for (int g : group) id.insert(id.end(), nodes[g].chain.begin(), nodes[g].chain.end());
        const double dir = top ? 1.0 : -1.0;
        const std::size_t loop_ids = id.size();
        for (std::size_t k = id.size(); k < cap.points.size(); ++k) {
          id.push_back(b.add(from_plane(slices[s].plane, cap.points[k], dir * cap.height[k])));
          // Flat lids stay in their plane; domes keep their shape up to a smooth join with the wall.
          fixed.push_back(opt.caps == CapStyle::Flat ? 1 : 0);
          keep_shape.resize(b.positions.size(), 0);
          // A contour without wall (lone slice) has nothing to continue: its domes keep their shape.
          keep_shape.back() = opt.caps == CapStyle::Rounded && lone ? 1 : 0;
          // The umbrella Laplacian of a vertex grows with its edges squared, so the energy per area of a
          // region grows with its edge length squared: rows of a coarser interior are scaled back by
          // 1 / uniform_scale, keeping the dome's stiffness against the walls as at the bound of 1 edge.
          if (cop.uniform_scale != 1.0 && !ring) {
            row_scale.resize(b.positions.size(), 1.0);
            row_scale.back() = 1.0 / cop.uniform_scale;
          }
        }
        // On a ring cap meshed coarser than the walls, the uniform umbrella matches the steps, not the
        // slopes, across the contours: the dome comes out lower, even with its rows scaled. Scale-aware terms
        // on the interior and its contours (FairingOptions::scale_aware) restore its volume.
        if (ring && id.size() > loop_ids) {  // a ring cap is never filled
          scale_aware.resize(b.positions.size(), 0);
          for (std::uint32_t u : id) scale_aware[u] = 1;
        }
        const bool flip = top == lone_hole;
        CapFill fill;
        for (const Triangle& t : cap.triangles) {
          b.triangles.push_back(flip ? Triangle{id[t[0]], id[t[2]], id[t[1]]} : Triangle{id[t[0]], id[t[1]], id[t[2]]});
          fill.triangles.push_back(b.triangles.back());
        }
        if (fillable) {
          const double area = node_area(nodes[n]), neighbour = neighbour_share(nodes, pair_links, n, s, top);
          // The dome's own height: cap_height, or less on a narrow region (triangulate_cap).
          const double height = *std::max_element(cap.height.begin(), cap.height.end());
          fill.frame = {slices[s].plane.origin.z, dir, height};
          fill.target = extrapolated_cap_volume(area, neighbour, spacing(s, !top), height, opt.cap_max_fill);
          fill.end = n;
          fill.slice = s;
          fill.top = top;
          fills.push_back(std::move(fill));
        }
        ++rep.caps;
      }
    }
  if (fw.record) {
    SurfacePlan& plan = *fw.record;
    if (rep.branchings > 0) plan.unusable = "contours branch between slices";
    if (!fw.to_remesh.empty()) plan.unusable = "a band is remeshed";
    plan.triangles = b.triangles;
    plan.vertices = b.positions.size();
    plan.contour_vertices = fw.contour_vertices;
  }
  if (fw.replay) {
    if (b.positions.size() != fw.replay->vertices) throw PlanMismatch{"the vertex count differs from the plan's frame"};
    b.triangles = fw.replay->triangles;
  }
}

// Step 8: the tiled surface faired and smoothed (free vertices), held within the caps' reach, its
// domes and closing walls filled towards the sections' trend.
TriangleMesh fair(FrameWork& fw, bool& manifold) {
  const detail::SurfaceParams& opt = fw.opt;
  auto& rep = fw.rep;
  auto& b = fw.b;
  auto& nodes = fw.nodes;
  auto& slices = fw.slices;
  auto& pair_links = fw.pair_links;
  auto& fixed = fw.fixed;
  auto& keep_shape = fw.keep_shape;
  auto& row_scale = fw.row_scale;
  auto& scale_aware = fw.scale_aware;
  auto& fills = fw.fills;
  TriangleMesh mesh{std::move(b.positions), std::move(b.triangles)};
  fixed.resize(mesh.positions.size(), 0);
  keep_shape.resize(mesh.positions.size(), 0);

  const TopologyReport coarse = check_topology(mesh, kCountsOnly);
  manifold = coarse.nonmanifold_edges == 0 && coarse.nonmanifold_vertices == 0 && coarse.misoriented_edges == 0;
  if (!manifold)
    rep.warnings.push_back("the tiled surface is not a clean 2-manifold (" + std::to_string(coarse.nonmanifold_edges) +
                           " non-manifold edges, " + std::to_string(coarse.nonmanifold_vertices) +
                           " non-manifold vertices); fairing and smoothing skipped");
  bool moved = false;
  if (manifold && opt.fairing) {
    FairingOptions fo;
    fo.shape_weight = 1.0;
    if (!row_scale.empty()) {
      row_scale.resize(mesh.positions.size(), 1.0);
      fo.row_scale = std::move(row_scale);
    }
    if (!scale_aware.empty()) {
      scale_aware.resize(mesh.positions.size(), 0);
      fo.scale_aware = std::move(scale_aware);
      fo.reference_edge = opt.edge;
    }
    if (fair_thin_plate(mesh, fixed, keep_shape, fo))
      moved = true;
    else
      rep.warnings.push_back("fairing failed (singular system); the surface is left unsmoothed");
  }
  // Faired domes fall short of ends that keep their size (a tube cut across): lift each towards the
  // volume the trend of its last two sections gives, within its height.
  if (moved)
    for (const CapFill& cf : fills) fill_cap(mesh.positions, cf.triangles, cf.frame, cf.target);
  // The walls into closing ends: widened to the smooth section-area curve's volume.
  if (moved && !fills.empty()) fill_end_bands(mesh, fills, nodes, slices, pair_links, fixed);
  return mesh;
}

// Step 9: one isotropic remeshing of the faired surface with every contour edge kept; returns those
// edges.
std::vector<std::array<std::uint32_t, 2>> remesh_final(FrameWork& fw, TriangleMesh& mesh, bool manifold) {
  const detail::SurfaceParams& opt = fw.opt;
  auto& nodes = fw.nodes;
  auto& engine = fw.engine;
  auto& fixed = fw.fixed;
  // Every contour edge: kept by the final remeshing and never flipped.
  std::vector<std::array<std::uint32_t, 2>> constrained;
  for (const Node& n : nodes)
    for (std::size_t k = 0; k < n.chain.size(); ++k) {
      const std::uint32_t a = n.chain[k], c = n.chain[(k + 1) % n.chain.size()];
      constrained.push_back({std::min(a, c), std::max(a, c)});
    }
  const int final_rounds = opt.rows ? opt.rows_final_remesh_iterations : opt.final_remesh_iterations;
  if (manifold && opt.remesh && final_rounds > 0) {
    // Where the contours had to be sampled finer than `edge` (tight bends keep within the contour
    // tolerance), triangles of `edge` against them would be poorly shaped: the target follows the
    // typical contour edge, down to half of `edge`.
    std::vector<double> lengths;
    for (const auto& e : constrained) lengths.push_back(distance(mesh.positions[e[0]], mesh.positions[e[1]]));
    double target = opt.edge;
    if (!lengths.empty()) {
      std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2),
                       lengths.end());
      target = std::clamp(1.1 * lengths[lengths.size() / 2], 0.5 * opt.edge, opt.edge);
    }
    RemeshOptions mo;
    mo.edge = target;
    mo.iterations = final_rounds;
    mo.engine = engine;
    mo.split_constraints = false;
    remesh_isotropic(mesh, constrained, fixed, mo);
    flip_edges_delaunay(mesh, constrained);
  }
  return constrained;
}

// Step 10: the few thin triangles left: their free vertices moved within the surface.
void repair_angles(FrameWork& fw, TriangleMesh& mesh, const std::vector<std::array<std::uint32_t, 2>>& constrained,
                   bool manifold) {
  const detail::SurfaceParams& opt = fw.opt;
  auto& fixed = fw.fixed;
  if (manifold && opt.angle_repair.passes > 0) {
    // Trial positions a fraction of an edge from their vertex: snapped by a walk over the surface
    // from one of the vertex's triangles (no tree to build).
    const SurfaceWalk surface = make_surface_walk(mesh);
    std::vector<std::int32_t> hints(mesh.positions.size(), -1);
    auto snap_to = [&](std::uint32_t v, Vec3 c) {
      if (hints[v] < 0) hints[v] = walk_start(surface, v);
      return hints[v] < 0 ? c : walk_closest(surface, c, hints[v]);
    };
    repair_small_angles(mesh.positions, mesh.triangles, fixed, snap_to, opt.angle_repair);
    // Slivers whose three vertices are all on contours (a small cap) cannot move: flip their edge
    // where that raises the pair's smallest angle, and repair around the new edges.
    FlipOptions fo;
    fo.max_dihedral_deg = 60;
    fo.only_below_deg = opt.angle_repair.target_deg;
    if (flip_edges_delaunay(mesh, constrained, fo) > 0)
      repair_small_angles(mesh.positions, mesh.triangles, fixed, snap_to, opt.angle_repair);
    // A plan's mesh is laid onto every frame: an ear turns flat where a frame's contour straightens.
    if (fw.record && flip_ears(mesh, constrained) > 0)
      repair_small_angles(mesh.positions, mesh.triangles, fixed, snap_to, opt.angle_repair);
  }
}

// Step 11: unused vertices dropped, back to world space, the final checks into the report.
TriangleMesh finish(FrameWork& fw, TriangleMesh& mesh) {
  const detail::SurfaceParams& opt = fw.opt;
  auto& rep = fw.rep;
  auto& world = fw.world;
  std::vector<std::uint32_t> remap(mesh.positions.size(), UINT32_MAX);
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t v : t) remap[v] = 0;
  TriangleMesh out;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    if (remap[v] == 0) {
      remap[v] = static_cast<std::uint32_t>(out.positions.size());
      out.positions.push_back(mesh.positions[v]);
    }
  for (const Triangle& t : mesh.triangles) out.triangles.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});

  for (Vec3& p : out.positions) p = from_plane(world, {p.x, p.y}, p.z);
  const TopologyReport fin =
      check_topology(out, {.self_intersections = opt.check_self_intersections, .counts_only = true});
  rep.vertices = out.positions.size();
  rep.triangles = out.triangles.size();
  rep.closed = fin.closed_manifold();
  rep.self_intersects = fin.self_intersections > 0;
  rep.self_intersections_checked = opt.check_self_intersections;
  rep.euler = fin.euler;
  rep.components = static_cast<int>(fin.components.size());
  rep.volume = fin.signed_volume;
  if (!rep.closed && opt.caps != CapStyle::Open)
    rep.warnings.push_back("the surface is not closed: " + std::to_string(fin.boundary_edges) + " boundary edges");
  if (rep.self_intersects) rep.warnings.push_back("the surface intersects itself");
  return out;
}

// The plan's final mesh (after the final remeshing and the small-angle repair of the plan's frame) as its
// contour vertices first, in the faired mesh's order, then every other vertex by its triangle and barycentric
// coordinates on the faired mesh (plan.embedding). `mesh` is reordered that way.
void record_final(SurfacePlan& plan, const TriangleMesh& faired, TriangleMesh& mesh) {
  std::map<std::tuple<double, double, double>, std::uint32_t> contour_at;
  for (std::uint32_t v = 0; v < plan.contour_vertices; ++v)
    contour_at[{faired.positions[v].x, faired.positions[v].y, faired.positions[v].z}] = v;
  std::vector<char> used(mesh.positions.size(), 0);
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t v : t) used[v] = 1;
  std::vector<std::uint32_t> remap(mesh.positions.size(), UINT32_MAX);
  std::vector<Vec3> positions(plan.contour_vertices);
  std::vector<char> kept(plan.contour_vertices, 0);  // per contour vertex: present in the final mesh
  const SurfaceProjector surface(faired);
  std::int32_t hint = -1;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    if (!used[v]) continue;
    const Vec3 p = mesh.positions[v];
    const auto it = contour_at.find({p.x, p.y, p.z});
    if (it != contour_at.end()) {
      remap[v] = it->second;
      positions[it->second] = p;
      kept[it->second] = 1;
      continue;
    }
    remap[v] = static_cast<std::uint32_t>(positions.size());
    positions.push_back(p);
    surface.closest(p, nullptr, &hint);
    const std::int32_t tri = surface.mesh_triangle(hint);
    PlanPoint e;
    e.triangle = static_cast<std::uint32_t>(std::max(tri, 0));
    const Triangle& t = faired.triangles[e.triangle];
    e.weights = barycentric(p, faired.positions[t[0]], faired.positions[t[1]], faired.positions[t[2]]);
    plan.embedding.push_back(e);
  }
  if (std::find(kept.begin(), kept.end(), 0) != kept.end())
    plan.unusable = "the final remeshing dropped a contour vertex";
  for (Triangle& t : mesh.triangles)
    for (std::uint32_t& v : t) v = remap[v];
  mesh.positions = std::move(positions);
  plan.final_triangles = mesh.triangles;
}

// The plan's final mesh on this frame's faired mesh (record_final's embedding).
TriangleMesh final_on_plan(const SurfacePlan& plan, const TriangleMesh& faired) {
  TriangleMesh out;
  out.positions.assign(faired.positions.begin(),
                       faired.positions.begin() + static_cast<std::ptrdiff_t>(plan.contour_vertices));
  for (const PlanPoint& e : plan.embedding) {
    const Triangle& t = faired.triangles[e.triangle];
    out.positions.push_back(e.weights[0] * faired.positions[t[0]] + e.weights[1] * faired.positions[t[1]] +
                            e.weights[2] * faired.positions[t[2]]);
  }
  out.triangles = plan.final_triangles;
  return out;
}

// Every step on one frame: recording a plan (fw.record), following one (fw.replay) or neither.
TriangleMesh run_steps(FrameWork& fw, const Sequence& seq, int frame) {
  const detail::SurfaceParams& opt = fw.opt;
  Location loc;
  loc.file = seq.source;
  loc.frame = frame;
  if (frame < 0 || frame >= static_cast<int>(seq.frames.size()))
    throw InvalidInput(ErrorCode::Usage, loc,
                       "frame " + std::to_string(frame) + " does not exist (the input has " +
                           std::to_string(seq.frames.size()) + " frames)",
                       "pick a frame from 0 to the frame count - 1");
  if (!(opt.edge > 0) || !std::isfinite(opt.edge))
    throw InvalidInput(ErrorCode::Usage, loc, "the target edge length must be a positive number of mm",
                       "use e.g. --edge 1.0");
  const Frame& f = seq.frames[static_cast<std::size_t>(frame)];
  fw.loc = loc;
  filter_frame(fw, seq, f, choose_label(f, opt, loc));
  canonical_contours(fw);
  link_nodes(fw, frame);
  tile_walls(fw);
  remesh_branch_bands(fw);
  add_caps(fw);
  bool manifold = false;
  TriangleMesh mesh = fair(fw, manifold);
  if (fw.replay) {  // the plan's final mesh on this frame's faired surface; nothing else moves
    TriangleMesh out = final_on_plan(*fw.replay, mesh);
    return finish(fw, out);
  }
  const TriangleMesh faired = fw.record ? mesh : TriangleMesh{};
  const auto constrained = remesh_final(fw, mesh, manifold);
  repair_angles(fw, mesh, constrained, manifold);
  if (fw.record) record_final(*fw.record, faired, mesh);
  return finish(fw, mesh);
}

}  // namespace

namespace detail {

SurfaceParams surface_params(const SurfaceOptions& options, const SurfaceTuning& tuning) {
  SurfaceParams p;
  static_cast<SurfaceOptions&>(p) = options;
  static_cast<SurfaceTuning&>(p) = tuning;
  p.angle_repair.target_deg = options.angle_target_deg;
  if (options.geometry_only) {  // a projection target: the geometry, not even triangles or a report
    p.rows = true;
    p.rows_final_remesh_iterations = 0;
    p.check_self_intersections = false;
    p.angle_repair.passes = 0;
  }
  return p;
}

TriangleMesh reconstruct_frame_tuned(const Sequence& seq, int frame, const SurfaceParams& opt, SurfaceReport* report) {
  FrameWork fw(opt);
  TriangleMesh out = run_steps(fw, seq, frame);
  // Bridges at a branching can fold the band where the sections merge far from where they are closest (two
  // arcs joining into one C-shaped section): a surface that fails its checks there is built once more with
  // the paper's tiling at its branchings, whose heights follow the distances to both slices' contours.
  const bool failed = fw.rep.self_intersects || (!fw.rep.closed && opt.caps != CapStyle::Open);
  if (failed && fw.rep.branchings > 0 && opt.tiling == Tiling::Bands && opt.check_self_intersections) {
    FrameWork retry(opt);
    retry.delaunay_branchings = true;
    TriangleMesh second = run_steps(retry, seq, frame);
    if (retry.rep.closed && !retry.rep.self_intersects) {
      retry.rep.warnings.push_back(
          "the band tiling's bridges folded at a branching; the paper's tiling was used there");
      out = std::move(second);
      fw.rep = std::move(retry.rep);
    }
  }
  if (report) *report = std::move(fw.rep);
  return out;
}

}  // namespace detail

TriangleMesh reconstruct_frame(const Sequence& seq, int frame, const SurfaceOptions& options, SurfaceReport* report) {
  return detail::reconstruct_frame_tuned(seq, frame, detail::surface_params(options), report);
}

SurfacePlan plan_surface(const Sequence& seq, int frame, const SurfaceOptions& options) {
  SurfacePlan plan;
  const detail::SurfaceParams opt = detail::surface_params(options);
  FrameWork fw(opt);
  fw.record = &plan;
  run_steps(fw, seq, frame);
  if (!options.rows || options.geometry_only) plan.unusable = "the bands are remeshed (rows off)";
  if (options.tiling != Tiling::Bands) plan.unusable = "the Delaunay tiling";
  return plan;
}

std::optional<TriangleMesh> reconstruct_frame_on_plan(const Sequence& seq, int frame, const SurfaceOptions& options,
                                                      const SurfacePlan& plan, SurfaceReport* report,
                                                      std::string* why_not) {
  if (!plan.unusable.empty()) {
    if (why_not) *why_not = plan.unusable;
    return std::nullopt;
  }
  const detail::SurfaceParams opt = detail::surface_params(options);
  FrameWork fw(opt);
  fw.replay = &plan;
  try {
    TriangleMesh out = run_steps(fw, seq, frame);
    if (report) *report = std::move(fw.rep);
    return out;
  } catch (const PlanMismatch& m) {
    if (why_not) *why_not = m.why;
    return std::nullopt;
  }
}

}  // namespace c4d
