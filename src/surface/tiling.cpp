// Tiling between two contours of adjacent slices: Lim et al. 2014, "Reconstruction from Segmented
// Contour Lines" (after Barequet & Sharir 1996). We tile each connected pair with the optimal
// band of Fuchs, Kedem & Uselton 1977 (shortest spanning edges, dynamic programming): every
// triangle has vertices on both slices, so none is flat and no collapsed pair can form. Branching
// (1→n, n→1) merges the n contours into one chain through bridges whose interior is lifted towards
// the other slice (Meyers, Skinner & Sloan 1992), which yields the saddle of the paper's ridge.
#include "contour4d/surface/tiling.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace c4d {

namespace {

// Optimal band path (Fuchs, Kedem & Uselton): the states (i, j) from (0, 0) to (n, m), lower index i
// modulo n, upper index j0 + j modulo m; consecutive states differ by one step on one chain.
struct BandPath {
  std::size_t i0 = 0, j0 = 0;  // lower index i means lower[(i0 + i) % n], upper j means upper[(j0 + j) % m]
  double cost = std::numeric_limits<double>::infinity();
  std::vector<std::pair<std::size_t, std::size_t>> states;
};

// The optimal path from the spanning edge (lower[i0], upper[j0]) around the band; empty states when
// the groups allow none.
BandPath band_path_from(const std::vector<std::uint32_t>& lower, const std::vector<std::uint32_t>& upper,
                        const std::vector<Vec3>& positions, const std::vector<int>& lower_group,
                        const std::vector<int>& upper_group, std::size_t i0, std::size_t j0) {
  BandPath out;
  out.i0 = i0;
  out.j0 = j0;
  const std::size_t n = lower.size(), m = upper.size();
  const bool grouped = lower_group.size() == n && upper_group.size() == m;
  // The chains' points in path order (index n is index 0 again, as m is), and their groups.
  std::vector<Vec3> L(n + 1), U(m + 1);
  std::vector<int> lg(n + 1, -1), ug(m + 1, -1);
  for (std::size_t i = 0; i <= n; ++i) {
    L[i] = positions[lower[(i0 + i) % n]];
    if (grouped) lg[i] = lower_group[(i0 + i) % n];
  }
  for (std::size_t j = 0; j <= m; ++j) {
    U[j] = positions[upper[(j0 + j) % m]];
    if (grouped) ug[j] = upper_group[(j0 + j) % m];
  }
  auto allowed = [&](std::size_t i, std::size_t j) { return lg[i] < 0 || ug[j] < 0 || lg[i] == ug[j]; };
  const std::size_t W = m + 1;
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<double> cost((n + 1) * W, inf);
  std::vector<char> from((n + 1) * W, 0);  // 1: came by advancing lower, 2: by advancing upper
  if (!allowed(0, 0)) return out;
  // Pruning (exact: the path found is the full programme's, to the bit). A greedy path's cost bounds
  // the optimum; every step still to come adds a spanning edge at least `gap` long (the chains'
  // separation along the line between their centroids, which no spanning edge can undercut); a state
  // whose cost plus that floor exceeds the bound (with a 1e-9 margin for the rounding of the sums) lies
  // on no optimal path and is left out. Rows of a band are parallel chains: the states kept form a
  // narrow corridor along the diagonal.
  double bound = inf, gap = 0.0;
  {
    Vec3 cl{}, cu{};
    for (std::size_t i = 0; i < n; ++i) cl += L[i];
    for (std::size_t j = 0; j < m; ++j) cu += U[j];
    const Vec3 axis = cu / static_cast<double>(m) - cl / static_cast<double>(n);
    const double len = norm(axis);
    if (len > 0 && std::isfinite(len)) {
      const Vec3 a = axis / len;
      double lo_top = inf, hi_bottom = -inf;
      for (std::size_t i = 0; i < n; ++i) hi_bottom = std::max(hi_bottom, dot(a, L[i]));
      for (std::size_t j = 0; j < m; ++j) lo_top = std::min(lo_top, dot(a, U[j]));
      if (std::isfinite(lo_top - hi_bottom)) gap = std::max(0.0, lo_top - hi_bottom) * (1.0 - 1e-6);
    }
    // The greedy path: the shorter next spanning edge, within the groups.
    std::size_t i = 0, j = 0;
    double c = 0.0;
    while (i < n || j < m) {
      const bool can_l = i < n && allowed(i + 1, j), can_u = j < m && allowed(i, j + 1);
      if (!can_l && !can_u) break;
      const double dl = can_l ? distance(L[i + 1], U[j]) : inf, du = can_u ? distance(L[i], U[j + 1]) : inf;
      if (dl <= du) {
        c += dl;
        ++i;
      } else {
        c += du;
        ++j;
      }
    }
    if (i == n && j == m) bound = c;
  }
  auto pruned = [&](double c, std::size_t i, std::size_t j) {
    return (c + static_cast<double>(n - i + m - j) * gap) * (1.0 - 1e-9) > bound;
  };
  cost[0] = 0.0;
  // Both ways into state (i, j) add the spanning edge (L(i), U(j)): it is measured once per state.
  // The lower step is tried first and the upper one taken only when strictly cheaper. Row i's states
  // start where row i − 1's first kept state is (none before it can be reached) and end where a state
  // is neither reached from row i − 1 nor from its left.
  std::size_t first = 0, last = 0;  // row i − 1's kept states
  for (std::size_t i = 0; i <= n; ++i) {
    std::size_t row_first = W, row_last = 0;
    for (std::size_t j = i == 0 ? 0 : first; j <= m; ++j) {
      if (i > 0 && j > last && !(j > 0 && cost[i * W + j - 1] < inf)) break;
      if (i == 0 && j == 0) {  // the start, cost 0
        row_first = row_last = 0;
        continue;
      }
      if (!allowed(i, j)) continue;
      const double by_lower = i > 0 ? cost[(i - 1) * W + j] : inf, by_upper = j > 0 ? cost[i * W + j - 1] : inf;
      if (!(by_lower < inf) && !(by_upper < inf)) continue;
      const double d = distance(L[i], U[j]);
      double c = inf;
      char came = 0;
      if (by_lower < inf) {
        c = by_lower + d;
        came = 1;
      }
      if (by_upper < inf && by_upper + d < c) {
        c = by_upper + d;
        came = 2;
      }
      if (pruned(c, i, j)) continue;
      cost[i * W + j] = c;
      from[i * W + j] = came;
      row_first = std::min(row_first, j);
      row_last = j;
    }
    if (row_first == W) break;  // no state of this row is kept: (n, m) cannot be reached
    first = row_first;
    last = row_last;
  }
  out.cost = cost[n * W + m];
  if (!(out.cost < std::numeric_limits<double>::infinity())) return out;
  std::size_t i = n, j = m;
  out.states.push_back({i, j});
  while (i > 0 || j > 0) {
    if (from[i * W + j] == 1)
      --i;
    else
      --j;
    out.states.push_back({i, j});
  }
  std::reverse(out.states.begin(), out.states.end());
  return out;
}

// Entries whose vertex appears once in the chain, with neighbours that appear once (not on a bridge).
std::vector<char> plain_entries(const std::vector<std::uint32_t>& chain) {
  std::vector<std::uint32_t> sorted = chain;
  std::sort(sorted.begin(), sorted.end());
  auto once = [&](std::uint32_t v) {
    const auto r = std::equal_range(sorted.begin(), sorted.end(), v);
    return r.second - r.first == 1;
  };
  const std::size_t n = chain.size();
  std::vector<char> out(n, 0);
  for (std::size_t k = 0; k < n; ++k)
    out[k] = once(chain[k]) && once(chain[(k + 1) % n]) && once(chain[(k + n - 1) % n]);
  return out;
}

// Optimal band (Fuchs, Kedem & Uselton): starts on lower[0] and its nearest upper vertex. Bridged
// chains (repeated vertices) start on a plain entry instead, and the best of the few nearest upper
// starts is taken: a start on a bridge end is ambiguous (both sides of the bridge meet it).
BandPath band_path(const std::vector<std::uint32_t>& lower, const std::vector<std::uint32_t>& upper,
                   const std::vector<Vec3>& positions, const std::vector<int>& lower_group = {},
                   const std::vector<int>& upper_group = {}) {
  const std::size_t n = lower.size(), m = upper.size();
  const bool grouped = lower_group.size() == n && upper_group.size() == m;
  const std::vector<char> lp = plain_entries(lower), up = plain_entries(upper);
  const bool bridged = std::find(lp.begin(), lp.end(), 0) != lp.end() || std::find(up.begin(), up.end(), 0) != up.end();
  std::size_t i0 = 0;
  if (bridged)
    for (std::size_t k = 0; k < n; ++k)
      if (lp[k]) {
        i0 = k;
        break;
      }
  std::vector<std::pair<double, std::size_t>> starts;
  for (std::size_t j = 0; j < m; ++j) {
    if (grouped && lower_group[i0] >= 0 && upper_group[j] >= 0 && lower_group[i0] != upper_group[j]) continue;
    if (bridged && !up[j]) continue;
    starts.push_back({distance(positions[lower[i0]], positions[upper[j]]), j});
  }
  if (starts.empty())
    for (std::size_t j = 0; j < m; ++j) starts.push_back({distance(positions[lower[i0]], positions[upper[j]]), j});
  const std::size_t tries = bridged ? std::min<std::size_t>(5, starts.size()) : 1;
  std::partial_sort(starts.begin(), starts.begin() + static_cast<std::ptrdiff_t>(tries), starts.end());
  BandPath best;
  for (std::size_t t = 0; t < tries; ++t) {
    BandPath p = band_path_from(lower, upper, positions, lower_group, upper_group, i0, starts[t].second);
    if (!p.states.empty() && p.cost < best.cost) best = std::move(p);
  }
  return best;
}

}  // namespace

std::vector<Triangle> tile_chains(const std::vector<std::uint32_t>& lower, const std::vector<std::uint32_t>& upper,
                                  const std::vector<Vec3>& positions) {
  return tile_chains(lower, upper, positions, {}, {});
}

std::vector<Triangle> tile_chains(const std::vector<std::uint32_t>& lower, const std::vector<std::uint32_t>& upper,
                                  const std::vector<Vec3>& positions, const std::vector<int>& lower_group,
                                  const std::vector<int>& upper_group) {
  const std::size_t n = lower.size(), m = upper.size();
  std::vector<Triangle> out;
  if (n == 0 || m == 0) return out;
  BandPath path = band_path(lower, upper, positions, lower_group, upper_group);
  if (path.states.empty()) path = band_path(lower, upper, positions);  // no tiling respects the groups
  if (path.states.empty()) return out;
  auto L = [&](std::size_t i) { return lower[(path.i0 + i) % n]; };
  auto U = [&](std::size_t j) { return upper[(path.j0 + j) % m]; };
  out.reserve(n + m);
  for (std::size_t k = path.states.size() - 1; k > 0; --k) {
    const auto [i1, j1] = path.states[k];
    const auto [i, j] = path.states[k - 1];
    if (i1 != i)
      out.push_back({L(i), L(i1), U(j)});
    else
      out.push_back({L(i), U(j1), U(j)});
  }
  return out;
}

RowPlan plan_rows(const std::vector<std::uint32_t>& lower, const std::vector<std::uint32_t>& upper,
                  const std::vector<Vec3>& positions, double spacing) {
  RowPlan plan;
  const std::size_t n = lower.size(), m = upper.size();
  if (n < 3 || m < 3 || !(spacing > 0)) return plan;
  const BandPath path = band_path(lower, upper, positions);
  if (path.states.empty()) return plan;
  const std::size_t spans = path.states.size() - 1;  // n + m spanning edges, the last equals the first
  plan.i0 = path.i0;
  plan.j0 = path.j0;
  for (std::size_t k = 0; k < spans; ++k)
    plan.spans.emplace_back(static_cast<std::uint32_t>(path.states[k].first),
                            static_cast<std::uint32_t>(path.states[k].second));
  // The band's width across: its spanning edges' mean length (the slant height, not the slices' gap: a
  // band between contours of very different size lies nearly flat).
  double across = 0.0;
  for (const auto& [i, j] : plan.spans)
    across += distance(positions[lower[(plan.i0 + i) % n]], positions[upper[(plan.j0 + j) % m]]);
  plan.intervals = static_cast<int>(std::lround(across / static_cast<double>(spans) / spacing));
  for (int r = 1; r < plan.intervals; ++r) {
    const double t = static_cast<double>(r) / plan.intervals;
    plan.counts.push_back(std::max<std::size_t>(
        3, static_cast<std::size_t>(std::lround((1.0 - t) * static_cast<double>(n) + t * static_cast<double>(m)))));
  }
  return plan;
}

std::vector<std::vector<Vec3>> rows_on_plan(const RowPlan& plan, const std::vector<std::uint32_t>& lower,
                                            const std::vector<std::uint32_t>& upper,
                                            const std::vector<Vec3>& positions) {
  std::vector<std::vector<Vec3>> rows;
  const std::size_t n = lower.size(), m = upper.size(), spans = plan.spans.size();
  if (plan.intervals < 2 || spans < 2) return rows;
  for (int r = 1; r < plan.intervals; ++r) {
    const double t = static_cast<double>(r) / plan.intervals;
    std::vector<Vec3> q(spans);
    std::vector<double> cum(spans + 1, 0.0);
    for (std::size_t k = 0; k < spans; ++k) {
      const auto [i, j] = plan.spans[k];
      q[k] = (1.0 - t) * positions[lower[(plan.i0 + i) % n]] + t * positions[upper[(plan.j0 + j) % m]];
      if (k > 0) cum[k] = cum[k - 1] + distance(q[k - 1], q[k]);
    }
    cum[spans] = cum[spans - 1] + distance(q[spans - 1], q[0]);
    const double total = cum[spans];
    const std::size_t count = plan.counts[static_cast<std::size_t>(r - 1)];
    std::vector<Vec3> row;
    row.reserve(count);
    std::size_t seg = 0;
    for (std::size_t c = 0; c < count; ++c) {
      const double s = total * static_cast<double>(c) / static_cast<double>(count);
      while (seg + 1 < spans && cum[seg + 1] <= s) ++seg;
      const double len = cum[seg + 1] - cum[seg];
      const double f = len > 0 ? (s - cum[seg]) / len : 0.0;
      row.push_back(q[seg] + f * (q[(seg + 1) % spans] - q[seg]));
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

std::vector<std::vector<Vec3>> interpolate_rows(const std::vector<std::uint32_t>& lower,
                                                const std::vector<std::uint32_t>& upper,
                                                const std::vector<Vec3>& positions, double spacing) {
  return rows_on_plan(plan_rows(lower, upper, positions, spacing), lower, upper, positions);
}

std::vector<std::uint32_t> bridge_chains(const std::vector<std::uint32_t>& a, std::size_t x_at,
                                         const std::vector<std::uint32_t>& b, std::size_t y_at,
                                         const std::vector<std::uint32_t>& bridge) {
  std::vector<std::uint32_t> out;
  out.reserve(a.size() + b.size() + 2 * bridge.size() + 2);
  for (std::size_t k = 0; k <= x_at; ++k) out.push_back(a[k]);
  out.insert(out.end(), bridge.begin(), bridge.end());
  for (std::size_t k = 0; k <= b.size(); ++k) out.push_back(b[(y_at + k) % b.size()]);
  out.insert(out.end(), bridge.rbegin(), bridge.rend());
  for (std::size_t k = x_at; k < a.size(); ++k) out.push_back(a[k]);
  return out;
}

}  // namespace c4d
