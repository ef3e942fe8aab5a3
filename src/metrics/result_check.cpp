// The output gate of the brief's rule "never report a broken result as done": each frame of a
// reconstruction is checked as a surface (check_topology: closed, manifold, outward, no crossing
// triangles) and against the volume its own contours give by Simpson's method of discs.
#include "contour4d/metrics/result_check.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "contour4d/metrics/topology.h"
#include "contour4d/metrics/volume.h"

namespace c4d {

namespace {

bool is_boundary_fault(const std::string& fault) { return fault.find("the mesh is not closed") != std::string::npos; }

// The topology faults of one frame (open ends allowed when !options.closed).
std::vector<std::string> surface_faults(const TriangleMesh& mesh, const ResultCheckOptions& options,
                                        std::size_t& crossings) {
  TopologyOptions topo;
  topo.self_intersections = options.self_intersections;
  const TopologyReport r = check_topology(mesh, topo);
  crossings = r.self_intersections;
  std::vector<std::string> faults;
  for (const std::string& f : r.faults)
    if (options.closed || !is_boundary_fault(f)) faults.push_back(f);
  return faults;
}

// The volume comparison: a collapsed, inside-out or ballooned frame is far from its discs. The difference is
// weighed against the outer contours' discs (ResultCheckOptions::volume_tolerance).
void check_volume(FrameCheck& c, const DiscVolume& discs, double tolerance) {
  c.simpson_volume = discs.volume;
  c.simpson_outer_volume = discs.outer_volume;
  if (!(discs.volume > 0.0) || !(discs.outer_volume > 0.0)) return;
  const double share = (c.volume - discs.volume) / discs.outer_volume;
  if (std::abs(share) <= tolerance) return;
  const bool holes = discs.outer_volume > discs.volume;
  c.faults.push_back(fmt::format(
      "volume {:.1f} ml against {:.1f} ml by Simpson's discs of its contours ({:+.1f} %{}, bound ±{:.0f} %)",
      c.volume / 1000.0, discs.volume / 1000.0, 100.0 * share,
      holes ? fmt::format(" of the {:.1f} ml its outer contours enclose", discs.outer_volume / 1000.0) : "",
      100.0 * tolerance));
}

// Positions that cannot belong to the shared triangles, or are not numbers.
void check_positions(FrameCheck& c, const std::vector<Vec3>& positions, std::size_t expected) {
  if (positions.size() != expected)
    c.faults.push_back(
        fmt::format("{} vertices where frame 0 has {}: no vertex correspondence", positions.size(), expected));
  const auto bad = std::count_if(positions.begin(), positions.end(), [](const Vec3& p) {
    return !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z);
  });
  if (bad > 0) c.faults.push_back(fmt::format("{} vertices with a non-finite coordinate", bad));
}

}  // namespace

bool ResultCheck::ok() const {
  return std::all_of(frames.begin(), frames.end(), [](const FrameCheck& f) { return f.ok(); });
}

std::string ResultCheck::summary() const {
  const auto first = std::find_if(frames.begin(), frames.end(), [](const FrameCheck& f) { return !f.ok(); });
  if (first == frames.end()) return {};
  std::string s = fmt::format("frame {}: ", first->frame);
  for (std::size_t k = 0; k < first->faults.size(); ++k) s += (k ? "; " : "") + first->faults[k];
  const auto others = std::count_if(first + 1, frames.end(), [](const FrameCheck& f) { return !f.ok(); });
  if (others > 0) s += fmt::format(" (and {} more failing frame{})", others, others == 1 ? "" : "s");
  return s;
}

ResultCheck check_result(const MeshSequence& result, const Sequence& contours, const ResultCheckOptions& options) {
  ResultCheck out;
  const std::size_t n = result.positions.size();
  out.frames.resize(n);
  const std::size_t vertices = n ? result.positions.front().size() : 0;
  const bool compare_volume = options.closed && contours.frames.size() == n;
  const std::vector<DiscVolume> discs = compare_volume ? simpson_volumes(contours) : std::vector<DiscVolume>{};
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t f) {
    FrameCheck& c = out.frames[f];
    c.frame = static_cast<int>(f);
    check_positions(c, result.positions[f], vertices);
    if (!c.ok()) return;
    const TriangleMesh mesh = result.frame(f);
    c.faults = surface_faults(mesh, options, c.self_intersections);
    c.volume = signed_volume(mesh);
    if (compare_volume && c.ok()) check_volume(c, discs[f], options.volume_tolerance);
  });
  return out;
}

}  // namespace c4d
