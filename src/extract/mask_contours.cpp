// Label images -> ordered closed contours per slice, per label, per frame.
//
// Reference: Miara et al., "New Method for 4D Reconstruction of Medical Images", §III.B
// ("Extraction des contours"): the segmented slices are turned into chained, ordered lists of
// contour points, for every slice of every time frame. We trace them with marching squares on each
// label's mask (sub-pixel, saddles resolved consistently), remove the pixel staircase by fitting
// the sub-pixel edge (fit_mask_staircase; or Taubin λ|μ smoothing) and resample evenly by arc
// length (docs/images.md).
#include "contour4d/extract/mask_contours.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>
#include <sstream>

#include "contour4d/core/errors.h"
#include "contour4d/extract/marching_squares.h"
#include "contour4d/io/label_presets.h"

namespace c4d {
namespace {

std::optional<int> parse_int(const std::string& s) {
  int v = 0;
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(s.data(), end, v);
  if (ec != std::errc() || ptr != end || s.empty()) return std::nullopt;
  return v;
}

std::string fmt_mm(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

std::string join_labels(const std::set<int>& present, const LabelPreset* preset) {
  std::ostringstream os;
  bool first = true;
  for (int v : present) {
    os << (first ? "" : ", ") << v;
    if (preset)
      if (auto n = preset_name(*preset, v)) os << " (" << *n << ")";
    first = false;
  }
  return first ? std::string("none") : os.str();
}

// Geometry of one slice along the slice axis: world = base(k) + a·ea + b·eb (a, b voxel indices).
struct SliceAxes {
  int axis = 2, ia = 0, ib = 1;  // slice axis and the two in-plane voxel axes (ia < ib)
  Vec3 col[3];                   // world direction of each voxel axis (unit)
  double sp[3] = {1, 1, 1};
  Vec3 origin;
};

SliceAxes slice_axes(const LabelVolume& v, int axis) {
  SliceAxes s;
  s.axis = axis;
  s.ia = axis == 0 ? 1 : 0;
  s.ib = axis == 2 ? 1 : 2;
  for (int a = 0; a < 3; ++a) {
    s.col[a] = {v.direction[static_cast<std::size_t>(a)], v.direction[static_cast<std::size_t>(3 + a)],
                v.direction[static_cast<std::size_t>(6 + a)]};
    s.sp[a] = v.spacing[static_cast<std::size_t>(a)];
  }
  s.origin = {v.origin[0], v.origin[1], v.origin[2]};
  return s;
}

// The contours of one slice k of one frame, for every requested label.
std::vector<Contour> slice_contours(const LabelVolume& vol, const SliceAxes& g, int k,
                                    const std::vector<std::pair<int, std::string>>& labels,
                                    const MaskExtractOptions& opt, bool ras) {
  const int W = vol.dims[static_cast<std::size_t>(g.ia)], H = vol.dims[static_cast<std::size_t>(g.ib)];
  const std::size_t stride[3] = {1, static_cast<std::size_t>(vol.dims[0]),
                                 static_cast<std::size_t>(vol.dims[0]) * static_cast<std::size_t>(vol.dims[1])};
  const std::size_t base = stride[g.axis] * static_cast<std::size_t>(k);
  const std::size_t sa = stride[g.ia], sb = stride[g.ib];
  auto at = [&](int a, int b) {
    return vol.labels[base + sa * static_cast<std::size_t>(a) + sb * static_cast<std::size_t>(b)];
  };

  // One pass: bounding box of each requested label in this slice.
  const std::size_t nl = labels.size();
  std::vector<std::array<int, 4>> box(nl, {W, H, -1, -1});
  for (int b = 0; b < H; ++b)
    for (int a = 0; a < W; ++a) {
      const int32_t v = at(a, b);
      if (v == 0) continue;
      for (std::size_t l = 0; l < nl; ++l)
        if (labels[l].first == v) {
          auto& bx = box[l];
          bx[0] = std::min(bx[0], a), bx[1] = std::min(bx[1], b), bx[2] = std::max(bx[2], a),
          bx[3] = std::max(bx[3], b);
        }
    }

  std::vector<Contour> out;
  const int margin = 1 + static_cast<int>(std::ceil(3.0 * std::max(0.0, opt.presmooth_sigma_px)));
  const Vec3 slice_base = g.origin + (k * g.sp[g.axis]) * g.col[g.axis];
  const bool edge_fit = opt.staircase == StaircaseSmoothing::EdgeFit && !(opt.presmooth_sigma_px > 0.0);
  for (std::size_t l = 0; l < nl; ++l) {
    const auto& bx = box[l];
    if (bx[2] < 0) continue;
    const int x0 = bx[0] - margin, y0 = bx[1] - margin;
    const int w = bx[2] - bx[0] + 1 + 2 * margin, h = bx[3] - bx[1] + 1 + 2 * margin;
    std::vector<float> mask(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0.0f);
    for (int y = std::max(0, y0); y < std::min(H, y0 + h); ++y)
      for (int x = std::max(0, x0); x < std::min(W, x0 + w); ++x)
        if (at(x, y) == labels[l].first)
          mask[static_cast<std::size_t>(x - x0) + static_cast<std::size_t>(w) * static_cast<std::size_t>(y - y0)] =
              1.0f;
    if (opt.presmooth_sigma_px > 0.0) mask = gaussian_blur(mask, w, h, opt.presmooth_sigma_px);
    const auto chains = marching_squares(mask, w, h, 0.5f);
    for (const auto& chain : chains) {
      // In-plane millimetres (a·Δa, b·Δb); smoothing and resampling happen here.
      std::vector<Vec2> mm(chain.size());
      for (std::size_t i = 0; i < chain.size(); ++i)
        mm[i] = {(chain[i].x + x0) * g.sp[g.ia], (chain[i].y + y0) * g.sp[g.ib]};
      std::vector<Vec2> poly = mm;
      if (edge_fit) {
        // Whole-pixel offsets keep every crossing an edge midpoint (what the fit relies on).
        std::vector<Vec2> px(chain.size());
        for (std::size_t i = 0; i < chain.size(); ++i) px[i] = {chain[i].x + x0, chain[i].y + y0};
        poly = fit_mask_staircase(px, {g.sp[g.ia], g.sp[g.ib]});
      } else if (opt.staircase != StaircaseSmoothing::None) {
        smooth_closed_taubin(poly, opt.taubin_passes);
      }
      if (opt.resample_mm > 0.0) {
        double len = 0.0;
        for (std::size_t i = 0; i < poly.size(); ++i) len += norm(poly[(i + 1) % poly.size()] - poly[i]);
        const int count = std::max(opt.min_points, static_cast<int>(std::lround(len / opt.resample_mm)));
        poly = resample_closed(poly, count);
      }
      // Smoothing a one-pixel-wide neck can fold it; the raw chain is always simple.
      if (poly != mm && is_self_intersecting(poly)) poly = mm;
      Contour c;
      c.label = labels[l].second;
      c.slice = k;
      c.points.reserve(poly.size());
      for (const Vec2& q : poly) {
        Vec3 p = slice_base + (q.x) * g.col[g.ia] + (q.y) * g.col[g.ib];
        if (ras) p = {-p.x, -p.y, p.z};
        c.points.push_back(p);
      }
      out.push_back(std::move(c));
    }
  }
  return out;
}

}  // namespace

std::vector<std::pair<int, std::string>> resolve_labels(const LabelSeries& series, const MaskExtractOptions& options) {
  Location where;
  where.file = series.source;
  const LabelPreset* preset = nullptr;
  if (!options.preset.empty()) {
    preset = find_label_preset(options.preset);
    if (!preset) {
      std::string names;
      for (const LabelPreset& p : label_presets()) names += (names.empty() ? "" : ", ") + p.name;
      throw InvalidInput(ErrorCode::Usage, where, "unknown label preset '" + options.preset + "'",
                         "use one of: " + names);
    }
  }
  std::set<int> present;
  for (const LabelVolume& v : series.frames) {
    int32_t last = 0;
    for (int32_t x : v.labels)
      if (x != 0 && x != last) present.insert(last = x);
  }
  const std::string present_text = join_labels(present, preset);
  std::vector<std::pair<int, std::string>> out;
  auto name_of = [&](int v) {
    if (preset)
      if (auto n = preset_name(*preset, v)) return *n;
    return std::to_string(v);
  };
  if (options.labels.empty()) {
    if (present.empty())
      throw InvalidInput(ErrorCode::UnknownLabel, where, "the label image has no non-zero label",
                         "check that this is a segmentation, not the image itself");
    for (int v : present) out.emplace_back(v, name_of(v));
    return out;
  }
  for (const std::string& want : options.labels) {
    int value = 0;
    if (auto n = parse_int(want)) {
      value = *n;
    } else if (preset) {
      auto v = preset_value(*preset, want);
      if (!v) {
        std::string names;
        for (const auto& [n2, v2] : preset->labels) names += (names.empty() ? "" : ", ") + n2;
        throw InvalidInput(ErrorCode::UnknownLabel, where,
                           "label '" + want + "' is not in preset '" + preset->name + "'", "use one of: " + names);
      }
      value = *v;
    } else {
      throw InvalidInput(ErrorCode::UnknownLabel, where, "label '" + want + "' is not a number",
                         "give a label value, or name the labels with a preset (--labels acdc or mnms)");
    }
    if (value == 0 || !present.count(value))
      throw InvalidInput(ErrorCode::UnknownLabel, where,
                         "label " + want + (want == std::to_string(value) ? "" : " (" + std::to_string(value) + ")") +
                             " is absent from every frame",
                         "labels present: " + present_text);
    bool dup = false;
    for (const auto& [v, n] : out) dup = dup || v == value;
    if (!dup) out.emplace_back(value, name_of(value));
  }
  return out;
}

Sequence extract_mask_contours(const LabelSeries& series, const MaskExtractOptions& options) {
  Location where;
  where.file = series.source;
  if (series.frames.empty())
    throw InvalidInput(ErrorCode::EmptyFrame, where, "the label series has no frames", "give at least one label image");
  if (options.space != "LPS" && options.space != "RAS")
    throw InvalidInput(ErrorCode::Usage, where, "unknown space '" + options.space + "'", "use LPS or RAS");
  const auto labels = resolve_labels(series, options);
  const LabelVolume& v0 = series.frames.front();
  int axis = options.slice_axis;
  if (axis < -1 || axis > 2)
    throw InvalidInput(ErrorCode::Usage, where, "slice axis must be 0, 1 or 2",
                       "omit it to use the axis with the largest spacing");
  if (axis < 0) {
    axis = 2;
    for (int a = 1; a >= 0; --a)
      if (v0.spacing[static_cast<std::size_t>(a)] > v0.spacing[static_cast<std::size_t>(axis)]) axis = a;
  }
  const SliceAxes g = slice_axes(v0, axis);
  const bool ras = options.space == "RAS";
  const int nk = v0.dims[static_cast<std::size_t>(axis)];
  const std::size_t nf = series.frames.size();
  std::vector<std::vector<Contour>> per(nf * static_cast<std::size_t>(nk));
  tbb::parallel_for(std::size_t{0}, per.size(), [&](std::size_t item) {
    const std::size_t f = item / static_cast<std::size_t>(nk);
    const int k = static_cast<int>(item % static_cast<std::size_t>(nk));
    per[item] = slice_contours(series.frames[f], g, k, labels, options, ras);
  });
  std::vector<RawContour> raw;
  for (std::size_t f = 0; f < nf; ++f) {
    int index = 0;
    for (int k = 0; k < nk; ++k)
      for (Contour& c : per[f * static_cast<std::size_t>(nk) + static_cast<std::size_t>(k)]) {
        RawContour rc;
        rc.frame = static_cast<int>(f);
        rc.index = index++;
        rc.contour = std::move(c);
        raw.push_back(std::move(rc));
      }
  }
  std::vector<double> times = series.times_ms;
  if (times.size() != nf) {
    times.resize(nf);
    for (std::size_t f = 0; f < nf; ++f) times[f] = static_cast<double>(f);
  }
  Sequence seq = build_sequence(raw, static_cast<int>(nf), times, series.source, options.stack);
  seq.space = options.space;
  return seq;
}

InputResult read_label_image_contours(const std::filesystem::path& input, const MaskExtractOptions& options) {
  InputResult r;
  const LabelSeries series = read_label_series(input);
  r.sequence = extract_mask_contours(series, options);
  r.format = "label-image";
  std::set<std::string> files(series.files.begin(), series.files.end());
  r.notes.push_back(std::to_string(series.frames.size()) + " frame(s) from " + std::to_string(files.size()) +
                    " label image file(s)");
  const LabelVolume& v = series.frames.front();
  r.notes.push_back("volume " + std::to_string(v.dims[0]) + "x" + std::to_string(v.dims[1]) + "x" +
                    std::to_string(v.dims[2]) + " voxels; coordinates " + r.sequence.space + " mm");
  int axis = options.slice_axis;
  if (axis < 0) {
    axis = 2;
    for (int a = 1; a >= 0; --a)
      if (v.spacing[static_cast<std::size_t>(a)] > v.spacing[static_cast<std::size_t>(axis)]) axis = a;
  }
  r.notes.push_back("slices along voxel axis " + std::to_string(axis) + " (" +
                    std::to_string(v.spacing[static_cast<std::size_t>(axis)]) + " mm apart); slice id = voxel index");
  std::string ls;
  for (const auto& [val, name] : resolve_labels(series, options))
    ls += (ls.empty() ? "" : ", ") + name + (name == std::to_string(val) ? "" : "=" + std::to_string(val));
  r.notes.push_back("labels: " + ls);
  std::size_t n = 0;
  for (const Frame& f : r.sequence.frames)
    for (const Slice& s : f.slices) n += s.contours.size();
  const std::string smoothing =
      options.staircase == StaircaseSmoothing::None ? "no smoothing"
      : options.staircase == StaircaseSmoothing::EdgeFit && !(options.presmooth_sigma_px > 0.0)
          ? "sub-pixel edge fit"
          : "Taubin " + std::to_string(options.taubin_passes) + " passes";
  r.notes.push_back(std::to_string(n) + " contours extracted (marching squares, " + smoothing + ", resampled every " +
                    fmt_mm(options.resample_mm) + " mm)");
  return r;
}

}  // namespace c4d
