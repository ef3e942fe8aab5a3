// Phantoms as point-sampled label masks.
//
// Reference: Miara et al., "New Method for 4D Reconstruction of Medical Images", §III.B and Fig. 18:
// the method starts from segmented slices, and its benefit over marching cubes shows on a mask whose
// slices are far apart. The mask is sampled at voxel centres from the phantom's analytic inside test,
// on the phantom's own slice planes, so its exact sections are the phantom's contours.
#include "contour4d/phantoms/rasterize.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "contour4d/core/errors.h"

namespace c4d {
namespace {

// Slice id -> signed offset along the sequence normal: offset(id) = base + id · step.
struct Lattice {
  double base = 0, step = 0;
  int count = 0;
};

Lattice slice_lattice(const Phantom& ph) {
  int id_lo = std::numeric_limits<int>::max(), id_hi = std::numeric_limits<int>::min();
  double off_lo = 0, off_hi = 0;
  for (const Frame& f : ph.contours.frames)
    for (const Slice& s : f.slices) {
      if (s.id < id_lo) id_lo = s.id, off_lo = s.offset;
      if (s.id > id_hi) id_hi = s.id, off_hi = s.offset;
    }
  if (id_lo >= id_hi)
    throw InvalidInput(ErrorCode::Usage, {},
                       "phantom " + ph.name + " has fewer than two slice planes: nothing to stack",
                       "use a smaller slice spacing");
  Lattice l;
  l.step = (off_hi - off_lo) / (id_hi - id_lo);
  l.base = off_lo - id_lo * l.step;
  l.count = id_hi + 1;
  return l;
}

}  // namespace

std::vector<LabelVolume> rasterize_phantom(const Phantom& ph, const RasterizeOptions& o) {
  if (!(o.pixel_x > 0 && o.pixel_x <= 100 && o.pixel_y > 0 && o.pixel_y <= 100))
    throw InvalidInput(ErrorCode::Usage, {}, "mask voxel size out of range",
                       "give an in-plane voxel size in (0, 100] mm");
  if (!(o.margin >= 0 && o.margin <= 1000))
    throw InvalidInput(ErrorCode::Usage, {}, "mask margin out of range", "give a margin in [0, 1000] mm");
  if (o.label < 1 || o.label > 32767)
    throw InvalidInput(ErrorCode::Usage, {}, "mask label out of range", "give a label in 1..32767");
  const Lattice lat = slice_lattice(ph);

  // In-plane axes: two local axes in cyclic order after the slice axis (z: x, y; y: z, x), moved by
  // the oblique rotation when the phantom is oblique, so that i × j is ± the slice normal.
  const Vec3 n = ph.contours.normal;
  const std::array<Vec3, 3> R =
      ph.oblique ? oblique_rotation() : std::array<Vec3, 3>{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  auto place = [&R](Vec3 v) { return Vec3{dot(R[0], v), dot(R[1], v), dot(R[2], v)}; };
  const Vec3 ex = place({1, 0, 0}), ey = place({0, 1, 0}), ez = place({0, 0, 1});
  Vec3 ci = ex, cj = ey;
  if (std::abs(dot(n, ey)) > 0.5)
    ci = ez, cj = ex;
  else if (std::abs(dot(n, ex)) > 0.5)
    ci = ey, cj = ez;
  // Axis k runs towards increasing slice id: flip i if needed (keeps the matrix a rotation).
  const Vec3 towards_id = (lat.step >= 0 ? 1.0 : -1.0) * n;
  if (dot(cross(ci, cj), towards_id) < 0) ci = -ci;
  const Vec3 ck = cross(ci, cj);
  const double dk = std::abs(lat.step);

  // In-plane extent: the truth meshes of every frame, plus the margin.
  double lo_i = std::numeric_limits<double>::infinity(), hi_i = -lo_i, lo_j = lo_i, hi_j = -lo_i;
  for (const TriangleMesh& m : ph.truth)
    for (const Vec3& p : m.positions) {
      lo_i = std::min(lo_i, dot(p, ci)), hi_i = std::max(hi_i, dot(p, ci));
      lo_j = std::min(lo_j, dot(p, cj)), hi_j = std::max(hi_j, dot(p, cj));
    }
  const double a0 = lo_i - o.margin + o.shift_px.x * o.pixel_x, b0 = lo_j - o.margin + o.shift_px.y * o.pixel_y;
  const int ni = static_cast<int>(std::ceil((hi_i + o.margin - a0) / o.pixel_x)) + 1;
  const int nj = static_cast<int>(std::ceil((hi_j + o.margin - b0) / o.pixel_y)) + 1;
  const int nk = lat.count;
  if (static_cast<double>(ni) * nj * nk * static_cast<double>(ph.truth.size()) > 2e9)
    throw InvalidInput(ErrorCode::Usage, {}, "mask too large", "use larger voxels");
  // Voxel (0, 0, 0): in-plane corner, on the plane of slice id 0 (offset along n = lat.base).
  const Vec3 origin = a0 * ci + b0 * cj + (lat.base - dot(a0 * ci + b0 * cj, n)) * n;

  LabelVolume proto;
  proto.dims = {ni, nj, nk};
  proto.spacing = {o.pixel_x, o.pixel_y, dk};
  proto.origin = {origin.x, origin.y, origin.z};
  proto.direction = {ci.x, cj.x, ck.x, ci.y, cj.y, ck.y, ci.z, cj.z, ck.z};
  std::vector<LabelVolume> out(ph.truth.size(), proto);
  const std::size_t plane = static_cast<std::size_t>(ni) * static_cast<std::size_t>(nj);
  for (LabelVolume& v : out) v.labels.assign(plane * static_cast<std::size_t>(nk), 0);
  // Every (frame, slice) fills its own part of the image: deterministic.
  tbb::parallel_for(std::size_t{0}, out.size() * static_cast<std::size_t>(nk), [&](std::size_t item) {
    const std::size_t f = item / static_cast<std::size_t>(nk);
    const int k = static_cast<int>(item % static_cast<std::size_t>(nk));
    int32_t* dst = out[f].labels.data() + plane * static_cast<std::size_t>(k);
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < ni; ++i) {
        const Vec3 p = origin + (i * o.pixel_x) * ci + (j * o.pixel_y) * cj + (k * dk) * ck;
        if (analytic_distance(ph, static_cast<int>(f), p) < 0)
          dst[static_cast<std::size_t>(i) + static_cast<std::size_t>(ni) * static_cast<std::size_t>(j)] = o.label;
      }
  });
  return out;
}

}  // namespace c4d
