// Lim et al. 2014, Fig. 1 (the 4D flowchart): frame 0's surface, then frame-by-frame deformation.
#include "contour4d/motion/reconstruct4d.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <map>
#include <mutex>

#include <tbb/parallel_for.h>

#include "contour4d/core/errors.h"

namespace c4d {

MeshSequence reconstruct_4d(const Sequence& seq, const Reconstruct4DOptions& options, Reconstruct4DReport* report) {
  const std::size_t n = seq.frames.size();
  if (n == 0) throw InvalidInput(ErrorCode::EmptyFrame, Location{seq.source}, "the input holds no frame");
  Reconstruct4DReport local;
  Reconstruct4DReport& rep = report ? *report : local;
  rep.surfaces.assign(n, {});
  // Frame 0 always; every frame when the morph projects onto each frame's own surface. With
  // MorphOptions::biharmonic, only the frames whose contour counts differ from the frame before are built
  // ahead (in parallel); the others when the morph first needs them (a frame that falls back).
  const bool project = options.morph.method == MorphMethod::RbfProject;
  auto counts = [&](std::size_t f) {
    std::map<int, std::size_t> c;
    for (const Slice& s : seq.frames[f].slices) c[s.id] = s.contours.size();
    return c;
  };
  std::vector<char> ahead(n, 0);
  ahead[0] = 1;
  for (std::size_t f = 1; f < n; ++f)
    ahead[f] = project && (!options.morph.biharmonic || counts(f) != counts(f - 1));
  auto build = [&](std::size_t f) {
    SurfaceOptions so = options.surface;
    if (f > 0 && options.fast_targets) {
      // Only the geometry of later frames is used (the morph projects onto it): no self-intersection test.
      // The small-angle repair stays: the relaxation takes its tangent planes from the landing triangles.
      so.rows = true;
      so.check_self_intersections = false;
    }
    return reconstruct_frame(seq, static_cast<int>(f), so, &rep.surfaces[f]);
  };
  std::vector<TriangleMesh> surfaces(n);
  std::vector<char> built(n, 0);
  std::vector<std::exception_ptr> errors(n);
  std::atomic<int> done{0};
  std::mutex progress_mutex;
  const int count = static_cast<int>(std::count(ahead.begin(), ahead.end(), 1));
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t f) {
    if (!ahead[f]) return;
    try {
      surfaces[f] = build(f);
      built[f] = 1;
    } catch (...) {
      errors[f] = std::current_exception();
    }
    const int d = ++done;
    if (options.progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      options.progress("surfaces", d, count);
    }
  });
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);  // the lowest failing frame, whatever the scheduling
  if (options.progress) options.progress("morph", 0, 1);
  const auto surface = [&](std::size_t f) -> const TriangleMesh& {
    if (!built[f]) {
      surfaces[f] = build(f);
      built[f] = 1;
    }
    return surfaces[f];
  };
  MeshSequence out = project ? morph_sequence(seq, surfaces[0], surface, options.morph, &rep.morph)
                             : morph_sequence(seq, surfaces[0], surfaces, options.morph, &rep.morph);
  if (options.progress) options.progress("morph", 1, 1);
  return out;
}

}  // namespace c4d
