// Mesh validity for the papers' claim of "a complete closed manifold" (Lim et al. 2014,
// "3D Reconstruction") and for the checks: boundary edges, edge and vertex manifoldness,
// consistent and outward orientation, components and genus from the Euler characteristic
// (χ = V − E + F = 2 − 2g − b per component), self-intersections, degenerate and duplicate elements.
//
// The mesh is treated as a triangle soup with shared indices, not loaded into a halfedge
// structure, because the faults we look for are exactly those a halfedge structure cannot hold.
// Self-intersections follow the rule of CGAL's Polygon_mesh_processing::self_intersections (two
// triangles intersect unless they only share a vertex or an edge), re-stated over vertex indices so
// that non-manifold input is fine; box_self_intersection_d prunes pairs, Epick predicates are exact.
#include "contour4d/metrics/topology.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <set>
#include <stdexcept>
#include <tuple>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "contour4d/core/union_find.h"
#include "simd/box_overlap_internal.h"

namespace c4d {
namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Box =
    CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t, CGAL::Box_intersection_d::ID_FROM_BOX_ADDRESS>;

Point to_point(Vec3 p) { return {p.x, p.y, p.z}; }

bool valid_triangle(const Triangle& t, std::size_t nv) {
  return t[0] < nv && t[1] < nv && t[2] < nv && t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
}

// One directed edge of a triangle, sorted by its undirected key.
struct HalfEdge {
  std::uint32_t lo, hi;               // undirected key
  std::uint32_t tri;                  // the triangle
  std::uint8_t corner_lo, corner_hi;  // the triangle's corner at lo, at hi
  bool forward;                       // traversed lo -> hi
};

std::string plural(std::size_t n, const char* one, const char* many) {
  return fmt::format("{} {}", n, n == 1 ? one : many);
}

// Do triangles i and j intersect other than in what they share? (CGAL PMP's rule, on indices.)
bool triangles_intersect(const std::vector<Vec3>& positions, const Triangle& s, const Triangle& t) {
  int shared_s[3], shared_t[3], n = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      if (s[a] == t[b]) {
        shared_s[n] = a;
        shared_t[n] = b;
        ++n;
      }
  auto P = [&](std::uint32_t v) { return to_point(positions[v]); };
  if (n == 3) return true;  // the same triangle twice
  if (n == 2) {
    // A shared edge: they overlap only when coplanar with the third corners on the same side.
    const int c = 3 - shared_s[0] - shared_s[1], d = 3 - shared_t[0] - shared_t[1];
    const Point pa = P(s[shared_s[0]]), pb = P(s[shared_s[1]]), pc = P(s[c]), pd = P(t[d]);
    return CGAL::coplanar(pa, pb, pc, pd) && CGAL::coplanar_orientation(pa, pb, pc, pd) == CGAL::POSITIVE;
  }
  const Kernel::Triangle_3 ts(P(s[0]), P(s[1]), P(s[2])), tt(P(t[0]), P(t[1]), P(t[2]));
  if (n == 1) {
    // A shared vertex: they intersect elsewhere iff the edge opposite it in one crosses the other.
    const int a = shared_s[0], b = shared_t[0];
    const Kernel::Segment_3 es(P(s[(a + 1) % 3]), P(s[(a + 2) % 3])), et(P(t[(b + 1) % 3]), P(t[(b + 2) % 3]));
    return CGAL::do_intersect(ts, et) || CGAL::do_intersect(tt, es);
  }
  return CGAL::do_intersect(ts, tt);
}
}  // namespace

namespace {

// Vertices whose triangles cannot cut each other: they form one closed, consistently oriented fan
// whose projection along a coordinate axis (the fan's main normal direction) turns the same way in
// every triangle and winds once around the vertex. The projected triangles then share only edges
// and the vertex, and since none projects flat, two of them meet in space only there: no pair
// through this vertex (or through an edge of it) needs a test. The projection drops a coordinate,
// so the orientations (exact predicates) and the winding (coordinate comparisons) are exact.
// Only the vertices flagged in `wanted` are examined (all when it is null).
std::vector<char> untangled_fans(const TriangleMesh& mesh, const std::vector<char>* wanted) {
  const std::size_t nv = mesh.positions.size();
  std::vector<char> ok(nv, 0);
  std::vector<std::uint32_t> start(nv + 1, 0);
  for (const Triangle& t : mesh.triangles)
    if (valid_triangle(t, nv))
      for (std::uint32_t v : t) ++start[v + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  // Per vertex, the directed edges opposite it (a -> b for its triangle (v, a, b)).
  std::vector<std::array<std::uint32_t, 2>> opposite(start.back());
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (const Triangle& t : mesh.triangles)
      if (valid_triangle(t, nv))
        for (int k = 0; k < 3; ++k) opposite[fill[t[k]]++] = {t[(k + 1) % 3], t[(k + 2) % 3]};
  }
  std::vector<std::uint32_t> ring;
  std::vector<Kernel::Point_2> flat;  // the ring projected, its first point again at the end
  for (std::size_t v = 0; v < nv; ++v) {
    if (wanted != nullptr && !(*wanted)[v]) continue;
    const std::uint32_t b = start[v], e = start[v + 1];
    const std::size_t k = e - b;
    if (k < 3 || !is_finite(mesh.positions[v])) continue;
    // The fan's cycle: from the first edge, each next edge starts where the last one ended. Every
    // vertex after the first has one edge out, so a neighbour met twice means the walk came back to
    // the first one early (and then cycles through the same neighbours): no fan.
    ring.assign(1, opposite[b][0]);
    std::uint32_t at = opposite[b][1];
    bool closed = true;
    for (std::size_t step = 1; step < k && closed; ++step) {
      if (at == ring[0]) {
        closed = false;
        break;
      }
      ring.push_back(at);
      std::size_t found = 0, next = 0;
      for (std::uint32_t r = b; r < e; ++r)
        if (opposite[r][0] == at) {
          ++found;
          next = r;
        }
      closed = found == 1;
      if (closed) at = opposite[next][1];
    }
    if (!closed || at != ring[0]) continue;
    ring.push_back(ring[0]);  // ring[i + 1] follows ring[i] for every i < k
    const Vec3 pv = mesh.positions[v];
    Vec3 normal{};
    bool finite = true;
    for (std::size_t i = 0; i < k; ++i) {
      const Vec3 pa = mesh.positions[ring[i]], pb = mesh.positions[ring[i + 1]];
      finite = finite && is_finite(pa);
      normal += cross(pa - pv, pb - pv);
    }
    if (!finite) continue;
    // The axis dropped, and the other two coordinates in the order that makes the fan turn positively.
    const double n[3] = {normal.x, normal.y, normal.z};
    int axis = 0;
    for (int c = 1; c < 3; ++c)
      if (std::abs(n[c]) > std::abs(n[axis])) axis = c;
    if (!(n[axis] != 0)) continue;
    int cu = (axis + 1) % 3, cw = (axis + 2) % 3;
    if (n[axis] < 0) std::swap(cu, cw);
    auto plane = [&](const Vec3& p) {
      const double q[3] = {p.x, p.y, p.z};
      return Kernel::Point_2(q[cu], q[cw]);
    };
    const Kernel::Point_2 o = plane(pv);
    // Upper half-turn: angles in [0, pi) around o.
    auto upper = [&](const Kernel::Point_2& a) { return a.y() > o.y() || (a.y() == o.y() && a.x() > o.x()); };
    flat.clear();
    for (std::size_t i = 0; i <= k; ++i) flat.push_back(plane(mesh.positions[ring[i]]));
    bool good = true;
    int turns = 0;
    for (std::size_t i = 0; i < k && good; ++i) {
      const Kernel::Point_2 &a = flat[i], &c = flat[i + 1];
      good = CGAL::orientation(o, a, c) == CGAL::LEFT_TURN;
      if (!upper(a) && upper(c)) ++turns;
    }
    ok[v] = good && turns == 1;
  }
  return ok;
}

// A grid key that matches nothing (see grid_overlapping_pairs).
constexpr std::uint32_t kNoKey = 0xFFFFFFFFu;

// std::nextafter(f, -infinity) for f not NaN (the largest float below f), without a library call.
inline float next_float_down(float f) {
  const auto u = std::bit_cast<std::uint32_t>(f);
  const float below = std::bit_cast<float>(f > 0.0f ? u - 1 : u + 1);
  return f == 0.0f ? -std::numeric_limits<float>::denorm_min() : below;
}

// Pair tests per box above which the grid gives way to CGAL (see grid_overlapping_pairs).
constexpr double kCrowded = 64.0;

// The grid over the boxes: its lower corner, cell size and cells per axis, each box's span of cells,
// and the boxes listed per cell (start: first item of each cell, CSR).
struct Grid {
  double lo[3] = {1e300, 1e300, 1e300};
  double cell = 0.0;
  std::int64_t size[3] = {0, 0, 0};
  std::size_t ncells = 0;
  std::vector<std::array<std::int32_t, 6>> span;  // per box: its cells from (i0, j0, k0) to (i1, j1, k1)
  std::vector<std::uint32_t> start, items;
};

// Sets the grid's corner, cell size (two median box sizes, doubled until the block holds at most
// 8 cells per box) and cells per axis; false when no grid fits.
bool choose_cells(const std::vector<std::array<double, 6>>& box, Grid& g) {
  const std::size_t n = box.size();
  // The boxes' extents.
  std::vector<double> sizes(n);
  double hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t m = 0; m < n; ++m) {
    double big = 0.0;
    for (int d = 0; d < 3; ++d) {
      big = std::max(big, box[m][d + 3] - box[m][d]);
      g.lo[d] = std::min(g.lo[d], box[m][d]);
      hi[d] = std::max(hi[d], box[m][d + 3]);
    }
    sizes[m] = big;
  }
  std::nth_element(sizes.begin(), sizes.begin() + static_cast<std::ptrdiff_t>(n / 2), sizes.end());
  g.cell = 2.0 * sizes[n / 2];
  if (!(g.cell > 0.0) || !std::isfinite(g.cell)) return false;
  for (;;) {
    double cells = 1.0;
    for (int d = 0; d < 3; ++d) {
      const double extent = std::floor((hi[d] - g.lo[d]) / g.cell) + 1.0;
      if (!(extent < 1e9)) return false;
      g.size[d] = static_cast<std::int64_t>(extent);
      cells *= extent;
    }
    if (cells <= std::max(4096.0, 8.0 * static_cast<double>(n))) break;
    g.cell *= 2.0;
  }
  g.ncells = static_cast<std::size_t>(g.size[0] * g.size[1] * g.size[2]);
  return true;
}

// The cell of coordinate v along axis d. Coordinates are at least lo: truncation is the floor.
// Monotone, so the cell of the larger of two lower corners is the larger of their cells.
std::int32_t cell_at(const Grid& g, double v, int d) {
  return static_cast<std::int32_t>(std::min(static_cast<std::int64_t>((v - g.lo[d]) / g.cell), g.size[d] - 1));
}

// The index of cell (i, j, k).
std::size_t cell_index(const Grid& g, std::int64_t i, std::int64_t j, std::int64_t k) {
  return static_cast<std::size_t>((i * g.size[1] + j) * g.size[2] + k);
}

// Calls visit(cell index) for every cell that box m meets.
template <class G>
void for_each_cell_of(const Grid& g, std::size_t m, G&& visit) {
  const auto& c = g.span[m];
  for (std::int64_t i = c[0]; i <= c[3]; ++i)
    for (std::int64_t j = c[1]; j <= c[4]; ++j)
      for (std::int64_t k = c[2]; k <= c[5]; ++k) visit(cell_index(g, i, j, k));
}

// Each box's span of cells.
void cell_spans(const std::vector<std::array<double, 6>>& box, Grid& g) {
  const std::size_t n = box.size();
  g.span.resize(n);
  for (std::size_t m = 0; m < n; ++m)
    for (int d = 0; d < 3; ++d) {
      g.span[m][d] = cell_at(g, box[m][d], d);
      g.span[m][d + 3] = cell_at(g, box[m][d + 3], d);
    }
}

// Lists the boxes per cell (g.start, g.items); false when the cells are crowded (more than
// kCrowded pair tests per box), then g.items stays empty.
bool bucket_boxes(Grid& g, std::size_t n) {
  g.start.assign(g.ncells + 1, 0);
  for (std::size_t m = 0; m < n; ++m) for_each_cell_of(g, m, [&](std::size_t c) { ++g.start[c + 1]; });
  double tests = 0.0;
  for (std::size_t c = 0; c < g.ncells; ++c)
    tests += 0.5 * static_cast<double>(g.start[c + 1]) * static_cast<double>(g.start[c + 1]);
  if (tests > kCrowded * static_cast<double>(n)) return false;
  for (std::size_t c = 0; c < g.ncells; ++c) g.start[c + 1] += g.start[c];
  g.items.resize(g.start[g.ncells]);
  std::vector<std::uint32_t> fill(g.start.begin(), g.start.end() - 1);
  for (std::size_t m = 0; m < n; ++m)
    for_each_cell_of(g, m, [&](std::size_t c) { g.items[fill[c]++] = static_cast<std::uint32_t>(m); });
  return true;
}

// Per box: 1 when its triangle is flagged (every box when `flagged` is null).
std::vector<char> flagged_boxes(const std::vector<std::size_t>& info, const std::vector<char>* flagged) {
  const std::size_t n = info.size();
  std::vector<char> marked(n, 1);
  if (flagged != nullptr)
    for (std::size_t m = 0; m < n; ++m) {
      const std::size_t t = info[m];
      marked[m] = t < flagged->size() && (*flagged)[t] ? 1 : 0;
    }
  return marked;
}

// Each box in single precision, rounded outwards (so a pair of closed boxes that overlap also
// overlaps here): 6 floats per box, lower x, y, z then upper x, y, z.
std::vector<float> loose_boxes(const std::vector<std::array<double, 6>>& box) {
  const std::size_t n = box.size();
  std::vector<float> loose_by_box(6 * n);
  for (std::size_t m = 0; m < n; ++m)
    for (int d = 0; d < 3; ++d) {
      const double l = box[m][d], h = box[m][d + 3];
      float fl = static_cast<float>(l), fh = static_cast<float>(h);
      fl = static_cast<double>(fl) > l ? next_float_down(fl) : fl;
      fh = static_cast<double>(fh) < h ? -next_float_down(-fh) : fh;
      loose_by_box[6 * m + static_cast<std::size_t>(d)] = fl;
      loose_by_box[6 * m + 3 + static_cast<std::size_t>(d)] = fh;
    }
  return loose_by_box;
}

// Each cell's items side by side, one array per coordinate, then the keys, one array per corner.
struct ItemColumns {
  // bounds[d * ni + a]: item a's lower (d < 3) or upper corner; keys[k * ni + a]. Three more
  // entries at the end: the last four-wide loads reach past the last item (their lanes are masked).
  std::vector<float> bounds;
  std::vector<std::uint32_t> keys;
};

// The items' loose bounds and keys, column by column.
ItemColumns item_columns(const std::vector<std::uint32_t>& items, const std::vector<float>& loose_by_box,
                         const std::vector<std::array<std::uint32_t, 3>>& keys) {
  const std::size_t ni = items.size();
  ItemColumns cols;
  cols.bounds.resize(6 * ni + 3);
  cols.keys.resize(3 * ni + 3);
  for (std::size_t a = 0; a < ni; ++a) {
    const std::size_t m = items[a];
    for (std::size_t d = 0; d < 6; ++d) cols.bounds[d * ni + a] = loose_by_box[6 * m + d];
    for (std::size_t k = 0; k < 3; ++k) cols.keys[k * ni + a] = keys[m][k];
  }
  return cols;
}

// What the pair loop reads: the exact boxes, the grid, the flags, and the item columns.
struct PairScan {
  const std::vector<std::array<double, 6>>& box;
  const Grid& grid;
  const std::vector<char>& marked;
  detail::BoxColumns columns;
};

// The pair loop's view of the boxes, the grid, the flags and the columns (cols must outlive it).
PairScan pair_scan(const std::vector<std::array<double, 6>>& box, const Grid& g, const std::vector<char>& marked,
                   const ItemColumns& cols) {
  const std::size_t ni = g.items.size();
  const float* lo0 = cols.bounds.data();
  const std::uint32_t* key0 = cols.keys.data();
  return {box,
          g,
          marked,
          {lo0, lo0 + ni, lo0 + 2 * ni, lo0 + 3 * ni, lo0 + 4 * ni, lo0 + 5 * ni, key0, key0 + ni, key0 + 2 * ni}};
}

// Appends to `out` the pairs (a, b) with a's item first, b after a in cell c (items start[c]..e),
// whose loose boxes overlap, that share no key, whose exact boxes overlap with one flagged, and
// that are met in this cell (ci, cj, ck), the cell of the larger lower corner.
void scan_item(const PairScan& s, std::uint32_t a, std::uint32_t e, std::int64_t ci, std::int64_t cj, std::int64_t ck,
               std::vector<std::array<std::uint32_t, 2>>& out) {
  const std::uint32_t p = s.grid.items[a];
  const auto& x = s.box[p];
  const auto& sx = s.grid.span[p];
  // Item b of the cell whose loose box overlaps a's and shares no key with it (simd/box_overlap_internal.h).
  detail::for_each_overlapping(s.columns, a, e, kNoKey, [&](std::uint32_t b) {
    const std::uint32_t q = s.grid.items[b];
    const auto& y = s.box[q];
    if (x[0] > y[3] || y[0] > x[3] || x[1] > y[4] || y[1] > x[4] || x[2] > y[5] || y[2] > x[5]) return;
    if (!s.marked[p] && !s.marked[q]) return;
    // Met only in the cell of the larger lower corner.
    const auto& sy = s.grid.span[q];
    if (std::max(sx[0], sy[0]) != ci || std::max(sx[1], sy[1]) != cj || std::max(sx[2], sy[2]) != ck) return;
    out.push_back({std::min(p, q), std::max(p, q)});
  });
}

// The cells in blocks of consecutive indices.
constexpr std::size_t kCellsPerBlock = 512;

// Lists the pairs of one block of cells into `out`, in the order of one loop over its cells.
void scan_block(const PairScan& s, std::size_t block, std::vector<std::array<std::uint32_t, 2>>& out) {
  const Grid& g = s.grid;
  const std::size_t c_end = std::min(g.ncells, (block + 1) * kCellsPerBlock);
  for (std::size_t c = block * kCellsPerBlock; c < c_end; ++c) {
    const std::uint32_t e = g.start[c + 1];
    if (e - g.start[c] < 2) continue;
    const auto ck = static_cast<std::int64_t>(c % static_cast<std::size_t>(g.size[2]));
    const auto cj =
        static_cast<std::int64_t>((c / static_cast<std::size_t>(g.size[2])) % static_cast<std::size_t>(g.size[1]));
    const auto ci = static_cast<std::int64_t>(c / static_cast<std::size_t>(g.size[2] * g.size[1]));
    for (std::uint32_t a = g.start[c]; a < e; ++a) scan_item(s, a, e, ci, cj, ck, out);
  }
}

// Calls f(x, y) once for every pair of boxes (x before y in `boxes`) whose closed boxes overlap and of
// which at least one is flagged (`flagged` null: every box), as CGAL's box_intersection_d would, through a
// grid: each box is listed in every cell of about two median box sizes that it meets, and a pair is met
// in the cell of the larger of their lower corners only (a cell that both boxes meet), so once. A
// surface's boxes are small and evenly spread; where the cells are crowded (more pair tests than
// kCrowded per box) it returns false having called nothing, and the caller asks CGAL.
//
// `keys` (one per box) lets the grid drop, on data it holds side by side, pairs the caller would drop
// anyway: two boxes with an equal key other than kNoKey (the caller: a shared vertex whose fan is
// untangled) are not reported.
template <class F>
bool grid_overlapping_pairs(const std::vector<std::array<double, 6>>& box, const std::vector<std::size_t>& info,
                            const std::vector<char>* flagged, const std::vector<std::array<std::uint32_t, 3>>& keys,
                            F&& f) {
  const std::size_t n = box.size();
  if (n < 2) return true;
  Grid g;
  if (!choose_cells(box, g)) return false;
  cell_spans(box, g);
  if (!bucket_boxes(g, n)) return false;
  const std::vector<char> marked = flagged_boxes(info, flagged);
  // Each cell's boxes side by side in single precision with their keys: the pair loop reads its cell
  // in order, four boxes per SSE2 compare where the CPU has it, and only the pairs that pass go on to
  // the exact test in double precision.
  const ItemColumns cols = item_columns(g.items, loose_boxes(box), keys);
  const PairScan s = pair_scan(box, g, marked, cols);
  // Each block lists its pairs in the serial loop's order (in parallel where the grid is large),
  // then f sees the blocks' pairs in block order: the calls and their order are those of one loop
  // over the cells, whatever the thread count.
  const std::size_t blocks = (g.ncells + kCellsPerBlock - 1) / kCellsPerBlock;
  std::vector<std::vector<std::array<std::uint32_t, 2>>> found(blocks);
  auto scan = [&](std::size_t block) { scan_block(s, block, found[block]); };
  if (n >= 8192 && blocks > 1)
    tbb::parallel_for(std::size_t{0}, blocks, scan);
  else
    for (std::size_t block = 0; block < blocks; ++block) scan(block);
  for (const auto& pairs : found)
    for (const auto& [p, q] : pairs) f(info[p], info[q]);
  return true;
}

// count_self_intersections and its restriction to flagged triangles (`only` null: all pairs).
std::size_t count_intersecting_pairs(const TriangleMesh& mesh, const std::vector<char>* only,
                                     std::vector<std::pair<std::size_t, std::size_t>>* pairs,
                                     std::size_t max_pairs_listed) {
  const std::size_t nv = mesh.positions.size();
  // The triangles tested (valid, finite, not collinear), in order: their boxes (min x y z, max x y z).
  std::vector<char> finite(nv);
  for (std::size_t v = 0; v < nv; ++v) finite[v] = is_finite(mesh.positions[v]) ? 1 : 0;
  std::vector<std::array<double, 6>> coords;
  std::vector<std::size_t> info;
  coords.reserve(mesh.triangles.size());
  info.reserve(mesh.triangles.size());
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const Triangle& t = mesh.triangles[i];
    if (!valid_triangle(t, nv) || !finite[t[0]] || !finite[t[1]] || !finite[t[2]]) continue;
    const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    if (CGAL::collinear(to_point(a), to_point(b), to_point(c)))
      continue;  // reported as degenerate, not as an intersection
    coords.push_back({std::min({a.x, b.x, c.x}), std::min({a.y, b.y, c.y}), std::min({a.z, b.z, c.z}),
                      std::max({a.x, b.x, c.x}), std::max({a.y, b.y, c.y}), std::max({a.z, b.z, c.z})});
    info.push_back(i);
  }
  auto flagged = [&](std::size_t i) { return only == nullptr || (i < only->size() && (*only)[i]); };
  std::size_t flagged_count = 0;
  std::size_t count = 0;
  std::set<std::pair<std::size_t, std::size_t>> first;  // the smallest pairs: same list whatever the visiting order
  // Every pair tested has a flagged triangle: only the fans of their vertices are needed.
  std::vector<char> wanted;
  if (only != nullptr) {
    wanted.assign(nv, 0);
    for (std::size_t i : info)
      if (flagged(i)) {
        ++flagged_count;
        for (std::uint32_t v : mesh.triangles[i]) wanted[v] = 1;
      }
  }
  const std::vector<char> untangled = untangled_fans(mesh, only != nullptr ? &wanted : nullptr);
  // Triangles x and y (indices) whose boxes overlap.
  auto callback = [&](std::size_t x, std::size_t y) {
    const std::size_t i = std::min(x, y), j = std::max(x, y);
    if (i == j) return;
    // A pair of two flagged triangles is met twice in the two-set search: counted from its smaller one.
    if (only != nullptr && flagged(y) && x > y) return;
    const Triangle &s = mesh.triangles[i], &t = mesh.triangles[j];
    for (std::uint32_t v : s)
      if (untangled[v] && (v == t[0] || v == t[1] || v == t[2])) return;
    if (!triangles_intersect(mesh.positions, mesh.triangles[i], mesh.triangles[j])) return;
    ++count;
    if (pairs != nullptr && max_pairs_listed > 0) {
      first.insert({i, j});
      if (first.size() > max_pairs_listed) first.erase(std::prev(first.end()));
    }
  };
  // The grid's keys: each triangle's vertices whose fans are untangled (pairs sharing one are dropped
  // by the callback's first test).
  std::vector<std::array<std::uint32_t, 3>> keys(info.size());
  for (std::size_t m = 0; m < info.size(); ++m) {
    const Triangle& t = mesh.triangles[info[m]];
    for (int k = 0; k < 3; ++k)
      keys[m][static_cast<std::size_t>(k)] =
          untangled[t[static_cast<std::size_t>(k)]] ? t[static_cast<std::size_t>(k)] : kNoKey;
  }
  // The grid, or CGAL's box search where the grid's cells are crowded.
  const bool nothing_flagged = only != nullptr && flagged_count == 0;
  if (!nothing_flagged && !grid_overlapping_pairs(coords, info, only, keys, callback)) {
    std::vector<Box> boxes;
    boxes.reserve(coords.size());
    for (std::size_t m = 0; m < coords.size(); ++m) {
      const auto& c = coords[m];
      boxes.emplace_back(CGAL::Bbox_3(c[0], c[1], c[2], c[3], c[4], c[5]), info[m]);
    }
    std::vector<const Box*> all, some;
    all.reserve(boxes.size());
    for (const Box& b : boxes) {
      all.push_back(&b);
      if (only != nullptr && flagged(b.info())) some.push_back(&b);
    }
    auto by_box = [&](const Box* x, const Box* y) { callback(x->info(), y->info()); };
    if (only == nullptr)
      CGAL::box_self_intersection_d<CGAL::Sequential_tag>(all.begin(), all.end(), by_box, std::ptrdiff_t(2000));
    else
      CGAL::box_intersection_d<CGAL::Sequential_tag>(some.begin(), some.end(), all.begin(), all.end(), by_box);
  }
  if (pairs != nullptr) pairs->assign(first.begin(), first.end());
  return count;
}

}  // namespace

std::size_t count_self_intersections(const TriangleMesh& mesh, std::vector<std::pair<std::size_t, std::size_t>>* pairs,
                                     std::size_t max_pairs_listed) {
  return count_intersecting_pairs(mesh, nullptr, pairs, max_pairs_listed);
}

std::size_t count_self_intersections_of(const TriangleMesh& mesh, const std::vector<char>& only,
                                        std::vector<std::pair<std::size_t, std::size_t>>* pairs,
                                        std::size_t max_pairs_listed) {
  return count_intersecting_pairs(mesh, &only, pairs, max_pairs_listed);
}

bool intersects_any(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                    const std::vector<std::uint32_t>& these, const std::vector<std::uint32_t>& others) {
  const std::size_t nv = positions.size();
  // A triangle's bounding box, or none when count_self_intersections would skip it.
  auto box = [&](std::uint32_t f) -> std::optional<CGAL::Bbox_3> {
    if (f >= triangles.size()) return std::nullopt;
    const Triangle& t = triangles[f];
    if (!valid_triangle(t, nv)) return std::nullopt;
    const Vec3 a = positions[t[0]], b = positions[t[1]], c = positions[t[2]];
    if (!is_finite(a) || !is_finite(b) || !is_finite(c)) return std::nullopt;
    const Point pa = to_point(a), pb = to_point(b), pc = to_point(c);
    if (CGAL::collinear(pa, pb, pc)) return std::nullopt;
    return pa.bbox() + pb.bbox() + pc.bbox();
  };
  std::vector<std::pair<std::uint32_t, CGAL::Bbox_3>> mine;
  for (std::uint32_t f : these)
    if (const auto b = box(f)) mine.push_back({f, *b});
  // Closed boxes, as box_self_intersection_d's default: an intersection always has overlapping boxes.
  auto hit = [&](std::uint32_t f, const CGAL::Bbox_3& bf, std::uint32_t g, const CGAL::Bbox_3& bg) {
    return f != g && CGAL::do_overlap(bf, bg) && triangles_intersect(positions, triangles[f], triangles[g]);
  };
  for (std::size_t i = 0; i < mine.size(); ++i)
    for (std::size_t j = i + 1; j < mine.size(); ++j)
      if (hit(mine[i].first, mine[i].second, mine[j].first, mine[j].second)) return true;
  for (std::uint32_t g : others) {
    if (std::find(these.begin(), these.end(), g) != these.end()) continue;
    const auto bg = box(g);
    if (!bg) continue;
    for (const auto& [f, bf] : mine)
      if (hit(f, bf, g, *bg)) return true;
  }
  return false;
}

namespace {

// Counts invalid, degenerate and (with `duplicates`) duplicate triangles and unreferenced vertices into
// r; returns the indices of the valid triangles.
std::vector<std::size_t> check_triangles(const TriangleMesh& mesh, bool duplicates, TopologyReport& r) {
  const std::size_t nv = mesh.positions.size();
  std::vector<std::size_t> tris;  // indices of valid triangles
  tris.reserve(mesh.triangles.size());
  std::vector<std::array<std::uint32_t, 3>> sorted_keys;
  std::vector<char> used(nv, 0);
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const Triangle& t = mesh.triangles[i];
    if (!valid_triangle(t, nv)) {
      ++r.invalid_triangles;
      continue;
    }
    tris.push_back(i);
    for (std::uint32_t v : t) used[v] = 1;
    if (duplicates) {
      std::array<std::uint32_t, 3> k = t;
      std::sort(k.begin(), k.end());
      sorted_keys.push_back(k);
    }
    if (CGAL::collinear(to_point(mesh.positions[t[0]]), to_point(mesh.positions[t[1]]), to_point(mesh.positions[t[2]])))
      ++r.degenerate_triangles;
  }
  std::sort(sorted_keys.begin(), sorted_keys.end());
  for (std::size_t i = 1; i < sorted_keys.size(); ++i) r.duplicate_triangles += sorted_keys[i] == sorted_keys[i - 1];
  r.unreferenced_vertices = static_cast<std::size_t>(std::count(used.begin(), used.end(), 0));
  return tris;
}

// Duplicate vertices: equal positions after a lexicographic sort.
std::size_t count_duplicate_vertices(const TriangleMesh& mesh) {
  std::size_t duplicates = 0;
  std::vector<std::uint32_t> order(mesh.positions.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const Vec3 p = mesh.positions[a], q = mesh.positions[b];
    return std::tie(p.x, p.y, p.z, a) < std::tie(q.x, q.y, q.z, b);
  });
  for (std::size_t i = 1; i < order.size(); ++i) duplicates += mesh.positions[order[i]] == mesh.positions[order[i - 1]];
  return duplicates;
}

std::uint8_t corner_of(const Triangle& t, std::uint32_t v) { return t[0] == v ? 0 : (t[1] == v ? 1 : 2); }

// The valid triangles' directed edges sorted by (lo, hi, tri): each run is one edge. A counting sort by
// the lower endpoint, then each vertex's few half-edges sorted by (hi, tri): one sort's order in linear time.
std::vector<HalfEdge> sorted_half_edges(const TriangleMesh& mesh, const std::vector<std::size_t>& tris) {
  const std::size_t nv = mesh.positions.size();
  std::vector<std::size_t> start(nv + 1, 0);
  for (std::size_t i : tris) {
    const Triangle& t = mesh.triangles[i];
    for (int k = 0; k < 3; ++k) ++start[std::min(t[k], t[(k + 1) % 3]) + 1];
  }
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<HalfEdge> he(3 * tris.size());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::size_t i : tris) {
    const Triangle& t = mesh.triangles[i];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3], lo = std::min(a, b), hi = std::max(a, b);
      he[fill[lo]++] = {lo, hi, static_cast<std::uint32_t>(i), corner_of(t, lo), corner_of(t, hi), a < b};
    }
  }
  for (std::size_t v = 0; v < nv; ++v)
    std::sort(he.begin() + static_cast<std::ptrdiff_t>(start[v]),
              he.begin() + static_cast<std::ptrdiff_t>(start[v + 1]),
              [](const HalfEdge& x, const HalfEdge& y) { return x.hi != y.hi ? x.hi < y.hi : x.tri < y.tri; });
  return he;
}

// The undirected edges, as runs of the sorted half-edges.
struct EdgeTable {
  // Orientation graph: two-triangle edges; parity_link = true when the pair must differ in flip.
  std::vector<std::vector<std::pair<std::size_t, bool>>> adj;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> boundary;
  std::vector<std::size_t> edge_start;  // index into he of each edge's first half-edge
  std::vector<std::size_t> edge_size;   // number of triangles on each edge
};

// Groups the half-edges into edges, counts non-manifold and misoriented edges into r, joins the
// triangles of each edge in `comp` and their corners at each end in `corners` (corner 3·tri + k). With
// `orientation_graph` false the two-triangle edges are not listed in the table's adjacency.
EdgeTable scan_edges(const std::vector<HalfEdge>& he, std::size_t triangle_count, bool orientation_graph,
                     UnionFind& comp, DisjointSets<std::uint32_t>& corners, TopologyReport& r) {
  EdgeTable t;
  if (orientation_graph) t.adj.resize(triangle_count);
  for (std::size_t s = 0; s < he.size();) {
    std::size_t e = s;
    while (e < he.size() && he[e].lo == he[s].lo && he[e].hi == he[s].hi) ++e;
    const std::size_t n = e - s;
    t.edge_start.push_back(s);
    t.edge_size.push_back(n);
    if (n == 1) t.boundary.push_back({he[s].lo, he[s].hi});
    if (n > 2) ++r.nonmanifold_edges;
    if (n == 2) {
      const bool same_way = he[s].forward == he[s + 1].forward;
      if (same_way) ++r.misoriented_edges;
      if (orientation_graph) {
        t.adj[he[s].tri].push_back({he[s + 1].tri, same_way});
        t.adj[he[s + 1].tri].push_back({he[s].tri, same_way});
      }
    }
    for (std::size_t k = s + 1; k < e; ++k) {
      comp.unite(he[s].tri, he[k].tri);
      corners.unite(3 * std::size_t{he[s].tri} + he[s].corner_lo, 3 * std::size_t{he[k].tri} + he[k].corner_lo);
      corners.unite(3 * std::size_t{he[s].tri} + he[s].corner_hi, 3 * std::size_t{he[k].tri} + he[k].corner_hi);
    }
    s = e;
  }
  return t;
}

// Orientation: propagates a flip parity over two-triangle edges; the minority of each patch is
// "against its neighbours" (r.flipped_triangles); a contradiction clears r.orientable.
void check_orientation(const std::vector<std::size_t>& tris, const EdgeTable& edges, TopologyReport& r) {
  std::vector<int> parity(edges.adj.size(), -1);
  std::vector<std::size_t> stack;
  for (std::size_t seed : tris) {
    if (parity[seed] >= 0) continue;
    std::size_t count[2] = {0, 0};
    parity[seed] = 0;
    stack.push_back(seed);
    while (!stack.empty()) {
      const std::size_t t = stack.back();
      stack.pop_back();
      ++count[parity[t]];
      for (const auto& [u, flip] : edges.adj[t]) {
        const int want = parity[t] ^ static_cast<int>(flip);
        if (parity[u] < 0) {
          parity[u] = want;
          stack.push_back(u);
        } else if (parity[u] != want) {
          r.orientable = false;
        }
      }
    }
    r.flipped_triangles += std::min(count[0], count[1]);
  }
}

// Vertex manifoldness: the triangles around a vertex must form one fan, i.e. their corners at it be
// joined through the edges incident to it (scan_edges). Returns the number of vertices that fail.
std::size_t count_nonmanifold_vertices(const TriangleMesh& mesh, const std::vector<std::size_t>& tris,
                                       DisjointSets<std::uint32_t>& corners) {
  std::vector<std::size_t> first_root(mesh.positions.size(), SIZE_MAX);
  std::vector<char> bad(mesh.positions.size(), 0);
  std::size_t nonmanifold = 0;
  for (std::size_t i : tris)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.triangles[i][k];
      const std::size_t root = corners.find(3 * i + k);
      if (first_root[v] == SIZE_MAX) {
        first_root[v] = root;
      } else if (first_root[v] != root && !bad[v]) {
        bad[v] = 1;
        ++nonmanifold;
      }
    }
  return nonmanifold;
}

// Creates r.components (numbered by first triangle) with their triangle counts; returns each
// triangle's component.
std::vector<std::size_t> assign_components(const std::vector<std::size_t>& tris, std::size_t triangle_count,
                                           UnionFind& comp, TopologyReport& r) {
  std::vector<std::size_t> comp_of(triangle_count, 0);
  std::vector<long> comp_index(triangle_count, -1);
  for (std::size_t i : tris) {
    const std::size_t root = comp.find(i);
    if (comp_index[root] < 0) {
      comp_index[root] = static_cast<long>(r.components.size());
      r.components.emplace_back();
    }
    comp_of[i] = static_cast<std::size_t>(comp_index[root]);
    ++r.components[comp_of[i]].triangles;
  }
  return comp_of;
}

// Counts each component's edges, vertices (a vertex shared by two components counts in both) and
// boundary loops (connected groups of boundary edges); returns per component whether its edges are manifold.
std::vector<char> count_component_elements(const TriangleMesh& mesh, const std::vector<std::size_t>& tris,
                                           const std::vector<HalfEdge>& he, const EdgeTable& edges,
                                           const std::vector<std::size_t>& comp_of, TopologyReport& r) {
  std::vector<char> comp_manifold(r.components.size(), 1);
  for (std::size_t k = 0; k < edges.edge_start.size(); ++k) {
    const std::size_t c = comp_of[he[edges.edge_start[k]].tri];
    ++r.components[c].edges;
    if (edges.edge_size[k] > 2) comp_manifold[c] = 0;
  }
  std::vector<std::pair<std::size_t, std::uint32_t>> cv;
  cv.reserve(3 * tris.size());
  for (std::size_t i : tris)
    for (std::uint32_t v : mesh.triangles[i]) cv.push_back({comp_of[i], v});
  std::sort(cv.begin(), cv.end());
  cv.erase(std::unique(cv.begin(), cv.end()), cv.end());
  for (const auto& [c, v] : cv) ++r.components[c].vertices;
  UnionFind bl(mesh.positions.size());
  for (const auto& [a, b] : edges.boundary) bl.unite(a, b);
  std::vector<std::pair<std::size_t, std::size_t>> loop_roots;  // (component, root vertex)
  for (std::size_t k = 0; k < edges.edge_start.size(); ++k)
    if (edges.edge_size[k] == 1)
      loop_roots.push_back({comp_of[he[edges.edge_start[k]].tri], bl.find(he[edges.edge_start[k]].lo)});
  std::sort(loop_roots.begin(), loop_roots.end());
  loop_roots.erase(std::unique(loop_roots.begin(), loop_roots.end()), loop_roots.end());
  for (const auto& [c, root] : loop_roots) ++r.components[c].boundary_loops;
  return comp_manifold;
}

// Each component's Euler characteristic and genus (χ = 2 − 2g − b), and their sum in r.genus.
void component_genus(const std::vector<char>& comp_manifold, TopologyReport& r) {
  r.genus = (r.nonmanifold_vertices == 0 && r.orientable) ? 0 : -1;
  for (std::size_t c = 0; c < r.components.size(); ++c) {
    ComponentTopology& ct = r.components[c];
    ct.euler = static_cast<long>(ct.vertices) - static_cast<long>(ct.edges) + static_cast<long>(ct.triangles);
    const long twice_genus = 2 - ct.euler - static_cast<long>(ct.boundary_loops);
    if (comp_manifold[c] && r.nonmanifold_vertices == 0 && r.orientable && twice_genus >= 0 && twice_genus % 2 == 0)
      ct.genus = static_cast<int>(twice_genus / 2);
    if (ct.genus < 0 || r.genus < 0)
      r.genus = -1;
    else
      r.genus += ct.genus;
  }
}

// Signed volume over the valid triangles (divergence theorem, centred for conditioning).
double signed_volume(const TriangleMesh& mesh, const std::vector<std::size_t>& tris) {
  const std::size_t nv = mesh.positions.size();
  Vec3 ref{};
  for (const Vec3& p : mesh.positions) ref += p;
  if (nv > 0) ref = ref / static_cast<double>(nv);
  double v = 0.0;
  for (std::size_t i : tris) {
    const Triangle& t = mesh.triangles[i];
    v += dot(mesh.positions[t[0]] - ref, cross(mesh.positions[t[1]] - ref, mesh.positions[t[2]] - ref));
  }
  return v / 6.0;
}

// The faults of r, in words, appended to r.faults.
void describe_faults(TopologyReport& r, const std::vector<std::pair<std::size_t, std::size_t>>& first_pairs) {
  auto& f = r.faults;
  if (r.invalid_triangles > 0)
    f.push_back(plural(r.invalid_triangles, "invalid triangle", "invalid triangles") +
                " (vertex index out of range or repeated); ignored by the other checks");
  if (r.boundary_edges > 0) {
    std::size_t loops = 0;
    for (const ComponentTopology& c : r.components) loops += c.boundary_loops;
    f.push_back(plural(r.boundary_edges, "boundary edge", "boundary edges") + " (" +
                (loops == 1 ? std::string("a hole") : fmt::format("{} holes", loops)) + "): the mesh is not closed");
  }
  if (r.nonmanifold_edges > 0)
    f.push_back(plural(r.nonmanifold_edges, "non-manifold edge", "non-manifold edges") +
                " (shared by more than two triangles)");
  if (r.nonmanifold_vertices > 0)
    f.push_back(plural(r.nonmanifold_vertices, "non-manifold vertex", "non-manifold vertices") +
                " (its triangles form several separate fans)");
  if (r.flipped_triangles > 0)
    f.push_back(fmt::format("{} oriented against {} neighbours ({} traversed the same way by both triangles)",
                            plural(r.flipped_triangles, "triangle", "triangles"),
                            r.flipped_triangles == 1 ? "its" : "their", plural(r.misoriented_edges, "edge", "edges")));
  else if (r.misoriented_edges > 0 || !r.orientable)
    f.push_back(fmt::format("no consistent orientation exists ({} traversed the same way by both triangles)",
                            plural(r.misoriented_edges, "edge", "edges")));
  if (r.closed() && r.edge_manifold() && r.consistently_oriented() && !(r.signed_volume > 0.0))
    f.push_back(fmt::format("the triangles face inward (signed volume {:.6g} mm³ <= 0)", r.signed_volume));
  if (r.degenerate_triangles > 0)
    f.push_back(plural(r.degenerate_triangles, "degenerate triangle", "degenerate triangles") + " (zero area)");
  if (r.duplicate_triangles > 0)
    f.push_back(plural(r.duplicate_triangles, "duplicate triangle", "duplicate triangles") + " (same three vertices)");
  if (r.duplicate_vertices > 0)
    f.push_back(plural(r.duplicate_vertices, "duplicate vertex", "duplicate vertices") +
                " (same position as another vertex)");
  if (r.unreferenced_vertices > 0)
    f.push_back(plural(r.unreferenced_vertices, "unreferenced vertex", "unreferenced vertices") +
                " (used by no triangle)");
  if (r.self_intersections > 0) {
    std::string list;
    for (const auto& [i, j] : first_pairs) list += fmt::format("{}{}–{}", list.empty() ? "" : ", ", i, j);
    f.push_back(
        fmt::format("{} of triangles intersect (first: {})", plural(r.self_intersections, "pair", "pairs"), list));
  }
}

}  // namespace

TopologyReport check_topology(const TriangleMesh& mesh, const TopologyOptions& options) {
  TopologyReport r;
  r.vertices = mesh.positions.size();
  r.triangles = mesh.triangles.size();
  if (mesh.triangles.empty()) {
    r.faults.push_back("the mesh has no triangles");
    r.genus = -1;
    return r;
  }
  // Triangles and corners are numbered in 32 bits (half the memory traffic of the sorts and the
  // disjoint sets); such a mesh would take more than 17 GB of triangles alone.
  if (mesh.triangles.size() > UINT32_MAX / 3)
    throw std::length_error(fmt::format("check_topology: more than {} triangles", UINT32_MAX / 3));
  const bool full = !options.counts_only;
  const std::vector<std::size_t> tris = check_triangles(mesh, full, r);  // the valid triangles
  if (full) r.duplicate_vertices = count_duplicate_vertices(mesh);

  // Edges, and components and vertex fans through them.
  const std::vector<HalfEdge> he = sorted_half_edges(mesh, tris);
  UnionFind comp(mesh.triangles.size());
  DisjointSets<std::uint32_t> corners(3 * mesh.triangles.size());
  const EdgeTable edges = scan_edges(he, mesh.triangles.size(), full, comp, corners, r);
  r.edges = edges.edge_start.size();
  r.boundary_edges = edges.boundary.size();
  r.euler = static_cast<long>(r.vertices - r.unreferenced_vertices) - static_cast<long>(r.edges) +
            static_cast<long>(tris.size());
  if (full) check_orientation(tris, edges, r);
  r.nonmanifold_vertices = count_nonmanifold_vertices(mesh, tris, corners);

  // Components with their Euler characteristic and boundary loops.
  const std::vector<std::size_t> comp_of = assign_components(tris, mesh.triangles.size(), comp, r);
  if (full) {
    const std::vector<char> comp_manifold = count_component_elements(mesh, tris, he, edges, comp_of, r);
    component_genus(comp_manifold, r);
  }

  r.signed_volume = signed_volume(mesh, tris);
  std::vector<std::pair<std::size_t, std::size_t>> first_pairs;
  if (options.self_intersections) {
    r.self_intersections = count_self_intersections(mesh, &first_pairs, 3);
    r.self_intersections_checked = true;
  }
  describe_faults(r, first_pairs);
  return r;
}

}  // namespace c4d
