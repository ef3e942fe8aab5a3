// Label images: ITK round trips (NIfTI, NRRD, MetaImage; 3D, 4D, one file per frame) and contour
// extraction checked against the exact sections of analytic shapes on an oblique grid.
#include "contour4d/io/images.h"

#include <gtest/gtest.h>

#include "cli_runner.h"

#include "ellipse_distance.h"
#include <tbb/global_control.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>

#include "contour4d/core/errors.h"
#include "contour4d/extract/mask_contours.h"
#include "contour4d/phantoms/rasterize.h"

namespace c4d {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("c4d_images_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Rotation of 30° about (1, 2, 3)/√14: an oblique direction matrix (columns = voxel axes).
std::array<double, 9> oblique() {
  const double th = std::numbers::pi / 6, c = std::cos(th), s = std::sin(th), t = 1 - c;
  const double n = std::sqrt(14.0), x = 1 / n, y = 2 / n, z = 3 / n;
  return {t * x * x + c,     t * x * y - s * z, t * x * z + s * y,  //
          t * x * y + s * z, t * y * y + c,     t * y * z - s * x,  //
          t * x * z - s * y, t * y * z + s * x, t * z * z + c};
}

// A shape in its local frame (mm, centred on the grid): inside(p) and the distance from a point of
// the slice plane z to the exact section curve.
struct Shape {
  std::function<bool(Vec3)> inside;
  std::function<double(double x, double y, double z)> section_distance;
};

Shape ellipsoid(double a, double b, double c) {
  Shape s;
  s.inside = [=](Vec3 p) { return p.x * p.x / (a * a) + p.y * p.y / (b * b) + p.z * p.z / (c * c) < 1; };
  s.section_distance = [=](double x, double y, double z) {
    const double k = std::sqrt(std::max(0.0, 1 - z * z / (c * c)));
    const double ea = a * k, eb = b * k;
    return c4d::test::ellipse_distance_aligned(ea, eb, x, y, 4000);
  };
  return s;
}

Shape torus(double R, double r) {
  Shape s;
  s.inside = [=](Vec3 p) {
    const double q = std::hypot(p.x, p.y) - R;
    return q * q + p.z * p.z < r * r;
  };
  s.section_distance = [=](double x, double y, double z) {
    const double w = std::sqrt(std::max(0.0, r * r - z * z));
    const double rho = std::hypot(x, y);
    return std::min(std::abs(rho - (R - w)), std::abs(rho - (R + w)));
  };
  return s;
}

struct Grid {
  LabelVolume vol;
  Vec3 centre;  // local origin in voxel-scaled coordinates (i·Δ0, j·Δ1, k·Δ2)
};

Grid rasterise(const Shape& shape, std::array<int, 3> dims, std::array<double, 3> spacing, int label = 1) {
  Grid g;
  g.vol.dims = dims;
  g.vol.spacing = spacing;
  g.vol.origin = {12, -7, 33};
  g.vol.direction = oblique();
  // Centre between voxels in-plane (no symmetry luck), and mid-way between two slices.
  g.centre = {(dims[0] - 1) * spacing[0] / 2 + 0.37, (dims[1] - 1) * spacing[1] / 2 - 0.21,
              (dims[2] - 1) * spacing[2] / 2};
  g.vol.labels.assign(static_cast<std::size_t>(dims[0] * dims[1] * dims[2]), 0);
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i) {
        const Vec3 p = Vec3{i * spacing[0], j * spacing[1], k * spacing[2]} - g.centre;
        if (shape.inside(p)) g.vol.labels[static_cast<std::size_t>(i + dims[0] * (j + dims[1] * k))] = label;
      }
  return g;
}

// World -> local shape frame: local = Dᵀ (p − origin) − centre.
Vec3 to_local(const Grid& g, Vec3 p) {
  const auto& D = g.vol.direction;
  const Vec3 d = p - Vec3{g.vol.origin[0], g.vol.origin[1], g.vol.origin[2]};
  return Vec3{D[0] * d.x + D[3] * d.y + D[6] * d.z, D[1] * d.x + D[4] * d.y + D[7] * d.z,
              D[2] * d.x + D[5] * d.y + D[8] * d.z} -
         g.centre;
}

double max_section_error(const Sequence& seq, const Grid& g, const Shape& s, std::size_t* points = nullptr,
                         double* rms = nullptr) {
  double worst = 0, sum2 = 0;
  std::size_t n = 0;
  for (const Frame& f : seq.frames)
    for (const Slice& sl : f.slices)
      for (const Contour& c : sl.contours)
        for (const Vec3& p : c.points) {
          const Vec3 q = to_local(g, p);
          const double e = s.section_distance(q.x, q.y, q.z);
          worst = std::max(worst, e);
          sum2 += e * e;
          ++n;
        }
  if (points) *points = n;
  if (rms) *rms = n ? std::sqrt(sum2 / static_cast<double>(n)) : 0.0;
  return worst;
}

void expect_same_geometry(const LabelVolume& a, const LabelVolume& b) {
  EXPECT_EQ(a.dims, b.dims);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(a.spacing[static_cast<std::size_t>(i)], b.spacing[static_cast<std::size_t>(i)], 1e-5);
    EXPECT_NEAR(a.origin[static_cast<std::size_t>(i)], b.origin[static_cast<std::size_t>(i)], 1e-4);
  }
  for (int i = 0; i < 9; ++i)
    EXPECT_NEAR(a.direction[static_cast<std::size_t>(i)], b.direction[static_cast<std::size_t>(i)], 1e-5);
  EXPECT_EQ(a.labels, b.labels);
}

template <typename F>
ErrorCode code_of_at(int line, F&& f) {
  try {
    f();
  } catch (const Error& e) {
    EXPECT_FALSE(std::string(e.what()).empty());
    return e.code();
  }
  ADD_FAILURE() << "no error thrown (test line " << line << ")";
  return ErrorCode::Internal;
}
#define code_of(f) code_of_at(__LINE__, f)

TEST(LabelImages, RoundTripAnalyticShapesOnAnObliqueGridWithinHalfAPixel) {
  const fs::path dir = temp_dir("roundtrip");
  struct Case {
    const char* name;
    Shape shape;
    std::array<int, 3> dims;
    std::array<double, 3> spacing;
    std::size_t contours_per_slice;  // 0: any
  };
  const Case cases[] = {
      {"ellipsoid", ellipsoid(25, 18, 30), {64, 52, 10}, {1.0, 1.0, 6.0}, 1},
      {"torus", torus(20, 8), {60, 64, 4}, {1.0, 1.0, 5.0}, 2},
      {"ellipsoid-aniso", ellipsoid(25, 18, 30), {64, 52, 10}, {1.0, 0.9, 6.0}, 1},
      {"torus-aniso", torus(20, 8), {60, 64, 4}, {1.1, 0.95, 5.0}, 2},
  };
  for (const Case& c : cases)
    for (const char* ext : {".nii.gz", ".nrrd", ".nii", ".mha"}) {
      SCOPED_TRACE(std::string(c.name) + ext);
      const Grid g = rasterise(c.shape, c.dims, c.spacing);
      const fs::path file = dir / (std::string(c.name) + ext);
      write_label_volume(file, {g.vol});
      const LabelSeries series = read_label_series(file);
      ASSERT_EQ(series.frames.size(), 1u);
      expect_same_geometry(g.vol, series.frames[0]);
      const Sequence seq = extract_mask_contours(series);
      ASSERT_EQ(seq.frames.size(), 1u);
      EXPECT_EQ(seq.space, "LPS");
      // Slice normal is the third direction column (slice axis: largest spacing).
      const Vec3 n{g.vol.direction[2], g.vol.direction[5], g.vol.direction[8]};
      EXPECT_NEAR(std::abs(dot(seq.normal, n)), 1.0, 1e-9);
      for (const Slice& s : seq.frames[0].slices) {
        if (c.contours_per_slice) {
          EXPECT_EQ(s.contours.size(), c.contours_per_slice) << "slice " << s.id;
        }
        for (const Contour& ct : s.contours) EXPECT_EQ(ct.label, "1");
      }
      std::size_t points = 0;
      double rms = 0;
      const double err = max_section_error(seq, g, c.shape, &points, &rms);
      // Half a pixel (of the smaller in-plane spacing when they differ); on average far better.
      const double px_min = std::min(c.spacing[0], c.spacing[1]);
      EXPECT_LE(err, 0.5 * px_min) << points << " points";
      EXPECT_LT(rms, 0.15 * px_min);
      std::printf(
          "[ figure ] %s%s: distance to the exact section max %.3f mm (%.2f px), rms %.3f mm (%.2f px), %zu points\n",
          c.name, ext, err, err / px_min, rms, rms / px_min, points);
      if (std::string(ext) == ".nii.gz") {
        MaskExtractOptions raw, gauss, t10;
        raw.staircase = StaircaseSmoothing::None;
        raw.resample_mm = 0;
        gauss.presmooth_sigma_px = 1.0;
        t10.staircase = StaircaseSmoothing::Taubin;
        for (auto [name, o] : {std::pair{"raw staircase", raw}, {"gauss 1.0 + taubin", gauss}, {"taubin 10", t10}}) {
          double r = 0;
          const double e = max_section_error(extract_mask_contours(series, o), g, c.shape, nullptr, &r);
          std::printf("[ figure ] %s, %s: max %.3f mm, rms %.3f mm\n", c.name, name, e, r);
        }
      }
    }
  fs::remove_all(dir);
}

// Distance (mm) from p to the closest exact section of slice `id` of frame `f` of the phantom (its
// contours, whose vertices lie on the analytic surface about 0.25 mm apart: chord error < 0.005 mm).
double section_distance(const Phantom& ph, int f, int id, Vec3 p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Slice& s : ph.contours.frames[static_cast<std::size_t>(f)].slices)
    if (s.id == id)
      for (const Contour& c : s.contours)
        for (std::size_t i = 0; i < c.points.size(); ++i) {
          const Vec3 a = c.points[i], b = c.points[(i + 1) % c.points.size()], ab = b - a;
          const double t = std::clamp(dot(p - a, ab) / std::max(dot(ab, ab), 1e-300), 0.0, 1.0);
          best = std::min(best, norm(p - (a + t * ab)));
        }
  return best;
}

// Each phantom (oblique, so the image's direction matrix is oblique) sampled on 1 mm pixels with
// 5–8 mm slices, written as NIfTI and NRRD, read back and traced: every extracted point lies within
// half a pixel of the exact section of its slice (the phantom's own contour on that plane).
TEST(LabelImages, RoundTripPhantomsOnAnObliqueGridWithinHalfAPixel) {
  const fs::path dir = temp_dir("roundtrip");
  struct Case {
    const char* name;
    double spacing;  // slice spacing (mm)
    int frame;       // which frame of the phantom
  };
  const Case cases[] = {{"ellipsoid", 6.0, 0},     {"ellipsoid", 8.0, 10},    {"torus", 5.0, 0},
                        {"left-heart-ed", 5.0, 0}, {"left-heart-es", 5.0, 0}, {"left-heart-ed", 8.0, 0}};
  const double px = 1.0;
  double worst_px = 0;
  for (const Case& c : cases) {
    PhantomOptions po;
    po.spacing = c.spacing;
    po.oblique = true;
    po.truth_edge = 0.25;
    const Phantom ph = make_phantom(c.name, po);
    RasterizeOptions ro;
    ro.pixel_x = ro.pixel_y = px;
    const std::vector<LabelVolume> vols = rasterize_phantom(ph, ro);
    ASSERT_EQ(vols.size(), ph.truth.size());
    for (const char* ext : {".nii.gz", ".nrrd"}) {
      SCOPED_TRACE(std::string(c.name) + ext);
      const fs::path file = dir / (std::string(c.name) + ext);
      write_label_volume(file, {vols[static_cast<std::size_t>(c.frame)]});
      const LabelSeries series = read_label_series(file);
      ASSERT_EQ(series.frames.size(), 1u);
      expect_same_geometry(vols[static_cast<std::size_t>(c.frame)], series.frames[0]);
      const auto& D = series.frames[0].direction;
      EXPECT_GT(std::min({std::abs(D[1]), std::abs(D[3]), std::abs(D[5])}), 0.05) << "direction matrix not oblique";
      const Sequence seq = extract_mask_contours(series);
      EXPECT_NEAR(std::abs(dot(seq.normal, ph.contours.normal)), 1.0, 1e-9);
      double worst = 0, sum2 = 0;
      std::size_t n = 0, contours = 0;
      for (const Slice& s : seq.frames[0].slices)
        for (const Contour& ct : s.contours) {
          ++contours;
          for (const Vec3& p : ct.points) {
            const double e = section_distance(ph, c.frame, s.id, p);
            worst = std::max(worst, e);
            sum2 += e * e;
            ++n;
          }
        }
      std::size_t exact = 0;
      for (const Slice& s : ph.contours.frames[static_cast<std::size_t>(c.frame)].slices) exact += s.contours.size();
      // Every exact section wider than a pixel shows up (the smallest apex/cap sections may not).
      EXPECT_GE(contours + 2, exact);
      ASSERT_GT(n, 0u);
      const double rms = std::sqrt(sum2 / static_cast<double>(n));
      worst_px = std::max(worst_px, worst / px);
      std::printf(
          "[ figure ] %s frame %d, %.0f mm slices%s: distance to the exact section max %.3f mm (%.2f px), "
          "rms %.3f mm, %zu contours (%zu exact), %zu points\n",
          c.name, c.frame, c.spacing, ext, worst, worst / px, rms, contours, exact, n);
      EXPECT_LE(worst, 0.5 * px);
      EXPECT_LT(rms, 0.15 * px);
      if (std::string(ext) == ".nii.gz") {
        MaskExtractOptions raw, taubin;
        raw.staircase = StaircaseSmoothing::None;
        raw.resample_mm = 0;
        taubin.staircase = StaircaseSmoothing::Taubin;
        for (auto [label, o] : {std::pair{"raw staircase", raw}, {"taubin 10", taubin}}) {
          double e = 0, r2 = 0;
          std::size_t m = 0;
          const Sequence other = extract_mask_contours(series, o);
          for (const Slice& s : other.frames[0].slices)
            for (const Contour& ct : s.contours)
              for (const Vec3& p : ct.points) {
                const double d = section_distance(ph, c.frame, s.id, p);
                e = std::max(e, d), r2 += d * d, ++m;
              }
          std::printf("[ figure ]   %s: max %.3f mm, rms %.3f mm\n", label, e, std::sqrt(r2 / static_cast<double>(m)));
        }
      }
    }
  }
  std::printf("[ figure ] round trip, all phantoms: worst point %.3f px (target <= 0.5 px)\n", worst_px);
  fs::remove_all(dir);
}

TEST(LabelImages, RasSpaceNegatesXAndY) {
  const Grid g = rasterise(ellipsoid(10, 8, 12), {30, 30, 5}, {1, 1, 5});
  LabelSeries s;
  s.frames = {g.vol};
  s.source = "memory";
  const Sequence lps = extract_mask_contours(s);
  MaskExtractOptions o;
  o.space = "RAS";
  const Sequence ras = extract_mask_contours(s, o);
  EXPECT_EQ(ras.space, "RAS");
  const Vec3 p = lps.frames[0].slices[0].contours[0].points[0];
  const Vec3 q = ras.frames[0].slices[0].contours[0].points[0];
  EXPECT_DOUBLE_EQ(p.x, -q.x);
  EXPECT_DOUBLE_EQ(p.y, -q.y);
  EXPECT_DOUBLE_EQ(p.z, q.z);
}

TEST(LabelImages, FourDFileAndOneFilePerFrameGiveTheSameFrames) {
  const fs::path dir = temp_dir("frames");
  Grid a = rasterise(ellipsoid(12, 10, 14), {32, 32, 6}, {1, 1, 6}, 3);
  Grid b = rasterise(ellipsoid(10, 9, 12), {32, 32, 6}, {1, 1, 6}, 3);
  write_label_volume(dir / "cine.nii.gz", {a.vol, b.vol});
  const LabelSeries four = read_label_series(dir / "cine.nii.gz");
  ASSERT_EQ(four.frames.size(), 2u);
  expect_same_geometry(a.vol, four.frames[0]);
  expect_same_geometry(b.vol, four.frames[1]);

  // ACDC layout: ground truth beside images; frame 2 before frame 10 (natural order).
  fs::create_directories(dir / "patient");
  write_label_volume(dir / "patient" / "p_frame10_gt.nii.gz", {b.vol});
  write_label_volume(dir / "patient" / "p_frame2_gt.nii.gz", {a.vol});
  write_label_volume(dir / "patient" / "p_frame2.nii.gz", {a.vol}, {ImagePixel::Float32, 0.25});
  const LabelSeries folder = read_label_series(dir / "patient");
  ASSERT_EQ(folder.frames.size(), 2u);
  EXPECT_EQ(folder.frames[0].labels, a.vol.labels);
  EXPECT_EQ(folder.frames[1].labels, b.vol.labels);
  const LabelSeries glob = read_label_series(dir / "patient" / "p_frame*_gt.nii.gz");
  ASSERT_EQ(glob.frames.size(), 2u);
  EXPECT_EQ(glob.frames[1].labels, b.vol.labels);
  EXPECT_TRUE(is_label_image_input(dir / "patient"));
  EXPECT_TRUE(is_label_image_input(dir / "patient" / "p_frame*_gt.nii.gz"));
  EXPECT_FALSE(is_label_image_input(dir / "nothing.json"));

  MaskExtractOptions o;
  o.preset = "acdc";
  o.labels = {"lv"};
  const Sequence seq = extract_mask_contours(four, o);
  ASSERT_EQ(seq.frames.size(), 2u);
  for (const Frame& f : seq.frames)
    for (const Slice& s : f.slices)
      for (const Contour& c : s.contours) EXPECT_EQ(c.label, "lv");
  fs::remove_all(dir);
}

TEST(LabelImages, FloatImageOfWholeNumbersIsAccepted) {
  const fs::path dir = temp_dir("float");
  const Grid g = rasterise(ellipsoid(10, 8, 12), {30, 30, 5}, {1, 1, 5}, 2);
  write_label_volume(dir / "f.nrrd", {g.vol}, {ImagePixel::Float32, 1.0});
  EXPECT_EQ(read_label_series(dir / "f.nrrd").frames[0].labels, g.vol.labels);
  fs::remove_all(dir);
}

TEST(LabelImages, SliceAxisAutoAndExplicit) {
  const Grid g = rasterise(ellipsoid(10, 12, 14), {6, 30, 30}, {5, 1, 1});
  LabelSeries s;
  s.frames = {g.vol};
  const Sequence seq = extract_mask_contours(s);
  const Vec3 n0{g.vol.direction[0], g.vol.direction[3], g.vol.direction[6]};
  EXPECT_NEAR(std::abs(dot(seq.normal, n0)), 1.0, 1e-9);
  MaskExtractOptions o;
  o.slice_axis = 2;
  const Sequence seq2 = extract_mask_contours(s, o);
  const Vec3 n2{g.vol.direction[2], g.vol.direction[5], g.vol.direction[8]};
  EXPECT_NEAR(std::abs(dot(seq2.normal, n2)), 1.0, 1e-9);
  for (const Slice& sl : seq2.frames[0].slices) EXPECT_TRUE(sl.id >= 0 && sl.id < 30);
}

TEST(LabelImages, DeterministicWhateverTheThreadCount) {
  const Grid g = rasterise(torus(12, 5), {40, 40, 8}, {1, 1, 2});
  LabelSeries s;
  s.frames = {g.vol, g.vol, g.vol};
  Sequence one, many;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = extract_mask_contours(s);
  }
  many = extract_mask_contours(s);
  ASSERT_EQ(one.frames.size(), many.frames.size());
  for (std::size_t f = 0; f < one.frames.size(); ++f) {
    ASSERT_EQ(one.frames[f].slices.size(), many.frames[f].slices.size());
    for (std::size_t i = 0; i < one.frames[f].slices.size(); ++i) {
      const auto& a = one.frames[f].slices[i].contours;
      const auto& b = many.frames[f].slices[i].contours;
      ASSERT_EQ(a.size(), b.size());
      for (std::size_t c = 0; c < a.size(); ++c) {
        ASSERT_EQ(a[c].points.size(), b[c].points.size());
        for (std::size_t p = 0; p < a[c].points.size(); ++p) EXPECT_TRUE(a[c].points[p] == b[c].points[p]);
      }
    }
  }
}

TEST(LabelImages, CorpusFilesAgreeAcrossFormats) {
  const fs::path dir = fs::path(C4D_CORPUS_DIR) / "images";
  const std::vector<LabelVolume> ref = read_label_image(dir / "tiny.nii.gz");
  ASSERT_EQ(ref.size(), 1u);
  EXPECT_EQ(ref[0].dims, (std::array<int, 3>{8, 8, 3}));
  EXPECT_NEAR(ref[0].spacing[2], 6.0, 1e-9);
  // nibabel wrote RAS (-10, 5, 20); ITK gives LPS.
  EXPECT_NEAR(ref[0].origin[0], 10.0, 1e-6);
  EXPECT_NEAR(ref[0].origin[1], -5.0, 1e-6);
  EXPECT_EQ(ref[0].labels[2 + 8 * (2 + 8 * 0)], 1);
  EXPECT_EQ(ref[0].labels[3 + 8 * (3 + 8 * 1)], 2);
  for (const char* f : {"tiny.nii", "tiny.nrrd", "tiny.mha"}) {
    const std::vector<LabelVolume> v = read_label_image(dir / f);
    ASSERT_EQ(v.size(), 1u) << f;
    EXPECT_EQ(v[0].labels, ref[0].labels) << f;
    expect_same_geometry(v[0], ref[0]);
  }
  const InputResult r = read_label_image_contours(dir / "tiny.nrrd");
  EXPECT_EQ(r.format, "label-image");
  EXPECT_EQ(r.sequence.frames.size(), 1u);
  EXPECT_EQ(labels(r.sequence), (std::vector<std::string>{"1", "2"}));
}

TEST(LabelImagesBadInput, EachFailureHasItsOwnCode) {
  const fs::path dir = temp_dir("bad");
  const Grid g = rasterise(ellipsoid(10, 8, 12), {30, 30, 5}, {1, 1, 5}, 1);

  // Non-integer values.
  write_label_volume(dir / "half.nii.gz", {g.vol}, {ImagePixel::Float32, 0.5});
  EXPECT_EQ(code_of([&] { read_label_series(dir / "half.nii.gz"); }), ErrorCode::Format);

  // A 2D image.
  LabelVolume flat = g.vol;
  flat.dims[2] = 1;
  flat.labels.resize(30 * 30);
  write_label_volume(dir / "flat.nrrd", {flat}, {ImagePixel::Int16, 1.0, true});
  EXPECT_EQ(code_of([&] { read_label_series(dir / "flat.nrrd"); }), ErrorCode::Format);

  // A label that is absent, and a name without a preset, and an unknown preset name.
  LabelSeries s;
  s.frames = {g.vol};
  MaskExtractOptions o;
  o.labels = {"7"};
  EXPECT_EQ(code_of([&] { extract_mask_contours(s, o); }), ErrorCode::UnknownLabel);
  o.labels = {"lv"};
  EXPECT_EQ(code_of([&] { extract_mask_contours(s, o); }), ErrorCode::UnknownLabel);
  o.preset = "acdc";  // lv = 3, absent
  EXPECT_EQ(code_of([&] { extract_mask_contours(s, o); }), ErrorCode::UnknownLabel);
  o.labels = {"liver"};
  EXPECT_EQ(code_of([&] { extract_mask_contours(s, o); }), ErrorCode::UnknownLabel);
  LabelSeries empty = s;
  std::fill(empty.frames[0].labels.begin(), empty.frames[0].labels.end(), 0);
  EXPECT_EQ(code_of([&] { extract_mask_contours(empty); }), ErrorCode::UnknownLabel);

  // Frames of different sizes; of different orientation.
  fs::create_directories(dir / "sizes");
  write_label_volume(dir / "sizes" / "a.nii.gz", {g.vol});
  write_label_volume(dir / "sizes" / "b.nii.gz", {rasterise(ellipsoid(10, 8, 12), {32, 30, 5}, {1, 1, 5}).vol});
  EXPECT_EQ(code_of([&] { read_label_series(dir / "sizes"); }), ErrorCode::Format);
  fs::create_directories(dir / "turned");
  LabelVolume turned = g.vol;
  turned.direction = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  write_label_volume(dir / "turned" / "a.nii.gz", {g.vol});
  write_label_volume(dir / "turned" / "b.nii.gz", {turned});
  EXPECT_EQ(code_of([&] { read_label_series(dir / "turned"); }), ErrorCode::NotParallel);

  // A frame without the label.
  LabelSeries gap = s;
  gap.frames.push_back(empty.frames[0]);
  EXPECT_EQ(code_of([&] { extract_mask_contours(gap); }), ErrorCode::EmptyFrame);

  // Truncated .nii.gz, every prefix length class: header only, half, all but the last bytes.
  write_label_volume(dir / "whole.nii.gz", {g.vol});
  std::ifstream in(dir / "whole.nii.gz", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  for (std::size_t keep : {std::size_t{40}, bytes.size() / 2, bytes.size() - 9}) {
    std::ofstream(dir / "cut.nii.gz", std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(keep));
    const ErrorCode c = code_of([&] { read_label_series(dir / "cut.nii.gz"); });
    EXPECT_EQ(c, ErrorCode::Parse) << "kept " << keep << " of " << bytes.size() << " bytes";
  }

  // A PNG renamed .nii: named for what it is.
  std::ofstream(dir / "photo.nii", std::ios::binary)
      << std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16) << std::string(200, 'x');
  try {
    read_label_series(dir / "photo.nii");
    ADD_FAILURE() << "a PNG read as a label image";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::Format);
    EXPECT_NE(std::string(e.what()).find("this is a PNG image, not a NIfTI"), std::string::npos) << e.what();
  }

  // A printf-style data file pattern, which crashes ITK's MetaIO (found by fuzz_images).
  EXPECT_EQ(code_of([&] { read_label_series(fs::path(C4D_CORPUS_DIR) / "images-bad" / "bad_13_printf_pattern.mha"); }),
            ErrorCode::Format);

  // Negative dimensions, which hang ITK's MetaIO (found by fuzz_images).
  EXPECT_EQ(code_of([&] { read_label_series(fs::path(C4D_CORPUS_DIR) / "images-bad" / "bad_13_negative_ndims.mha"); }),
            ErrorCode::Format);

  // Missing file; MetaImage header whose data file is missing; empty file.
  EXPECT_EQ(code_of([&] { read_label_series(dir / "none.nii.gz"); }), ErrorCode::FileNotFound);
  std::ofstream(dir / "lone.mhd") << "ObjectType = Image\nNDims = 3\nDimSize = 4 4 4\nElementType = MET_SHORT\n"
                                     "ElementDataFile = lone.raw\n";
  EXPECT_EQ(code_of([&] { read_label_series(dir / "lone.mhd"); }), ErrorCode::MissingCompanion);
  std::ofstream(dir / "zero.nii").close();
  EXPECT_EQ(code_of([&] { read_label_series(dir / "zero.nii"); }), ErrorCode::EmptyFile);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace c4d

// End to end through the CLI: each bad image input gets its own exit code and leaves nothing behind
// (`extract` and `reconstruct`), and the Sunnybrook reader names a missing DICOM image.
namespace c4d {
namespace {

using test::run_cli;

TEST(LabelImagesCli, BadInputsExitWithTheirCodeAndWriteNothing) {
  ASSERT_TRUE(fs::exists(C4D_CLI)) << "CLI not built: " << C4D_CLI;
  const fs::path dir = temp_dir("cli_bad");
  const fs::path in = dir / "in", out = dir / "out";
  fs::create_directories(in);
  fs::create_directories(out);
  const Grid g = rasterise(ellipsoid(10, 8, 12), {30, 30, 5}, {1, 1, 5}, 1);
  write_label_volume(in / "good.nii.gz", {g.vol});
  write_label_volume(in / "half.nii.gz", {g.vol}, {ImagePixel::Float32, 0.5});
  LabelVolume flat = g.vol;
  flat.dims[2] = 1;
  flat.labels.resize(30 * 30);
  write_label_volume(in / "flat.nrrd", {flat}, {ImagePixel::Int16, 1.0, true});
  {
    std::ifstream f(in / "good.nii.gz", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(f)), {});
    std::ofstream(in / "truncated.nii.gz", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  fs::create_directories(in / "sizes");
  write_label_volume(in / "sizes" / "a.nii.gz", {g.vol});
  write_label_volume(in / "sizes" / "b.nii.gz", {rasterise(ellipsoid(10, 8, 12), {32, 30, 5}, {1, 1, 5}).vol});
  LabelVolume empty = g.vol;
  std::fill(empty.labels.begin(), empty.labels.end(), 0);
  write_label_volume(in / "empty.nii.gz", {empty});
  std::ofstream(in / "notanimage.nii") << "this is not a NIfTI file\n";

  // A Sunnybrook folder whose contour file names a DICOM image that is absent.
  const fs::path sb = fs::path(C4D_DATA_DIR) / "sunnybrook-SC-HF-I-1";
  ASSERT_TRUE(fs::is_directory(sb)) << "real data folder missing: " << sb;
  const fs::path sbc = in / "sunnybrook";
  fs::copy(sb, sbc, fs::copy_options::recursive);
  std::vector<fs::path> dicoms;
  for (const auto& e : fs::directory_iterator(sbc / "dicoms_contoured")) dicoms.push_back(e.path());
  std::sort(dicoms.begin(), dicoms.end());
  ASSERT_FALSE(dicoms.empty());
  fs::remove(dicoms.front());

  struct Case {
    std::string input, extra;
    ErrorCode code;
  };
  const Case cases[] = {
      {(in / "half.nii.gz").string(), "", ErrorCode::Format},                 // non-integer labels
      {(in / "flat.nrrd").string(), "", ErrorCode::Format},                   // a 2D image
      {(in / "sizes").string(), "", ErrorCode::Format},                       // frames of different sizes
      {(in / "truncated.nii.gz").string(), "", ErrorCode::Parse},             // corrupt (truncated) file
      {(in / "notanimage.nii").string(), "", ErrorCode::Parse},               // not an image at all
      {(in / "empty.nii.gz").string(), "", ErrorCode::UnknownLabel},          // no label in any frame
      {(in / "good.nii.gz").string(), "--label 7", ErrorCode::UnknownLabel},  // the asked label is absent
      {sbc.string(), "", ErrorCode::MissingCompanion},                        // a contour's DICOM image is missing
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.input + " " + c.extra);
    EXPECT_EQ(run_cli("extract '" + c.input + "' " + c.extra + " -o '" + (out / "x.json").string() + "'"),
              static_cast<int>(c.code));
    EXPECT_EQ(run_cli("reconstruct '" + c.input + "' " + c.extra + " -o '" + (out / "mesh").string() + "'"),
              static_cast<int>(c.code));
    EXPECT_TRUE(fs::is_empty(out)) << "a failed run left files behind";
  }
  // The good file goes through.
  EXPECT_EQ(run_cli("extract '" + (in / "good.nii.gz").string() + "' -o '" + (out / "x.json").string() + "'"), 0);
  EXPECT_TRUE(fs::exists(out / "x.json"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace c4d
