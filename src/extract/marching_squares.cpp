// Marching squares on a 2D field, with Taubin smoothing and arc-length resampling of the chains.
//
// References: Miara et al., "New Method for 4D Reconstruction of Medical Images", §III.B
// (contour extraction as an ordered chain of points); W. E. Lorensen, H. E. Cline, "Marching
// cubes", SIGGRAPH 1987 (the 2D case table); G. Taubin, "A signal processing approach to fair
// surface design", SIGGRAPH 1995 (λ|μ smoothing without shrinkage).
#include "contour4d/extract/marching_squares.h"

#include <algorithm>
#include <cmath>
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

std::vector<std::vector<Vec2>> marching_squares(const std::vector<float>& field, int width, int height,
                                                float level) {
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
  for (int i = -r; i <= r; ++i) sum += k[static_cast<std::size_t>(i + r)] = static_cast<float>(std::exp(-0.5 * i * i / (sigma * sigma)));
  for (float& v : k) v = static_cast<float>(v / sum);
  std::vector<float> tmp(field.size(), 0.0f), out(field.size(), 0.0f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float acc = 0.0f;
      for (int i = std::max(-r, -x); i <= std::min(r, width - 1 - x); ++i)
        acc += k[static_cast<std::size_t>(i + r)] * field[static_cast<std::size_t>(x + i) + static_cast<std::size_t>(width) * y];
      tmp[static_cast<std::size_t>(x) + static_cast<std::size_t>(width) * y] = acc;
    }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float acc = 0.0f;
      for (int i = std::max(-r, -y); i <= std::min(r, height - 1 - y); ++i)
        acc += k[static_cast<std::size_t>(i + r)] * tmp[static_cast<std::size_t>(x) + static_cast<std::size_t>(width) * (y + i)];
      out[static_cast<std::size_t>(x) + static_cast<std::size_t>(width) * y] = acc;
    }
  return out;
}

}  // namespace c4d
