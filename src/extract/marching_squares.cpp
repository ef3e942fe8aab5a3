// Marching squares on a 2D field, the sub-pixel fit of a mask's staircase, Taubin smoothing and
// arc-length resampling of the chains.
//
// References: Miara et al., "New Method for 4D Reconstruction of Medical Images", §III.B
// (contour extraction as an ordered chain of points); W. E. Lorensen, H. E. Cline, "Marching
// cubes", SIGGRAPH 1987 (the 2D case table); G. Taubin, "A signal processing approach to fair
// surface design", SIGGRAPH 1995 (λ|μ smoothing without shrinkage); W. S. Cleveland, "Robust
// locally weighted regression and smoothing scatterplots", JASA 1979 (local polynomial fits with a
// tricube kernel, which have no curvature bias); R. Whitaker, "Reducing aliasing artifacts in
// iso-surfaces of binary volumes", VolVis 2000, and V. Lempitsky, "Surface extraction from binary
// volumes with higher-order smoothness", CVPR 2010 (a smooth boundary must stay consistent with the
// binary samples: here, cross each traced edge between its two pixel centres).
#include "contour4d/extract/marching_squares.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <cstddef>

namespace c4d {
namespace {

// Crossing points live on cell edges. Edge ids: 2·(x + W·y) for the horizontal edge from pixel
// (x, y) to (x + 1, y), 2·(x + W·y) + 1 for the vertical edge from (x, y) to (x, y + 1), on the
// field padded by one outside pixel on each side (W = width + 2).
struct Padded {
  int w = 0, h = 0;
  std::vector<float> v;
  float at(int x, int y) const { return v[static_cast<std::size_t>(x) + static_cast<std::size_t>(w) * y]; }
};

Padded pad(const std::vector<float>& field, int width, int height, float level) {
  Padded p;
  p.w = width + 2;
  p.h = height + 2;
  // Outside pixels count as 0 (background of a mask), or sit below a level <= 0.
  const float outside = level > 0.0f ? 0.0f : level - 1.0f;
  p.v.assign(static_cast<std::size_t>(p.w) * p.h, outside);
  for (int y = 0; y < height; ++y)
    std::copy_n(field.begin() + static_cast<std::ptrdiff_t>(y) * width, width,
                p.v.begin() + static_cast<std::ptrdiff_t>(y + 1) * p.w + 1);
  return p;
}

}  // namespace

std::vector<std::vector<Vec2>> marching_squares(const std::vector<float>& field, int width, int height, float level) {
  std::vector<std::vector<Vec2>> chains;
  if (width <= 0 || height <= 0 || field.size() < static_cast<std::size_t>(width) * height) return chains;
  const Padded p = pad(field, width, height, level);
  const int W = p.w, H = p.h;
  auto id_h = [W](int x, int y) { return 2 * (x + W * y); };
  auto id_v = [W](int x, int y) { return 2 * (x + W * y) + 1; };
  // next[e]: the crossing that follows crossing e along its chain (inside on the left), -1 if none.
  std::vector<int> next(static_cast<std::size_t>(2) * W * H, -1);

  for (int y = 0; y + 1 < H; ++y) {
    for (int x = 0; x + 1 < W; ++x) {
      // Corners counter-clockwise (x right, y up): p0 (x,y), p1 (x+1,y), p2 (x+1,y+1), p3 (x,y+1).
      const float f[4] = {p.at(x, y), p.at(x + 1, y), p.at(x + 1, y + 1), p.at(x, y + 1)};
      const bool in[4] = {f[0] > level, f[1] > level, f[2] > level, f[3] > level};
      const int n_in = in[0] + in[1] + in[2] + in[3];
      if (n_in == 0 || n_in == 4) continue;
      // Edge k runs from corner k to corner k+1 around the cell.
      const int edge[4] = {id_h(x, y), id_v(x + 1, y), id_h(x, y + 1), id_v(x, y)};
      // Walking the cell boundary counter-clockwise, an "exit" goes inside -> outside and an
      // "entry" outside -> inside. The chain through this cell runs from an exit to an entry.
      int exits[2], entries[2], ne = 0, nn = 0;
      for (int k = 0; k < 4; ++k) {
        const bool a = in[k], b = in[(k + 1) % 4];
        if (a && !b) exits[ne++] = k;
        if (!a && b) entries[nn++] = k;
      }
      if (ne == 1) {
        next[edge[exits[0]]] = edge[entries[0]];
        continue;
      }
      // Saddle: two exits, two entries alternating. Joined inside corners pair each exit with the
      // next entry counter-clockwise; separated ones with the previous entry.
      const bool join = 0.25f * (f[0] + f[1] + f[2] + f[3]) > level;
      for (int a = 0; a < 2; ++a) {
        const int e = exits[a];
        auto gap = [&](int b) { return join ? (entries[b] - e + 4) % 4 : (e - entries[b] + 4) % 4; };
        const int best = gap(0) < gap(1) ? 0 : 1;
        next[edge[e]] = edge[entries[best]];
      }
    }
  }

  auto crossing = [&](int id) -> Vec2 {
    const int cell = id / 2;
    const int x = cell % W, y = cell / W;
    const bool vertical = (id & 1) != 0;
    const float a = p.at(x, y);
    const float b = vertical ? p.at(x, y + 1) : p.at(x + 1, y);
    const double t = std::clamp(static_cast<double>(level - a) / static_cast<double>(b - a), 0.0, 1.0);
    // Padded pixel (x, y) is field pixel (x - 1, y - 1).
    return vertical ? Vec2{x - 1.0, y - 1.0 + t} : Vec2{x - 1.0 + t, y - 1.0};
  };

  std::vector<char> seen(next.size(), 0);
  for (std::size_t s = 0; s < next.size(); ++s) {
    if (next[s] < 0 || seen[s]) continue;
    std::vector<Vec2> chain;
    int e = static_cast<int>(s);
    while (e >= 0 && !seen[static_cast<std::size_t>(e)]) {
      seen[static_cast<std::size_t>(e)] = 1;
      chain.push_back(crossing(e));
      e = next[static_cast<std::size_t>(e)];
    }
    if (chain.size() >= 3) chains.push_back(std::move(chain));
  }
  return chains;
}

void smooth_closed_taubin(std::vector<Vec2>& polyline, int passes, double lambda, double mu) {
  const std::size_t n = polyline.size();
  if (n < 3 || passes <= 0) return;
  std::vector<Vec2> tmp(n);
  auto step = [&](double factor) {
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 prev = polyline[(i + n - 1) % n], next = polyline[(i + 1) % n];
      const Vec2 lap = 0.5 * (prev + next) - polyline[i];
      tmp[i] = polyline[i] + factor * lap;
    }
    polyline.swap(tmp);
  };
  for (int k = 0; k < passes; ++k) {
    step(lambda);
    step(mu);
  }
}

namespace {

// The staircase and what is known of each vertex: its position (mm), the direction of its grid
// edge and the variance of the true crossing along that edge (mm²); and the fit's limits.
struct Staircase {
  std::vector<Vec2> c, e;
  std::vector<double> var_along;
  double floor_var = 0.0;   // no vertex pins the curve tighter than this (mm²)
  double max_window = 0.0;  // largest half-window (mm of arc)
  double cos_turn = 0.0;    // the window stops where the tangent has turned this much
};

// The chain in mm, with each vertex's edge direction and uncertainty.
Staircase staircase(const std::vector<Vec2>& chain, Vec2 sp) {
  const std::size_t n = chain.size();
  Staircase s;
  s.c.resize(n);
  s.e.resize(n);
  s.var_along.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.c[i] = {chain[i].x * sp.x, chain[i].y * sp.y};
    // On a 0/1 field every crossing is an edge midpoint: x is whole on vertical edges.
    const bool vertical = chain[i].x == std::floor(chain[i].x);
    s.e[i] = vertical ? Vec2{0, 1} : Vec2{1, 0};
    const double half = 0.5 * (vertical ? sp.y : sp.x);
    s.var_along[i] = half * half / 3.0;  // uniform over the edge
  }
  return s;
}

// Unit tangents of the closed polyline cur (central differences).
void tangents(const std::vector<Vec2>& cur, std::vector<Vec2>& tan) {
  const std::size_t n = cur.size();
  for (std::size_t i = 0; i < n; ++i) {
    Vec2 t = cur[(i + 1) % n] - cur[(i + n - 1) % n];
    const double len = norm(t);
    tan[i] = len > 0 ? (1.0 / len) * t : Vec2{1, 0};
  }
}

// The fit window around vertex i (i first): each side until `informative` vertices whose edge runs
// more along the curve than across it, the arc length reaches max_window or the curve turns too much.
void fit_window(const Staircase& s, const std::vector<Vec2>& cur, const std::vector<Vec2>& tan, std::size_t i,
                int informative, std::vector<std::size_t>& window) {
  const std::size_t n = cur.size();
  const auto sn = static_cast<std::ptrdiff_t>(n);
  auto wrap = [sn](std::ptrdiff_t k) { return static_cast<std::size_t>((k % sn + sn) % sn); };
  const Vec2 t = tan[i];
  window.assign(1, i);
  for (int dir = -1; dir <= 1; dir += 2) {
    int count = 0;
    double arc = 0;
    Vec2 prev = cur[i];
    for (std::ptrdiff_t k = 1; k < static_cast<std::ptrdiff_t>(n / 2); ++k) {
      const std::size_t j = wrap(static_cast<std::ptrdiff_t>(i) + dir * k);
      arc += norm(cur[j] - prev);
      prev = cur[j];
      if (arc > s.max_window || dot(tan[j], t) < s.cos_turn) break;
      window.push_back(j);
      const Vec2 nj{-tan[j].y, tan[j].x};
      if (std::abs(dot(s.e[j], nj)) < 0.7071) ++count;
      if (count >= informative) break;
    }
  }
}

// A local fit v = Σ sol[m] u^m over the tangent frame (origin, t, nn) of a vertex.
struct LocalFit {
  Vec2 origin, t, nn;
  double umax = 0;
  double sol[4] = {0, 0, 0, 0};
  double at(double u) const { return sol[0] + u * (sol[1] + u * (sol[2] + u * sol[3])); }
  double slope(double u) const { return sol[1] + u * (2 * sol[2] + 3 * sol[3] * u); }
};

// Weighted least squares v = Σ sol[m] u^m (m <= nb - 1) over the window: each vertex counts by the
// inverse of its uncertainty across the curve, which lies along its edge. Fills fit.umax and the
// normal equations M (nb rows, right-hand side in column nb), in scaled powers (u / umax)^m.
void normal_equations(const Staircase& s, const std::vector<Vec2>& tan, const std::vector<std::size_t>& window, int nb,
                      LocalFit& fit, double (&M)[4][5]) {
  double umax = 0;
  for (std::size_t j : window) umax = std::max(umax, std::abs(dot(s.c[j] - fit.origin, fit.t)));
  umax = 1.05 * umax + 1e-12;
  fit.umax = umax;
  for (std::size_t j : window) {
    const Vec2 d = s.c[j] - fit.origin;
    const double u = dot(d, fit.t), v = dot(d, fit.nn);
    const Vec2 nj{-tan[j].y, tan[j].x};
    const double en = dot(s.e[j], nj);
    const double z = std::min(1.0, std::abs(u) / umax), k3 = 1 - z * z * z;
    const double w = k3 * k3 * k3 / (s.var_along[j] * en * en + s.floor_var);
    // Scaled powers (u / umax)^m keep the system well conditioned.
    double bvec[4] = {1, u / umax, 0, 0};
    for (int m = 2; m < 4; ++m) bvec[m] = bvec[m - 1] * bvec[1];
    for (int aa = 0; aa < nb; ++aa) {
      M[aa][nb] += w * bvec[aa] * v;
      for (int bb = 0; bb < nb; ++bb) M[aa][bb] += w * bvec[aa] * bvec[bb];
    }
  }
}

// Solves M (Gaussian elimination with partial pivoting) into fit.sol, unscaled; false when singular.
bool solve_fit(double (&M)[4][5], int nb, LocalFit& fit) {
  const double scale = M[0][0];
  for (int col = 0; col < nb; ++col) {
    int piv = col;
    for (int rr = col + 1; rr < nb; ++rr)
      if (std::abs(M[rr][col]) > std::abs(M[piv][col])) piv = rr;
    if (!(std::abs(M[piv][col]) > 1e-12 * scale)) return false;
    for (int cc = 0; cc <= nb; ++cc) std::swap(M[col][cc], M[piv][cc]);
    for (int rr = 0; rr < nb; ++rr) {
      if (rr == col) continue;
      const double fct = M[rr][col] / M[col][col];
      for (int cc = col; cc <= nb; ++cc) M[rr][cc] -= fct * M[col][cc];
    }
  }
  for (int m = 0; m < nb; ++m) {
    double scale_m = 1;
    for (int k = 0; k < m; ++k) scale_m *= fit.umax;
    fit.sol[m] = M[m][nb] / M[m][m] / scale_m;
  }
  return true;
}

// The mask's own constraint: the boundary crosses each edge between its two pixel centres. A fit
// that crosses the inner half of its window outside that is the wrong model there (a flat run next
// to curved flanks, a sharp tip): false, and the window shrinks.
bool fit_consistent(const Staircase& s, const std::vector<std::size_t>& window, const LocalFit& fit, double tolerance) {
  for (std::size_t j : window) {
    const Vec2 d = s.c[j] - fit.origin;
    const double u = dot(d, fit.t), v = dot(d, fit.nn);
    if (std::abs(u) > 0.6 * fit.umax) continue;
    const double fu = fit.at(u);
    const double slope = fit.slope(u);
    const double denom = dot(s.e[j], fit.nn) - slope * dot(s.e[j], fit.t);
    if (std::abs(denom) < 0.3) continue;  // an edge nearly along the curve bounds little
    if (std::abs((fu - v) / denom) > std::sqrt(3.0 * s.var_along[j]) * (1 + tolerance)) return false;
  }
  return true;
}

// The new point of vertex i: where the fit crosses the vertex's own edge, kept between the edge's
// two pixel centres (the mask says the boundary crosses there); for an edge nearly along the curve,
// the fit's point over the vertex, kept within half an edge of the midpoint.
Vec2 refit_point(const Staircase& s, std::size_t i, const LocalFit& fit) {
  const Vec2 d = s.c[i] - fit.origin;
  const double u = dot(d, fit.t), v = dot(d, fit.nn);
  const double slope = fit.slope(u);
  const double et = dot(s.e[i], fit.t), enn = dot(s.e[i], fit.nn), denom = enn - slope * et;
  const double half = std::sqrt(3.0 * s.var_along[i]);
  if (std::abs(denom) >= 0.3) return s.c[i] + std::clamp((fit.at(u) - v) / denom, -half, half) * s.e[i];
  const Vec2 q = fit.origin + u * fit.t + fit.at(u) * fit.nn, step = q - s.c[i];
  const double len = norm(step);
  return len > half ? s.c[i] + (half / len) * step : q;
}

// Vertex i refitted around the current curve: the first consistent fit, from the widest window
// down; the edge midpoint when none is (it lies within half a pixel of the boundary).
Vec2 fit_vertex(const Staircase& s, const std::vector<Vec2>& cur, const std::vector<Vec2>& tan, std::size_t i,
                const StaircaseFitOptions& o, std::vector<std::size_t>& window) {
  LocalFit fit;
  fit.t = tan[i];
  fit.nn = {-fit.t.y, fit.t.x};
  fit.origin = cur[i];
  for (int informative = o.informative; informative >= 1; --informative) {
    fit_window(s, cur, tan, i, informative, window);
    if (window.size() < 5) break;
    const int nb = std::clamp(o.degree, 1, 3) + 1;
    double M[4][5] = {};
    normal_equations(s, tan, window, nb, fit, M);
    for (double& x : fit.sol) x = 0;
    if (!solve_fit(M, nb, fit)) continue;
    if (!fit_consistent(s, window, fit, o.tolerance)) continue;
    return refit_point(s, i, fit);
  }
  return s.c[i];
}

}  // namespace

std::vector<Vec2> fit_mask_staircase(const std::vector<Vec2>& chain, Vec2 sp, const StaircaseFitOptions& o) {
  const std::size_t n = chain.size();
  Staircase s = staircase(chain, sp);
  if (n < 5) return s.c;
  const double px = std::min(sp.x, sp.y);
  s.floor_var = (0.02 * px) * (0.02 * px);  // no vertex pins the curve tighter than 0.02 px
  s.max_window = o.max_window_px * px;
  s.cos_turn = std::cos(o.max_turn_deg * std::numbers::pi / 180.0);
  // Tangents come from the current estimate of the curve; the first is a Taubin-smoothed staircase.
  std::vector<Vec2> cur = s.c, next(n), tan(n);
  smooth_closed_taubin(cur, 10);
  std::vector<std::size_t> window;
  for (int it = 0; it < std::max(1, o.iterations); ++it) {
    tangents(cur, tan);
    for (std::size_t i = 0; i < n; ++i) next[i] = fit_vertex(s, cur, tan, i, o, window);
    cur.swap(next);
  }
  return cur;
}

std::vector<Vec2> resample_closed(const std::vector<Vec2>& polyline, int count) {
  const std::size_t n = polyline.size();
  if (n < 2 || count < 3) return polyline;
  std::vector<double> cum(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) cum[i + 1] = cum[i] + norm(polyline[(i + 1) % n] - polyline[i]);
  const double total = cum[n];
  if (!(total > 0.0)) return polyline;
  std::vector<Vec2> out;
  out.reserve(static_cast<std::size_t>(count));
  std::size_t seg = 0;
  for (int k = 0; k < count; ++k) {
    const double s = total * k / count;
    while (seg + 1 < n && cum[seg + 1] <= s) ++seg;
    const double len = cum[seg + 1] - cum[seg];
    const double t = len > 0.0 ? (s - cum[seg]) / len : 0.0;
    const Vec2 a = polyline[seg], b = polyline[(seg + 1) % n];
    out.push_back(a + t * (b - a));
  }
  return out;
}

std::vector<float> gaussian_blur(const std::vector<float>& field, int width, int height, double sigma) {
  if (!(sigma > 0.0) || width <= 0 || height <= 0) return field;
  const int r = static_cast<int>(std::ceil(3.0 * sigma));
  std::vector<float> k(static_cast<std::size_t>(2 * r + 1));
  double sum = 0.0;
  for (int i = -r; i <= r; ++i)
    sum += k[static_cast<std::size_t>(i + r)] = static_cast<float>(std::exp(-0.5 * i * i / (sigma * sigma)));
  for (float& v : k) v = static_cast<float>(v / sum);
  std::vector<float> tmp(field.size(), 0.0f), out(field.size(), 0.0f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float acc = 0.0f;
      for (int i = std::max(-r, -x); i <= std::min(r, width - 1 - x); ++i)
        acc += k[static_cast<std::size_t>(i + r)] *
               field[static_cast<std::size_t>(x + i) + static_cast<std::size_t>(width) * y];
      tmp[static_cast<std::size_t>(x) + static_cast<std::size_t>(width) * y] = acc;
    }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float acc = 0.0f;
      for (int i = std::max(-r, -y); i <= std::min(r, height - 1 - y); ++i)
        acc += k[static_cast<std::size_t>(i + r)] *
               tmp[static_cast<std::size_t>(x) + static_cast<std::size_t>(width) * (y + i)];
      out[static_cast<std::size_t>(x) + static_cast<std::size_t>(width) * y] = acc;
    }
  return out;
}

}  // namespace c4d
