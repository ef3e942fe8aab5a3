// Breath-hold slice alignment (slice_alignment.h). Neither paper corrects slice shifts; short-axis cine stacks
// are acquired one breath-hold per slice, and cardiac modelling pipelines (e.g. biv-me's guide-point fitting)
// realign slices in plane so that the ventricle's centroids follow a smooth long axis. Here: the area-weighted
// centroid of one structure per slice, averaged over frames, a robust polynomial fit of the centroids along the
// stack normal (Tukey's bisquare, iteratively reweighted), and each slice moved onto the fit.
#include "contour4d/core/slice_alignment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <Eigen/Dense>

#include "slice_alignment_internal.h"

namespace c4d {

namespace {

// The label on the most (frame, slice) pairs; ties: the first by name.
std::string most_common_label(const Sequence& seq) {
  std::map<std::string, int> count;
  for (const Frame& f : seq.frames)
    for (const Slice& s : f.slices) {
      std::vector<std::string> seen;
      for (const Contour& c : s.contours)
        if (std::find(seen.begin(), seen.end(), c.label) == seen.end()) seen.push_back(c.label);
      for (const std::string& l : seen) ++count[l];
    }
  std::string best;
  int most = 0;
  for (const auto& [label, n] : count)
    if (n > most) best = label, most = n;
  return best;
}

// The centroid of a slice's `label` contours in the stack's (u, v) plane, each contour weighted by its area
// (whatever its orientation); false if none.
bool slice_centroid(const Sequence& seq, const Slice& s, const std::string& label, Vec2& out) {
  double weight = 0, cu = 0, cv = 0;
  for (const Contour& c : s.contours) {
    if (c.label != label || c.points.size() < 3) continue;
    double area = 0, au = 0, av = 0;
    const std::size_t n = c.points.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& p = c.points[i];
      const Vec3& q = c.points[(i + 1) % n];
      const double pu = dot(p, seq.u), pv = dot(p, seq.v), qu = dot(q, seq.u), qv = dot(q, seq.v);
      const double cross = pu * qv - qu * pv;
      area += cross;
      au += (pu + qu) * cross;
      av += (pv + qv) * cross;
    }
    if (std::abs(area) < 1e-12) continue;
    const double a = std::abs(area);
    cu += a * au / (3 * area);
    cv += a * av / (3 * area);
    weight += a;
  }
  if (weight <= 0) return false;
  out = {cu / weight, cv / weight};
  return true;
}

struct SliceCentroid {
  int slice = 0;
  double offset = 0;
  Vec2 centroid;
};

// Each slice's centroid averaged over the frames that hold the label, by offset.
std::vector<SliceCentroid> mean_centroids(const Sequence& seq, const std::string& label) {
  std::map<int, std::pair<SliceCentroid, int>> acc;
  for (const Frame& f : seq.frames)
    for (const Slice& s : f.slices) {
      Vec2 c;
      if (!slice_centroid(seq, s, label, c)) continue;
      auto& [sc, n] = acc[s.id];
      sc.slice = s.id;
      sc.offset = s.offset;
      sc.centroid = sc.centroid + c;
      ++n;
    }
  std::vector<SliceCentroid> out;
  for (auto& [id, entry] : acc) {
    entry.first.centroid = entry.first.centroid * (1.0 / entry.second);
    out.push_back(entry.first);
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.offset < b.offset; });
  return out;
}

// The design matrix (powers of the offset mapped to [−1, 1]) and the centroids.
void design(const std::vector<SliceCentroid>& c, int degree, Eigen::MatrixXd& A, Eigen::MatrixXd& Y) {
  const Eigen::Index n = static_cast<Eigen::Index>(c.size()), m = degree + 1;
  const double lo = c.front().offset, span = std::max(c.back().offset - lo, 1e-9);
  A.resize(n, m);
  Y.resize(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    const SliceCentroid& ci = c[static_cast<std::size_t>(i)];
    const double t = 2 * (ci.offset - lo) / span - 1;
    for (Eigen::Index k = 0; k < m; ++k) A(i, k) = std::pow(t, static_cast<double>(k));
    Y(i, 0) = ci.centroid.x;
    Y(i, 1) = ci.centroid.y;
  }
}

// Each slice's distance from a fitted axis.
std::vector<double> residuals(const Eigen::MatrixXd& Y, const Eigen::MatrixXd& fit) {
  std::vector<double> r(static_cast<std::size_t>(Y.rows()));
  for (Eigen::Index i = 0; i < Y.rows(); ++i) r[static_cast<std::size_t>(i)] = (Y.row(i) - fit.row(i)).norm();
  return r;
}

Eigen::MatrixXd weighted_fit(const Eigen::MatrixXd& A, const Eigen::MatrixXd& Y, const Eigen::VectorXd& w) {
  const Eigen::MatrixXd Aw = w.asDiagonal() * A;
  return A * (A.transpose() * Aw).ldlt().solve(Aw.transpose() * Y);
}

// A start that one or two shifted slices cannot pull (least median of squares): the exact fit through each
// choice of degree + 1 slices (at most kMaxSubsets, taken evenly), kept where the h-th residual is least.
// The shifted slices at the ends of the stack have the most leverage on a plain least-squares start.
Eigen::VectorXd robust_start(const Eigen::MatrixXd& A, const Eigen::MatrixXd& Y) {
  const Eigen::Index n = A.rows(), m = A.cols();
  // The subsets are drawn from at most kCandidates slices spread evenly over the stack (a CT stack has hundreds).
  constexpr Eigen::Index kCandidates = 40;
  std::vector<Eigen::Index> candidates;
  for (Eigen::Index q = 0; q < std::min(n, kCandidates); ++q)
    candidates.push_back(n <= kCandidates ? q : q * (n - 1) / (kCandidates - 1));
  std::vector<std::vector<Eigen::Index>> subsets;
  std::vector<Eigen::Index> pick(static_cast<std::size_t>(m));
  const auto enumerate = [&](auto&& self, std::size_t from, std::size_t depth) -> void {
    if (depth == pick.size()) {
      subsets.push_back(pick);
      return;
    }
    for (std::size_t i = from; i < candidates.size(); ++i) {
      pick[depth] = candidates[i];
      self(self, i + 1, depth + 1);
    }
  };
  enumerate(enumerate, 0, 0);
  constexpr std::size_t kMaxSubsets = 4000;
  const std::size_t stride = subsets.size() / kMaxSubsets + 1;
  // The h-th smallest residual, h = (n + m + 1) / 2: the exact fit through m slices has m zero residuals, so a
  // plain median would not tell the subsets apart on short stacks.
  const std::size_t h = static_cast<std::size_t>((n + m + 1) / 2);
  double best = std::numeric_limits<double>::infinity();
  Eigen::MatrixXd best_fit = Y;
  for (std::size_t k = 0; k < subsets.size(); k += stride) {
    Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
    for (Eigen::Index i : subsets[k]) w(i) = 1;
    const Eigen::MatrixXd fit = weighted_fit(A, Y, w);
    if (!fit.allFinite()) continue;
    std::vector<double> r = residuals(Y, fit);
    std::nth_element(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(h - 1), r.end());
    if (r[h - 1] < best) best = r[h - 1], best_fit = fit;
  }
  const std::vector<double> r = residuals(Y, best_fit);
  const double scale = std::max(detail::kMadToSigma * best, 1e-9);
  Eigen::VectorXd w(n);
  for (Eigen::Index i = 0; i < n; ++i) w(i) = r[static_cast<std::size_t>(i)] <= 2.5 * scale + 0.5 ? 1.0 : 0.0;
  return w;
}

// Tukey-bisquare iteratively reweighted least squares of the centroids (u and v together: one residual length
// per slice) against a polynomial in the normalised offset, from the robust start. Returns the fitted
// centroids; `weights` the last weights.
std::vector<Vec2> robust_axis(const std::vector<SliceCentroid>& c, int degree, const SliceAlignmentOptions& o,
                              std::vector<double>& weights) {
  Eigen::MatrixXd A, Y;
  design(c, degree, A, Y);
  const Eigen::Index n = A.rows(), m = A.cols();
  Eigen::VectorXd w = robust_start(A, Y);
  Eigen::MatrixXd fit = Y;
  for (int it = 0; it < o.iterations; ++it) {
    if (w.count() <= m) w.setOnes();  // too few slices trusted to define the axis: plain least squares
    fit = weighted_fit(A, Y, w);
    const std::vector<double> r = residuals(Y, fit);
    const double scale = std::max(o.min_scale_mm, detail::kMadToSigma * detail::median(r));
    for (Eigen::Index i = 0; i < n; ++i) w(i) = detail::tukey_weight(r[static_cast<std::size_t>(i)], scale);
  }
  weights.assign(w.data(), w.data() + n);
  std::vector<Vec2> out(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) out[static_cast<std::size_t>(i)] = {fit(i, 0), fit(i, 1)};
  return out;
}

}  // namespace

namespace detail {

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double tukey_weight(double r, double sigma) {
  constexpr double kTukey = 4.685;  // the bisquare's cut-off in σ
  const double z = r / (kTukey * sigma);
  return z < 1 ? (1 - z * z) * (1 - z * z) : 0.0;
}

void move_slice(Sequence& seq, int id, Vec3 shift) {
  for (Frame& f : seq.frames)
    for (Slice& s : f.slices)
      if (s.id == id)
        for (Contour& c : s.contours)
          for (Vec3& p : c.points) p = p + shift;
}

}  // namespace detail

SliceAlignment align_slices(Sequence& seq, const SliceAlignmentOptions& options) {
  SliceAlignment out;
  out.method = "centroid-axis";
  out.label = options.label.empty() ? most_common_label(seq) : options.label;
  const std::vector<SliceCentroid> c = mean_centroids(seq, out.label);
  const int n = static_cast<int>(c.size());
  // Two slices more than coefficients: a shifted slice can stand out.
  out.degree = std::min(options.max_degree, n - 3);
  if (out.degree < 1) {  // a constant axis would take the stack's tilt against the ventricle for shifts
    out.degree = -1;
    return out;
  }
  std::vector<double> weights;
  const std::vector<Vec2> axis = robust_axis(c, out.degree, options, weights);
  for (int i = 0; i < n; ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    const Vec2 d = axis[k] - c[k].centroid;
    SliceShift s;
    s.slice = c[k].slice;
    s.offset_mm = c[k].offset;
    s.shift = seq.u * d.x + seq.v * d.y;
    s.shift_mm = std::hypot(d.x, d.y);
    s.weight = weights[k];
    detail::move_slice(seq, s.slice, s.shift);
    out.shifts.push_back(s);
  }
  return out;
}

}  // namespace c4d
