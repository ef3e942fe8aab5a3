// Analytic phantoms with exact plane sections.
// Lim et al. 2014, "Comparison with Idealized Model": an ellipse swept 180° about the z-axis,
// scaled per state (ED, ES), its two end ellipses extruded to y = 35 and sliced every 5 mm.
// Here that construction and three simpler shapes are meshed as structured grids whose rings at
// the slice heights ARE the contours: every contour vertex is a truth vertex and every contour
// edge a truth edge, so the truth has zero conformity error against its own contours.
// docs/phantoms.md states the parameters and how each ambiguity of the paper was read.
#include "contour4d/phantoms/phantom.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include <tbb/parallel_for.h>

#include "contour4d/core/errors.h"

namespace c4d {

namespace {

constexpr double kPi = std::numbers::pi;

// Reading of "major axis of 2 units in the x-axis and minor axis of 1 unit in the z-axis": SEMI-axes
// 2 and 1. Only this reading lets both states be "extruded upwards to y = 35" (their end ellipses
// lie at y = 20 and 13.75; with semi-axes 1 and 0.5 the ED ends would lie at y = 40, above 35), it
// keeps the apex fixed at y = -80 mm in both states (the ES shift of -5 mm exactly compensates the
// shorter y scale), and it gives left-ventricle volumes (ED 124 mL, ES 67 mL) instead of 25 and
// 14 mL. docs/phantoms.md discusses it.
constexpr double kHeartA = 2.0;
constexpr double kHeartB = 1.0;
constexpr double kHeartTop = 35.0;   // y of the flat caps (mm)
constexpr double kCycleMs = 1000.0;  // length of one cycle of a cyclic phantom (ms)

using PointFn = std::function<Vec3(double d, double t)>;

//! One closed loop of mesh vertices with the grid parameter of each (for stitching).
struct Ring {
  std::vector<std::uint32_t> idx;
  std::vector<double> param;  // increasing, param[0] == t0
  double t0 = 0.0;
  double period = 2 * kPi;
};

std::uint32_t add_vertex(TriangleMesh& m, Vec3 p) {
  m.positions.push_back(p);
  return static_cast<std::uint32_t>(m.positions.size() - 1);
}

void add_triangle(TriangleMesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  if (a == b || b == c || a == c) return;  // a fan onto a pole closes with one degenerate step
  m.triangles.push_back({a, b, c});
}

Ring make_ring(TriangleMesh& m, const PointFn& f, double d, double t0, double period, int n) {
  Ring r;
  r.t0 = t0;
  r.period = period;
  for (int j = 0; j < n; ++j) {
    const double t = t0 + period * j / n;
    r.idx.push_back(add_vertex(m, f(d, t)));
    r.param.push_back(t);
  }
  return r;
}

Ring pole_ring(TriangleMesh& m, Vec3 p, double t0, double period) {
  Ring r;
  r.t0 = t0;
  r.period = period;
  r.idx.push_back(add_vertex(m, p));
  r.param.push_back(t0);
  return r;
}

//! Samples per ring so that no ring edge is longer than `edge` (mm), a multiple of 4, >= 8.
int ring_count(const PointFn& f, double d, double t0, double period, double edge) {
  constexpr int kProbe = 256;
  double worst = 0.0;
  Vec3 prev = f(d, t0);
  for (int j = 1; j <= kProbe; ++j) {
    const Vec3 p = f(d, t0 + period * j / kProbe);
    worst = std::max(worst, distance(p, prev));
    prev = p;
  }
  const int n = static_cast<int>(std::ceil(worst * kProbe / edge));
  return std::max(8, (n + 3) / 4 * 4);
}

//! Triangulates the band between two rings sharing t0 and period: a merge walk over the
//! parameters, so rings of different sizes stitch without slivers. Ring A comes first in the
//! sheet's ordering; the caller fixes the global orientation afterwards.
void stitch(TriangleMesh& m, const Ring& A, const Ring& B) {
  const std::size_t na = A.idx.size(), nb = B.idx.size();
  auto pa = [&](std::size_t k) { return k < na ? (A.param[k] - A.t0) / A.period : 1.0; };
  auto pb = [&](std::size_t k) { return k < nb ? (B.param[k] - B.t0) / B.period : 1.0; };
  std::size_t i = 0, j = 0;
  while (i < na || j < nb) {
    bool advance_a;
    if (i == na) {
      advance_a = false;
    } else if (j == nb) {
      advance_a = true;
    } else {
      const double a1 = pa(i + 1), b1 = pb(j + 1);
      if (std::abs(a1 - b1) > 1e-12) {
        advance_a = a1 < b1;
      } else {  // equal parameters: the shorter diagonal
        const Vec3 ai = m.positions[A.idx[i]], ai1 = m.positions[A.idx[(i + 1) % na]];
        const Vec3 bj = m.positions[B.idx[j]], bj1 = m.positions[B.idx[(j + 1) % nb]];
        advance_a = distance(ai1, bj) < distance(ai, bj1);
      }
    }
    if (advance_a) {
      add_triangle(m, A.idx[i], B.idx[j % nb], A.idx[(i + 1) % na]);
      ++i;
    } else {
      add_triangle(m, A.idx[i % na], B.idx[j], B.idx[(j + 1) % nb]);
      ++j;
    }
  }
}

//! Flat cap inside `boundary` (a planar ring): rings shrunk toward the centroid, then a pole.
//! The cap comes before the boundary in the sheet's ordering.
void cap(TriangleMesh& m, const Ring& boundary, const PointFn& f, double d, double edge) {
  Vec3 c{};
  for (std::uint32_t v : boundary.idx) c += m.positions[v];
  c = c / static_cast<double>(boundary.idx.size());
  double radius = 0.0;
  for (std::uint32_t v : boundary.idx) radius = std::max(radius, distance(m.positions[v], c));
  const int levels = std::max(1, static_cast<int>(std::ceil(radius / edge)));
  Ring prev = pole_ring(m, c, boundary.t0, boundary.period);
  for (int k = 1; k < levels; ++k) {
    const double lambda = static_cast<double>(k) / levels;
    const int n = std::max(6, static_cast<int>(std::ceil(lambda * static_cast<double>(boundary.idx.size()))));
    const PointFn shrunk = [&](double dd, double t) { return c + lambda * (f(dd, t) - c); };
    Ring r = make_ring(m, shrunk, d, boundary.t0, boundary.period, n);
    stitch(m, prev, r);
    prev = std::move(r);
  }
  stitch(m, prev, boundary);
}

//! Heights in [d0, d1], both included, such that corresponding probe points of consecutive rings
//! are about `edge` apart, landing exactly on every `forced` height strictly inside.
std::vector<double> march(const std::function<double(double, double)>& gap, double d0, double d1,
                          std::vector<double> forced, double edge) {
  std::sort(forced.begin(), forced.end());
  std::vector<double> out{d0};
  double d = d0;
  double step = (d1 - d0) / 16;
  std::size_t next_forced = 0;
  while (next_forced < forced.size() && forced[next_forced] <= d0) ++next_forced;
  while (d < d1) {
    // Grow the previous step a little; while that is too long, shrink it by the gap ratio (the
    // gap grows about linearly with the step, like its square root near a pole).
    step = std::min(d1 - d, 1.3 * step);
    for (int it = 0; it < 60; ++it) {
      const double g = gap(d, d + step);
      if (g <= edge || step <= 1e-7 * (d1 - d0)) break;
      step = std::max(1e-7 * (d1 - d0), step * std::max(0.1, 0.95 * edge / g));
    }
    double dn = std::min(d1, d + step);
    if (next_forced < forced.size() && forced[next_forced] < d1 && forced[next_forced] <= d + 1.5 * step) {
      dn = forced[next_forced++];
    } else if (dn < d1 && d1 - dn < 0.5 * step) {
      dn = d1;  // no sliver band before the end
    }
    out.push_back(dn);
    d = dn;
    if (out.size() > 200000)
      throw InvalidInput(ErrorCode::Internal, {}, "phantom: too many rings (truth edge too small for the shape)");
  }
  out.back() = d1;
  return out;
}

//! The sheet of rings between two heights (a tube piece of one component).
double max_gap(const PointFn& f, double t0, double period, double da, double db) {
  constexpr int kProbe = 48;
  double g = 0.0;
  for (int j = 0; j < kProbe; ++j) {
    const double t = t0 + period * (j + 0.5) / kProbe;
    g = std::max(g, distance(f(da, t), f(db, t)));
  }
  return g;
}

//! A section ring that is a contour: its slice id.
struct Section {
  int slice = 0;
  Ring ring;
};

//! The truth of one frame in the phantom's local frame, with its section rings.
struct FrameShape {
  TriangleMesh mesh;
  std::vector<Section> sections;
};

//! A slice plane of the lattice: slice id and height on the local slice axis (mm).
struct Plane1D {
  int id = 0;
  double h = 0.0;
};

// ---------------------------------------------------------------------------------------------
// Ellipsoid with semi-axes (a, a, c), centred at the origin, axis z.

FrameShape ellipsoid_frame(double a, double c, const std::vector<Plane1D>& planes, double edge) {
  // Height parameter d = -z runs from the top pole (d = -c) to the bottom pole (d = c).
  const PointFn f = [a, c](double d, double t) {
    const double r = a * std::sqrt(std::max(0.0, 1.0 - (d / c) * (d / c)));
    return Vec3{r * std::cos(t), r * std::sin(t), -d};
  };
  const double margin = 1e-6 * c;
  std::vector<double> forced;
  for (const Plane1D& p : planes)
    if (std::abs(p.h) < c - margin) forced.push_back(-p.h);
  const auto heights = march([&](double da, double db) { return max_gap(f, 0, 2 * kPi, da, db); }, -c, c, forced, edge);
  FrameShape out;
  Ring prev = pole_ring(out.mesh, {0, 0, c}, 0, 2 * kPi);
  for (std::size_t k = 1; k + 1 < heights.size(); ++k) {
    const double d = heights[k];
    Ring r = make_ring(out.mesh, f, d, 0, 2 * kPi, ring_count(f, d, 0, 2 * kPi, edge));
    stitch(out.mesh, prev, r);
    for (const Plane1D& p : planes)
      if (-p.h == d) out.sections.push_back({p.id, r});
    prev = std::move(r);
  }
  stitch(out.mesh, prev, pole_ring(out.mesh, {0, 0, -c}, 0, 2 * kPi));
  return out;
}

// ---------------------------------------------------------------------------------------------
// Torus with axis z: ring radius R, tube radius r.

FrameShape torus_frame(double R, double r, const std::vector<Plane1D>& planes, double edge) {
  // Tube angle psi in [-pi/2, 3pi/2): the section by z = h is psi = asin(h/r) (outer circle) and
  // pi - asin(h/r) (inner circle).
  const PointFn f = [R, r](double psi, double t) {
    const double rho = R + r * std::cos(psi);
    return Vec3{rho * std::cos(t), rho * std::sin(t), r * std::sin(psi)};
  };
  struct Target {
    double psi;
    int slice;
  };
  std::vector<Target> targets;
  for (const Plane1D& p : planes) {
    if (std::abs(p.h) >= r * (1 - 1e-6)) continue;
    const double s = std::asin(p.h / r);
    targets.push_back({s, p.id});
    targets.push_back({kPi - s, p.id});
  }
  const double psi0 = -kPi / 2, span = 2 * kPi;
  const int n = std::max(8, static_cast<int>(std::ceil(span * r / edge)));
  const double step = span / n;
  std::vector<Target> grid;
  for (int k = 0; k < n; ++k) {
    const double psi = psi0 + step * k;
    bool near = false;
    for (const Target& t : targets) near = near || std::abs(t.psi - psi) < 0.5 * step;
    if (!near) grid.push_back({psi, -1});
  }
  grid.insert(grid.end(), targets.begin(), targets.end());
  std::sort(grid.begin(), grid.end(), [](const Target& x, const Target& y) { return x.psi < y.psi; });
  FrameShape out;
  std::vector<Ring> rings;
  for (const Target& g : grid) {
    rings.push_back(make_ring(out.mesh, f, g.psi, 0, 2 * kPi, ring_count(f, g.psi, 0, 2 * kPi, edge)));
    if (g.slice >= 0) out.sections.push_back({g.slice, rings.back()});
  }
  for (std::size_t k = 0; k < rings.size(); ++k) stitch(out.mesh, rings[k], rings[(k + 1) % rings.size()]);
  return out;
}

// ---------------------------------------------------------------------------------------------
// The swept ellipse of Lim et al. (left-heart) and its mirror (bifurcation).
// Unit frame: an ellipse with semi-axes a (radial) and b (z) centred at distance R from the z-axis,
// swept half a turn so it lies at Y <= 0; depth d = -Y. The saddle is at depth c = R - a. World
// (local, before --oblique): x = sx X, y = ty + sign sy (c - d), z = sz Z. Legs continue the two
// end ellipses for d < 0 up to the cap at world y = cap_y.

struct Swept {
  double R = 3, a = 1, b = 0.5;
  double sx = 1, sy = 1, sz = 1;
  double ty = 0;      // world y of the saddle
  double sign = 1;    // +1: legs up (left heart), -1: legs down (bifurcation)
  double cap_y = 35;  // world y of the flat caps
  double saddle() const { return R - a; }
  double depth_of(double y) const { return saddle() - (y - ty) / (sign * sy); }
  double y_of(double d) const { return ty + sign * sy * (saddle() - d); }
  Vec3 world(double X, double d, double Z) const { return {sx * X, y_of(d), sz * Z}; }
  std::vector<double> params() const { return {R, a, b, sx, sy, sz, ty, sign, cap_y}; }
};

Swept swept_from(const std::vector<double>& p) {
  Swept s;
  s.R = p[0], s.a = p[1], s.b = p[2], s.sx = p[3], s.sy = p[4], s.sz = p[5], s.ty = p[6], s.sign = p[7], s.cap_y = p[8];
  return s;
}

//! One loop below the saddle: phi = phimax sin t, x = sign(cos t) sqrt(rho^2 - d^2).
Vec3 swept_single(const Swept& s, double d, double t) {
  const double phimax = std::acos(std::clamp((d - s.R) / s.a, -1.0, 1.0));
  const double phi = phimax * std::sin(t);
  const double rho = s.R + s.a * std::cos(phi);
  const double x = (std::cos(t) >= 0 ? 1.0 : -1.0) * std::sqrt(std::max(0.0, rho * rho - d * d));
  return s.world(x, d, s.b * std::sin(phi));
}

//! A leg (side +1: x > 0, t in [-pi/2, pi/2); side -1: t in [pi/2, 3pi/2)) at depth d <= c.
Vec3 swept_leg(const Swept& s, double side, double d, double t) {
  const double phi = kPi * std::sin(t);
  const double rho = s.R + s.a * std::cos(phi);
  const double dd = std::max(d, 0.0);
  return s.world(side * std::sqrt(std::max(0.0, rho * rho - dd * dd)), d, s.b * std::sin(phi));
}

FrameShape swept_frame(const Swept& s, const std::vector<Plane1D>& planes, double edge) {
  const double c = s.saddle(), bottom = s.R + s.a;
  const double d_cap = s.depth_of(s.cap_y);
  if (!(d_cap < c))
    throw InvalidInput(ErrorCode::Internal, {}, "phantom: the cap lies below the saddle (bad parameters)");
  const PointFn right = [&s](double d, double t) { return swept_leg(s, 1.0, d, t); };
  const PointFn left = [&s](double d, double t) { return swept_leg(s, -1.0, d, t); };
  const PointFn single = [&s](double d, double t) { return swept_single(s, d, t); };
  const double margin = 1e-9 * (bottom - d_cap);
  std::vector<double> forced_up, forced_low;
  std::vector<std::pair<double, int>> slice_depth;
  for (const Plane1D& p : planes) {
    const double d = s.depth_of(p.h);
    if (d <= d_cap + margin || d >= bottom - margin) continue;
    if (std::abs(d - c) <= margin) {
      slice_depth.emplace_back(c, p.id);  // through the saddle: two loops touching at the saddle
      continue;
    }
    slice_depth.emplace_back(d, p.id);
    (d < c ? forced_up : forced_low).push_back(d);
  }
  // Where the legs meet the swept part, unless a slice plane is already there.
  bool junction_is_slice = false;
  for (double d : forced_up) junction_is_slice = junction_is_slice || std::abs(d) <= margin;
  if (d_cap < 0 && !junction_is_slice) forced_up.push_back(0.0);
  const auto up = march(
      [&](double da, double db) {
        return std::max(max_gap(right, -kPi / 2, kPi, da, db), max_gap(left, kPi / 2, kPi, da, db));
      },
      d_cap, c, forced_up, edge);
  const auto low =
      march([&](double da, double db) { return max_gap(single, 0, 2 * kPi, da, db); }, c, bottom, forced_low, edge);
  auto slice_at = [&](double d) {
    for (const auto& [sd, id] : slice_depth)
      if (sd == d) return id;
    return -1;
  };

  FrameShape out;
  TriangleMesh& m = out.mesh;
  // The saddle ring: one loop of the lower family, whose samples t = pi/2 and 3pi/2 are the one
  // saddle vertex; its halves are the bottom rings of the legs.
  const int ns = ring_count(single, c, 0, 2 * kPi, edge);
  const std::uint32_t saddle_vertex = add_vertex(m, s.world(0.0, c, 0.0));
  Ring saddle_ring, right_half, left_half;
  for (int j = 0; j < ns; ++j) {
    const double t = 2 * kPi * j / ns;
    const bool pinch = (4 * j == ns) || (4 * j == 3 * ns);
    saddle_ring.idx.push_back(pinch ? saddle_vertex : add_vertex(m, single(c, t)));
    saddle_ring.param.push_back(t);
  }
  right_half.t0 = -kPi / 2, right_half.period = kPi;
  left_half.t0 = kPi / 2, left_half.period = kPi;
  for (int j = 3 * ns / 4; j < ns; ++j)
    right_half.idx.push_back(saddle_ring.idx[j]), right_half.param.push_back(saddle_ring.param[j] - 2 * kPi);
  for (int j = 0; j < ns / 4; ++j)
    right_half.idx.push_back(saddle_ring.idx[j]), right_half.param.push_back(saddle_ring.param[j]);
  for (int j = ns / 4; j < 3 * ns / 4; ++j)
    left_half.idx.push_back(saddle_ring.idx[j]), left_half.param.push_back(saddle_ring.param[j]);

  // Legs: cap, rings down to the saddle.
  for (int side = 0; side < 2; ++side) {
    const PointFn& f = side == 0 ? right : left;
    const double t0 = side == 0 ? -kPi / 2 : kPi / 2;
    Ring top = make_ring(m, f, d_cap, t0, kPi, ring_count(f, d_cap, t0, kPi, edge));
    cap(m, top, f, d_cap, edge);
    Ring prev = std::move(top);
    for (std::size_t k = 1; k + 1 < up.size(); ++k) {
      Ring r = make_ring(m, f, up[k], t0, kPi, ring_count(f, up[k], t0, kPi, edge));
      stitch(m, prev, r);
      if (const int id = slice_at(up[k]); id >= 0) out.sections.push_back({id, r});
      prev = std::move(r);
    }
    stitch(m, prev, side == 0 ? right_half : left_half);
  }
  if (const int id = slice_at(c); id >= 0) {
    out.sections.push_back({id, right_half});
    out.sections.push_back({id, left_half});
  }
  // Below the saddle: one loop per height down to the bottom pole.
  Ring prev = saddle_ring;
  for (std::size_t k = 1; k + 1 < low.size(); ++k) {
    Ring r = make_ring(m, single, low[k], 0, 2 * kPi, ring_count(single, low[k], 0, 2 * kPi, edge));
    stitch(m, prev, r);
    if (const int id = slice_at(low[k]); id >= 0) out.sections.push_back({id, r});
    prev = std::move(r);
  }
  stitch(m, prev, pole_ring(m, s.world(0.0, bottom, 0.0), 0, 2 * kPi));
  return out;
}

//! Exact volume of the swept shape when the caps lie on the legs (Pappus for the half turn,
//! prisms for the legs); NaN when the caps cut the swept part.
double swept_volume(const Swept& s) {
  const double d_cap = s.depth_of(s.cap_y);
  if (d_cap > 0) return std::numeric_limits<double>::quiet_NaN();
  const double ellipse = kPi * s.a * s.b;
  return s.sx * s.sy * s.sz * ellipse * kPi * s.R + 2 * ellipse * s.sx * s.sz * s.sy * (-d_cap);
}

// ---------------------------------------------------------------------------------------------
// The catalogue.

enum class Kind { Ellipsoid, Torus, Swept };

struct Spec {
  const char* name;
  const char* description;
  const char* label;
  Kind kind;
  int default_frames;  // 1: single frame; 3: ED, ES, ED; otherwise a cosine cycle
  double default_offset;
  bool axis_y;                 // slice axis y (else z)
  std::vector<double> ed, es;  // shape parameters at the two extremes of the cycle
};

const std::vector<Spec>& catalogue() {
  static const std::vector<Spec> specs = {
      {"ellipsoid",
       "ellipsoid 25x25x40 mm shrinking to 19x19x30 and back (20 frames); apex and base cross planes",
       "ellipsoid",
       Kind::Ellipsoid,
       20,
       2.5,
       false,
       {25, 40},
       {19, 30}},
      {"bifurcation",
       "one trunk above, two legs below; the branch point moves down through a slice plane (20 frames)",
       "bifurcation",
       Kind::Swept,
       20,
       2.5,
       true,
       {3, 1, 1, 6, 6, 6, 1.0, -1, -30},
       {3, 1, 1, 6, 6, 6, -4.0, -1, -30}},
      {"torus",
       "torus R 30 mm, tube 12 mm breathing to 9 mm (10 frames); every section a ring with a hole",
       "torus",
       Kind::Torus,
       10,
       0.0,
       false,
       {30, 12},
       {30, 9}},
      {"left-heart",
       "idealized left heart of Lim et al. 2014: ED, ES, ED (3 frames), slices y = 32.5 - 5k",
       "lv",
       Kind::Swept,
       3,
       32.5,
       true,
       {3, kHeartA, kHeartB, 5, 20, 18, 0, 1, kHeartTop},
       {3, kHeartA, kHeartB, 3.5, 18.75, 14, -5, 1, kHeartTop}},
      {"left-heart-cycle",
       "idealized left heart, smooth cycle ED -> ES -> ED (20 frames)",
       "lv",
       Kind::Swept,
       20,
       32.5,
       true,
       {3, kHeartA, kHeartB, 5, 20, 18, 0, 1, kHeartTop},
       {3, kHeartA, kHeartB, 3.5, 18.75, 14, -5, 1, kHeartTop}},
      {"left-heart-ed",
       "idealized left heart, end-diastole only (1 frame)",
       "lv",
       Kind::Swept,
       1,
       32.5,
       true,
       {3, kHeartA, kHeartB, 5, 20, 18, 0, 1, kHeartTop},
       {}},
      {"left-heart-es",
       "idealized left heart, end-systole only (1 frame)",
       "lv",
       Kind::Swept,
       1,
       32.5,
       true,
       {3, kHeartA, kHeartB, 3.5, 18.75, 14, -5, 1, kHeartTop},
       {}},
  };
  return specs;
}

const Spec& find_spec(const std::string& name) {
  for (const Spec& s : catalogue())
    if (name == s.name) return s;
  std::string names;
  for (const Spec& s : catalogue()) names += (names.empty() ? "" : ", ") + std::string(s.name);
  throw InvalidInput(ErrorCode::Usage, {}, "unknown phantom \"" + name + "\"", "choose one of: " + names);
}

void check_options(const PhantomOptions& o) {
  auto bad = [](const std::string& what, const std::string& hint) {
    throw InvalidInput(ErrorCode::Usage, {}, what, hint);
  };
  if (!(o.spacing >= 0.2 && o.spacing <= 100))
    bad("slice spacing out of range", "give --spacing between 0.2 and 100 mm");
  if (!std::isnan(o.offset) && !(std::abs(o.offset) <= 1000))
    bad("slice offset out of range", "give --offset within ±1000 mm");
  if (o.frames < 0 || o.frames > 1000) bad("frame count out of range", "give --frames between 1 and 1000 (0: default)");
  if (!(o.truth_edge >= 0.05 && o.truth_edge <= 10))
    bad("truth edge length out of range", "give a truth edge between 0.05 and 10 mm");
}

//! Extent of a frame's shape along the local slice axis (mm).
std::pair<double, double> extent(Kind kind, const std::vector<double>& p) {
  if (kind == Kind::Ellipsoid) return {-p[1], p[1]};
  if (kind == Kind::Torus) return {-p[1], p[1]};
  const Swept s = swept_from(p);
  const double y_bottom = s.y_of(s.R + s.a);
  return {std::min(y_bottom, s.cap_y), std::max(y_bottom, s.cap_y)};
}

Vec3 rotate(const std::array<Vec3, 3>& R, Vec3 p) { return {dot(R[0], p), dot(R[1], p), dot(R[2], p)}; }
Vec3 rotate_back(const std::array<Vec3, 3>& R, Vec3 p) { return R[0] * p.x + R[1] * p.y + R[2] * p.z; }

//! Local coordinates of a world point of the phantom (the slice axis becomes z).
Vec3 to_local(const Phantom& ph, Vec3 p) {
  return ph.oblique ? rotate_back(oblique_rotation(), p - oblique_translation()) : p;
}

}  // namespace

std::array<Vec3, 3> oblique_rotation() {
  const Vec3 k = normalized(Vec3{1, 2, 3});
  const double th = 30.0 * kPi / 180.0, c = std::cos(th), s = std::sin(th), C = 1 - c;
  return {Vec3{c + k.x * k.x * C, k.x * k.y * C - k.z * s, k.x * k.z * C + k.y * s},
          Vec3{k.y * k.x * C + k.z * s, c + k.y * k.y * C, k.y * k.z * C - k.x * s},
          Vec3{k.z * k.x * C - k.y * s, k.z * k.y * C + k.x * s, c + k.z * k.z * C}};
}

Vec3 oblique_translation() { return {12, -7, 33}; }

std::vector<std::string> phantom_names() {
  std::vector<std::string> out;
  for (const Spec& s : catalogue()) out.emplace_back(s.name);
  return out;
}

std::string phantom_description(const std::string& name) { return find_spec(name).description; }

Phantom make_phantom(const std::string& name, const PhantomOptions& options) {
  const Spec& spec = find_spec(name);
  check_options(options);
  Phantom ph;
  ph.name = spec.name;
  ph.description = spec.description;
  ph.oblique = options.oblique;

  // Frames and their parameters: a cosine cycle between the two extremes.
  // Single-frame phantoms and "left-heart" (ED, ES, ED) have a fixed frame count.
  const bool fixed = spec.default_frames <= 3;
  const int frames = fixed || options.frames == 0 ? spec.default_frames : options.frames;
  std::vector<double> times;
  for (int f = 0; f < frames; ++f) {
    std::vector<double> p = spec.ed;
    double w = 0.0;
    if (fixed && frames == 3) {
      w = f == 1 ? 1.0 : 0.0;
      times.push_back(f * kCycleMs / 2);
    } else if (frames > 1) {
      w = 0.5 * (1 - std::cos(2 * kPi * f / frames));
      times.push_back(f * kCycleMs / frames);
    } else {
      times.push_back(0.0);
    }
    if (!spec.es.empty())
      for (std::size_t i = 0; i < p.size(); ++i) p[i] = spec.ed[i] + w * (spec.es[i] - spec.ed[i]);
    ph.shape_parameters.push_back(std::move(p));
  }

  // The slice lattice over the union of the frames' extents.
  const double offset = std::isnan(options.offset) ? spec.default_offset : options.offset;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& p : ph.shape_parameters) {
    const auto [a, b] = extent(spec.kind, p);
    lo = std::min(lo, a), hi = std::max(hi, b);
  }
  const double eps = 1e-9 * (hi - lo);
  const auto k0 = static_cast<long long>(std::floor((lo + eps - offset) / options.spacing)) + 1;
  const auto k1 = static_cast<long long>(std::ceil((hi - eps - offset) / options.spacing)) - 1;
  if (k1 < k0) throw InvalidInput(ErrorCode::Usage, {}, "no slice plane cuts the phantom", "use a smaller --spacing");
  std::vector<Plane1D> planes;
  for (long long k = k0; k <= k1; ++k) planes.push_back({static_cast<int>(k - k0), offset + options.spacing * k});

  // Local frame: slice axis e; the oblique motion maps local to world.
  const Vec3 axis = spec.axis_y ? Vec3{0, 1, 0} : Vec3{0, 0, 1};
  const std::array<Vec3, 3> R = oblique_rotation();
  const Vec3 T = oblique_translation();
  auto place = [&](Vec3 p) { return options.oblique ? rotate(R, p) + T : p; };
  const Vec3 normal = options.oblique ? rotate(R, axis) : axis;
  const Plane in_plane = make_plane({0, 0, 0}, normal);

  // Frames are independent: build them in parallel, each into its own slot (deterministic).
  std::vector<FrameShape> shapes(static_cast<std::size_t>(frames));
  tbb::parallel_for(std::size_t{0}, shapes.size(), [&](std::size_t f) {
    const auto& p = ph.shape_parameters[f];
    FrameShape shape = spec.kind == Kind::Ellipsoid ? ellipsoid_frame(p[0], p[1], planes, options.truth_edge)
                       : spec.kind == Kind::Torus   ? torus_frame(p[0], p[1], planes, options.truth_edge)
                                                    : swept_frame(swept_from(p), planes, options.truth_edge);
    for (Vec3& v : shape.mesh.positions) v = place(v);
    if (signed_volume(shape.mesh) < 0)
      for (Triangle& t : shape.mesh.triangles) std::swap(t[1], t[2]);
    shapes[f] = std::move(shape);
  });
  std::vector<RawContour> raw;
  for (int f = 0; f < frames; ++f) {
    const auto& p = ph.shape_parameters[static_cast<std::size_t>(f)];
    FrameShape& shape = shapes[static_cast<std::size_t>(f)];
    // Contours: the section rings, counter-clockwise about the stack normal.
    std::stable_sort(shape.sections.begin(), shape.sections.end(),
                     [](const Section& x, const Section& y) { return x.slice < y.slice; });
    int index = 0;
    for (const Section& s : shape.sections) {
      RawContour rc;
      rc.frame = f;
      rc.index = index++;
      rc.contour.label = spec.label;
      rc.contour.slice = s.slice;
      std::vector<Vec2> q;
      for (std::uint32_t v : s.ring.idx) {
        rc.contour.points.push_back(shape.mesh.positions[v]);
        q.push_back(to_plane(in_plane, shape.mesh.positions[v]));
      }
      if (signed_area(q) < 0) std::reverse(rc.contour.points.begin(), rc.contour.points.end());
      raw.push_back(std::move(rc));
    }
    const double v_exact = spec.kind == Kind::Ellipsoid ? 4.0 / 3.0 * kPi * p[0] * p[0] * p[1]
                           : spec.kind == Kind::Torus   ? 2 * kPi * kPi * p[0] * p[1] * p[1]
                                                        : swept_volume(swept_from(p));
    ph.true_volume_mm3.push_back(std::isnan(v_exact) ? signed_volume(shape.mesh) : v_exact);
    ph.truth.push_back(std::move(shape.mesh));
  }
  ph.contours = build_sequence(raw, frames, times, "phantom " + ph.name);
  ph.contours.space = "unknown";
  // Offsets of the first and last lattice plane along the sequence normal.
  const double o1 = dot(place(axis * planes.front().h), ph.contours.normal);
  const double o2 = dot(place(axis * planes.back().h), ph.contours.normal);
  ph.slab_min = std::min(o1, o2);
  ph.slab_max = std::max(o1, o2);
  return ph;
}

double analytic_distance(const Phantom& ph, int frame, Vec3 world) {
  const Spec& spec = find_spec(ph.name);
  const auto& p = ph.shape_parameters.at(static_cast<std::size_t>(frame));
  const Vec3 q = to_local(ph, world);
  if (spec.kind == Kind::Torus) return std::hypot(std::hypot(q.x, q.y) - p[0], q.z) - p[1];
  // Implicit function over the norm of its gradient (central differences, world mm).
  std::function<double(Vec3)> g;
  double cap_distance = -std::numeric_limits<double>::infinity();
  if (spec.kind == Kind::Ellipsoid) {
    g = [a = p[0], c = p[1]](Vec3 x) { return (x.x * x.x + x.y * x.y) / (a * a) + x.z * x.z / (c * c) - 1; };
  } else {
    const Swept s = swept_from(p);
    g = [s](Vec3 x) {
      const double X = x.x / s.sx, Z = x.z / s.sz, Y = -s.depth_of(x.y);
      const double rho = Y <= 0 ? std::hypot(X, Y) : std::abs(X);
      return ((rho - s.R) / s.a) * ((rho - s.R) / s.a) + (Z / s.b) * (Z / s.b) - 1;
    };
    cap_distance = (q.y - s.cap_y) * s.sign;
  }
  constexpr double h = 1e-5;
  const Vec3 grad{(g(q + Vec3{h, 0, 0}) - g(q - Vec3{h, 0, 0})) / (2 * h),
                  (g(q + Vec3{0, h, 0}) - g(q - Vec3{0, h, 0})) / (2 * h),
                  (g(q + Vec3{0, 0, h}) - g(q - Vec3{0, 0, h})) / (2 * h)};
  const double gn = norm(grad);
  const double lateral = gn > 0 ? g(q) / gn : g(q);
  return std::max(lateral, cap_distance);
}

}  // namespace c4d
