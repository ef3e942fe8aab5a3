// Lim et al. 2014, Fig. 1 (the 4D flowchart): frame 0's surface, then frame-by-frame deformation.
#include "contour4d/motion/reconstruct4d.h"

#include <atomic>
#include <exception>
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
  // Frame 0 always; every frame when the morph projects onto each frame's own surface.
  const bool all = options.morph.method == MorphMethod::RbfProject;
  const std::size_t count = all ? n : 1;
  std::vector<TriangleMesh> surfaces(count);
  std::vector<std::exception_ptr> errors(count);
  std::atomic<int> done{0};
  std::mutex progress_mutex;
  tbb::parallel_for(std::size_t(0), count, [&](std::size_t f) {
    try {
      SurfaceOptions so = options.surface;
      if (f > 0 && options.fast_targets) {
        // Only the geometry of later frames is used (the morph projects onto it): no self-intersection test.
        // The small-angle repair stays: the relaxation takes its tangent planes from the landing triangles.
        so.rows = true;
        so.check_self_intersections = false;
      }
      surfaces[f] = reconstruct_frame(seq, static_cast<int>(f), so, &rep.surfaces[f]);
    } catch (...) {
      errors[f] = std::current_exception();
    }
    const int d = ++done;
    if (options.progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      options.progress("surfaces", d, static_cast<int>(count));
    }
  });
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);  // the lowest failing frame, whatever the scheduling
  if (options.progress) options.progress("morph", 0, 1);
  MeshSequence out = morph_sequence(seq, surfaces[0], surfaces, options.morph, &rep.morph);
  if (options.progress) options.progress("morph", 1, 1);
  return out;
}

}  // namespace c4d
