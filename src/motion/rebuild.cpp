// All frames, each its own surface on one mesh (rebuild.h): Miara et al. §III.D's base mesh with per-frame
// geometry, where the base mesh is the plan frame's surface plan and each frame's geometry its own one-frame surface.
#include "contour4d/motion/rebuild.h"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <limits>
#include <map>
#include <mutex>

#include <fmt/format.h>

#include <tbb/parallel_for.h>

#include "contour4d/core/contour.h"
#include "contour4d/core/normals.h"
#include "contour4d/metrics/quality.h"
#include "contour4d/metrics/surface_projector.h"
#include "contour4d/metrics/topology.h"
#include "contour4d/surface/angle_repair.h"

namespace c4d {

namespace {

// How far (in target edges) and how steeply (cosine of the normals' angle) a rebuilt vertex may move onto
// the frame's own surface: the plan's counts give that surface up to its discretisation (a tenth of a mm
// on real data), so a longer move or a surface facing another way is another sheet, and the vertex stays.
constexpr double kMaxMoveEdges = 3.0;
constexpr double kMinNormalCos = 0.5;
constexpr int kUntangleRounds = 8;  // rounds of 10 umbrella steps where triangles cross
// A frame whose plan mesh leaves more than this share of its free vertices off its own surface (farther than
// kMaxMoveEdges or facing another way) is not that surface: the plan's counts do not suit it (a base contour
// a third of the plan frame's), and it is carried instead (reconstruct4d.h).
constexpr double kMaxOffSurfaceShare = 0.005;
// A frame whose settled plan mesh keeps more than this share (%) of triangles with an angle below 25° is
// squeezed where its contours shrank far below the plan frame's (biv-me's base contour in early diastole): it
// is carried instead, and is not a frame others are carried from.
constexpr double kMaxBadTrianglePct = 1.0;

// What settle_on_own left: free vertices that found no landing, crossing triangle pairs.
struct Settled {
  std::size_t off_surface = 0;  // free vertices farther than kMaxMoveEdges edges or facing another way
  std::size_t crossings = 0;    // crossing triangle pairs (0: none)
};

// The rebuilt frame on its own one-frame surface: the free (non-contour) vertices projected onto it (a move
// of at most kMaxMoveEdges edges onto a part facing the vertex's way, else the vertex stays), then the
// small-angle repair within it; where triangles still cross, the local untangling and the repair again.
Settled settle_on_own(TriangleMesh& mesh, std::size_t contour_vertices, const TriangleMesh& own, double edge,
                      double angle_target_deg) {
  Settled out;
  const SurfaceProjector surface(own);
  if (surface.empty()) return out;
  std::vector<Vec3>& x = mesh.positions;
  const std::vector<Vec3> normals = area_weighted_normals(x, mesh.triangles, Vec3{});
  std::vector<std::int32_t> hints(x.size(), -1);
  for (std::size_t v = contour_vertices; v < x.size(); ++v) {
    Vec3 n;
    const Vec3 q = surface.closest(x[v], &n, &hints[v]);
    if (distance(q, x[v]) <= kMaxMoveEdges * edge && dot(n, normals[v]) >= kMinNormalCos)
      x[v] = q;
    else
      ++out.off_surface;
  }
  std::vector<char> fixed(x.size(), 0);
  std::fill(fixed.begin(), fixed.begin() + static_cast<std::ptrdiff_t>(contour_vertices), 1);
  const SurfaceSnap snap = [&](std::uint32_t v, Vec3 p) { return surface.closest(p, nullptr, &hints[v]); };
  AngleRepairOptions repair;
  repair.target_deg = angle_target_deg;
  repair_small_angles(x, mesh.triangles, fixed, snap, repair);
  const TopologyOptions exact{.self_intersections = true, .counts_only = true};
  if (check_topology(mesh, exact).self_intersections == 0) return out;
  untangle(x, mesh.triangles, fixed, snap, kUntangleRounds);
  repair_small_angles(x, mesh.triangles, fixed, snap, repair);
  out.crossings = check_topology(mesh, exact).self_intersections;
  return out;
}

// The frame the plan is made on: of the frames whose slices hold as many contours as frame 0's, the one whose
// contours' total length is the median. The other frames then stretch or squeeze its triangles by at most
// half the cycle's range: a plan made at either end (biv-me's base contour shrinks to a third in systole)
// leaves the frames at the other end off their own surfaces, or folded.
std::size_t plan_frame(const Sequence& seq, const std::string& label) {
  const Sequence sub = label.empty() ? seq : select_label(seq, label);
  auto counts = [&](std::size_t f) {
    std::map<int, std::size_t> c;
    for (const Slice& s : sub.frames[f].slices)
      if (!s.contours.empty()) c[s.id] = s.contours.size();
    return c;
  };
  const auto first = counts(0);
  std::vector<std::pair<double, std::size_t>> lengths;  // (total contour length, frame)
  for (std::size_t f = 0; f < sub.frames.size(); ++f) {
    if (counts(f) != first) continue;
    double length = 0.0;
    for (const Slice& s : sub.frames[f].slices)
      for (const Contour& c : s.contours) length += perimeter(c.points);
    lengths.emplace_back(length, f);
  }
  std::sort(lengths.begin(), lengths.end());
  return lengths[(lengths.size() - 1) / 2].second;
}

}  // namespace

std::optional<MeshSequence> rebuild_frames(const Sequence& seq, const SurfaceOptions& options, RebuildReport* report,
                                           std::vector<SurfaceReport>* surfaces,
                                           const std::function<void(int, int)>& progress) {
  RebuildReport local;
  RebuildReport& rep = report ? *report : local;
  const std::size_t n = seq.frames.size();
  const std::size_t planned = plan_frame(seq, options.label);
  rep.plan_frame = static_cast<int>(planned);
  const SurfacePlan plan = plan_surface(seq, static_cast<int>(planned), options);
  if (!plan.unusable.empty()) {
    rep.why_not = plan.unusable;
    return std::nullopt;
  }
  std::vector<std::optional<TriangleMesh>> meshes(n);
  std::vector<SurfaceReport> reports(n);
  std::vector<std::string> why(n);
  std::vector<std::exception_ptr> errors(n);
  std::mutex mutex;
  int done = 0;
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t f) {
    try {
      meshes[f] = reconstruct_frame_on_plan(seq, static_cast<int>(f), options, plan, &reports[f], &why[f]);
      if (meshes[f]) {
        SurfaceOptions own_options = options;
        own_options.geometry_only = true;
        const TriangleMesh own = reconstruct_frame(seq, static_cast<int>(f), own_options);
        const Settled settled =
            settle_on_own(*meshes[f], plan.contour_vertices, own, options.edge, options.angle_target_deg);
        const std::size_t free = plan.embedding.size();
        if (static_cast<double>(settled.off_surface) > kMaxOffSurfaceShare * static_cast<double>(free)) {
          why[f] = fmt::format("the plan's mesh lies off the frame's own surface ({} of {} vertices)",
                               settled.off_surface, free);
          meshes[f].reset();
        } else if (settled.crossings > 0) {
          why[f] = fmt::format("the plan's mesh on its contours crosses itself ({} triangle pairs)", settled.crossings);
          meshes[f].reset();
        } else if (const AngleQuality q = angle_quality(*meshes[f]); q.bad_pct > kMaxBadTrianglePct) {
          why[f] = fmt::format(
              "the plan's mesh is squeezed on its contours ({:.1f} % of triangles with an angle below "
              "25°)",
              q.bad_pct);
          meshes[f].reset();
        }
      }
    } catch (...) {
      errors[f] = std::current_exception();
    }
    if (progress) {
      std::lock_guard<std::mutex> lock(mutex);
      progress(++done, static_cast<int>(n));
    }
  });
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  if (std::none_of(meshes.begin(), meshes.end(), [](const auto& m) { return m.has_value(); })) {
    rep.why_not = "no frame holds on the plan (" + why[planned] + ")";
    return std::nullopt;
  }
  MeshSequence out;
  out.triangles = plan.final_triangles;
  for (std::size_t f = 0; f < n; ++f) {
    out.times_ms.push_back(seq.frames[f].time_ms);
    if (meshes[f]) {
      out.positions.push_back(std::move(meshes[f]->positions));
    } else {
      rep.unfit.push_back(static_cast<int>(f));
      rep.unfit_why.push_back(why[f]);
      out.positions.emplace_back();
    }
  }
  if (surfaces) *surfaces = std::move(reports);
  return out;
}

}  // namespace c4d
