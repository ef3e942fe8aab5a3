// Lim et al. 2014, Fig. 1 (the 4D flowchart): frame 0's surface, then frame-by-frame deformation; by default
// every frame rebuilt on one mesh (rebuild.h), the others carried (motion/carry_unfit_internal.h).
#include "contour4d/motion/reconstruct4d.h"

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <map>
#include <mutex>
#include <optional>

#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "contour4d/core/errors.h"
#include "carry_unfit_internal.h"

namespace c4d {

namespace {

// Slices whose contour count changes between consecutive frames (Miara et al. Fig. 14's events).
std::vector<SliceEvent> count_events(const Sequence& seq) {
  std::vector<SliceEvent> events;
  std::map<int, int> before;
  for (std::size_t f = 0; f < seq.frames.size(); ++f) {
    std::map<int, int> now;
    for (const Slice& s : seq.frames[f].slices) now[s.id] = static_cast<int>(s.contours.size());
    if (f > 0) {
      std::map<int, std::pair<int, int>> change;
      for (const auto& [id, c] : before) change[id].first = c;
      for (const auto& [id, c] : now) change[id].second = c;
      for (const auto& [id, ba] : change)
        if (ba.first != ba.second) {
          const auto [b, a] = ba;
          const char* kind = b == 0              ? "appear"
                             : a == 0            ? "vanish"
                             : (b == 1 && a > 1) ? "split"
                             : (b > 1 && a == 1) ? "merge"
                                                 : "change";
          events.push_back({static_cast<int>(f), id, kind, b, a});
        }
    }
    before = std::move(now);
  }
  return events;
}

// AllFramesMethod::Carry: frame 0's surface, then every frame on its own (carry.h).
MeshSequence carry_4d(const Sequence& seq, const Reconstruct4DOptions& options, Reconstruct4DReport& rep,
                      const std::function<TriangleMesh(std::size_t)>& build) {
  const std::size_t n = seq.frames.size();
  if (options.progress) options.progress("frame 0", 0, 1);
  const TriangleMesh frame0 = build(0);
  std::mutex mutex;
  int done = 0;
  auto own = [&](std::size_t t) {
    TriangleMesh m = build(t);
    if (options.progress) {
      std::lock_guard<std::mutex> lock(mutex);
      options.progress("frames", ++done, static_cast<int>(n) - 1);
    }
    return m;
  };
  MeshSequence out = carry_frames(seq, frame0, own, options.carry, &rep.carry);
  rep.morph.frames.assign(n, {});
  for (std::size_t t = 0; t < n; ++t) {
    rep.morph.frames[t].matched = rep.carry.frames[t].matched_contours;
    rep.morph.frames[t].projection_mean = rep.carry.frames[t].projection_mean;
    rep.morph.frames[t].projection_max = rep.carry.frames[t].projection_max;
  }
  rep.morph.events = count_events(seq);
  rep.morph.submeshes = submesh_lifetimes(seq);
  return out;
}

}  // namespace

MeshSequence reconstruct_4d(const Sequence& seq, const Reconstruct4DOptions& options, Reconstruct4DReport* report) {
  const std::size_t n = seq.frames.size();
  if (n == 0) throw InvalidInput(ErrorCode::EmptyFrame, Location{seq.source}, "the input holds no frame");
  Reconstruct4DReport local;
  Reconstruct4DReport& rep = report ? *report : local;
  rep.surfaces.assign(n, {});
  // Frame 0 always; every frame when the morph projects onto each frame's own surface.
  if (options.all_frames == AllFramesMethod::Auto || options.all_frames == AllFramesMethod::Rebuild) {
    std::optional<MeshSequence> rebuilt =
        rebuild_frames(seq, options.surface, &rep.rebuild, &rep.surfaces, [&](int done, int total) {
          if (options.progress) options.progress("frames", done, total);
        });
    if (options.all_frames == AllFramesMethod::Rebuild && (!rebuilt || !rep.rebuild.unfit.empty()))
      throw InvalidInput(
          ErrorCode::Usage, Location{seq.source},
          "every frame on one mesh is not possible: " +
              (rebuilt ? "frame " + std::to_string(rep.rebuild.unfit[0]) + ": " + rep.rebuild.unfit_why[0]
                       : rep.rebuild.why_not),
          "use --method auto (the default), which carries the mesh onto frames whose contours change");
    if (rebuilt) {
      rep.used = AllFramesMethod::Rebuild;
      rep.morph.frames.assign(n, {});
      rep.carry.frames.assign(n, {});
      detail::carry_unfit(seq, *rebuilt, options, rep);
      rep.morph.events = count_events(seq);
      rep.morph.submeshes = submesh_lifetimes(seq);
      return std::move(*rebuilt);
    }
    rep.surfaces.assign(n, {});
  }
  const std::size_t ahead = options.morph.method == MorphMethod::RbfProject ? n : 1;  // frames [0, ahead)
  auto build = [&](std::size_t f) {
    SurfaceOptions so = options.surface;
    if (f == 0) {  // the carried mesh: remeshed bands, evenly spread, at the angle the morph keeps later
      so.rows = false;
      so.remesher = RemeshEngine::Fast;
      so.angle_target_deg = options.morph.angle_repair.target_deg;
    } else {
      so.geometry_only = true;  // only the geometry of later frames is used: the morph projects onto it
    }
    return reconstruct_frame(seq, static_cast<int>(f), so, &rep.surfaces[f]);
  };
  if (options.all_frames == AllFramesMethod::Carry) {
    rep.used = AllFramesMethod::Carry;
    MeshSequence out = carry_4d(seq, options, rep, build);
    detail::recarry_all(seq, out, nullptr, options, rep);
    return out;
  }
  rep.used = AllFramesMethod::Morph;
  // The surfaces are built by tasks that take the frames in increasing order, while this thread morphs
  // (from frame 0's surface on) and builds a frame itself when the morph needs one nobody has taken yet:
  // the morph overlaps the building. Each surface depends on its frame only, so the result does not
  // depend on the scheduling.
  std::vector<TriangleMesh> surfaces(n);
  std::vector<char> built(n, 0), taken(n, 0);
  std::vector<std::exception_ptr> errors(n);
  std::mutex mutex;  // guards built, taken and errors
  std::condition_variable ready;
  // Takes frame f if nobody has (or the next ahead frame when f < 0) and builds it; false if none was taken.
  auto take_and_build = [&](std::ptrdiff_t f) {
    std::size_t g = n;
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (f >= 0) {
        if (!taken[static_cast<std::size_t>(f)]) g = static_cast<std::size_t>(f);
      } else {
        for (std::size_t k = 0; k < ahead && g == n; ++k)
          if (!taken[k]) g = k;
      }
      if (g == n) return false;
      taken[g] = 1;
    }
    std::exception_ptr error;
    TriangleMesh mesh;
    try {
      mesh = build(g);
    } catch (...) {
      error = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mutex);
      surfaces[g] = std::move(mesh);
      errors[g] = error;
      built[g] = 1;
    }
    ready.notify_all();
    return true;
  };
  // Frame t's surface, built here if nobody has taken it; waits for it otherwise.
  // Called by the morph's thread only, frames in increasing order: frame t asked for, the frames before it done.
  const auto surface = [&](std::size_t t) -> const TriangleMesh& {
    if (options.progress && t > 0) options.progress("frames", static_cast<int>(t) - 1, static_cast<int>(n) - 1);
    take_and_build(static_cast<std::ptrdiff_t>(t));
    std::unique_lock<std::mutex> lock(mutex);
    ready.wait(lock, [&] { return built[t] != 0; });
    if (errors[t]) std::rethrow_exception(errors[t]);
    return surfaces[t];
  };
  tbb::task_group builders;
  const int workers = std::max(1, tbb::this_task_arena::max_concurrency() - 1);
  for (int w = 0; w < workers; ++w)
    builders.run([&] {
      while (take_and_build(-1)) {}
    });
  MeshSequence out;
  std::exception_ptr morph_error;
  try {
    const TriangleMesh& frame0 = surface(0);
    out = morph_sequence(seq, frame0, surface, options.morph, &rep.morph);
  } catch (...) {
    morph_error = std::current_exception();
  }
  builders.wait();  // every ahead frame is built, as the morph may have stopped on a later one's error
  // A surface that failed is reported before the morph's own error: the lowest failing frame.
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  if (morph_error) std::rethrow_exception(morph_error);
  if (options.morph.method == MorphMethod::RbfProject) detail::recarry_all(seq, out, &surfaces, options, rep);
  if (options.progress && n > 1) options.progress("frames", static_cast<int>(n) - 1, static_cast<int>(n) - 1);
  return out;
}

}  // namespace c4d
