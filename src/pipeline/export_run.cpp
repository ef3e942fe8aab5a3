// The export run (export_run.h): an output folder checked and read, its ends made flow faces, the cycle cut
// into solver steps, the cavity meshed and moved through every step, then one writer per solver.
#include "contour4d/pipeline/export_run.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "contour4d/core/errors.h"
#include "contour4d/io/mesh_output.h"
#include "contour4d/io/vtk_grid.h"
#include "contour4d/io/vtk_xml.h"
#include "contour4d/metrics/crease.h"
#include "contour4d/metrics/topology.h"
#include "contour4d/solver/openfoam.h"
#include "contour4d/solver/svfsi.h"
#include "contour4d/solver/vampy.h"
#include "contour4d/temporal/sequence.h"

namespace c4d {
namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

Json read_report(const fs::path& folder) {
  const fs::path path = folder / "report.json";
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw IoError(ErrorCode::MissingCompanion, {path.string()}, "report.json is missing beside the meshes",
                  "export needs the stack normal and frame times that `contour4d reconstruct` writes there");
  try {
    return Json::parse(read_file(path));
  } catch (const Json::exception& e) {
    throw IoError(ErrorCode::Parse, {path.string()}, std::string("report.json is not valid JSON: ") + e.what());
  }
}

// The stack normal of report.json (rounded to 4 decimals there).
Vec3 report_normal(const Json& report, const fs::path& folder) {
  const Json& n = report.contains("stack_normal") ? report["stack_normal"] : Json();
  if (!n.is_array() || n.size() != 3 || !n[0].is_number() || !n[1].is_number() || !n[2].is_number())
    throw IoError(ErrorCode::Format, {(folder / "report.json").string()}, "report.json has no stack_normal",
                  "give the folder of a `contour4d reconstruct` run");
  return {n[0].get<double>(), n[1].get<double>(), n[2].get<double>()};
}

// Real frame times: the user's, else the folder's when report.json says they are known.
void apply_times(ExportInput& in, const Json& report, const ExportRunOptions& o) {
  const std::size_t n = in.seq.positions.size();
  if (o.frame_ms > 0.0 || o.cycle_ms > 0.0) {
    const double step = o.frame_ms > 0.0 ? o.frame_ms : o.cycle_ms / static_cast<double>(n);
    for (std::size_t f = 0; f < n; ++f) in.seq.times_ms[f] = step * static_cast<double>(f);
    in.times_source = o.frame_ms > 0.0 ? "--frame-ms" : "--cycle-ms";
    return;
  }
  const Json& ft = report.contains("frame_times") ? report["frame_times"] : Json();
  const bool known = ft.is_object() && ft.value("known", false);
  in.times_source = ft.is_object() ? ft.value("source", std::string("unknown")) : "unknown";
  if (!known)
    throw InvalidInput(
        ErrorCode::UnknownFrameTimes, {in.folder.string()},
        fmt::format("the frame times of this folder are unknown ({}: frame index × 1 ms)", in.times_source),
        "give the real ones: --cycle-ms MS (the cycle's length) or --frame-ms MS (between frames)");
}

}  // namespace

ExportInput load_export_input(const fs::path& folder, const ExportRunOptions& options) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw IoError(ErrorCode::FileNotFound, {folder.string()}, "output folder not found",
                  "give a folder written by `contour4d reconstruct` (mesh.pvd, frames/, report.json)");
  ExportInput in;
  in.folder = folder;
  in.seq = to_mesh_sequence(read_mesh_frames(folder), folder.string());
  if (in.seq.positions.size() < 2)
    throw InvalidInput(ErrorCode::TooFewFrames, {folder.string()},
                       fmt::format("the folder holds {} frame (a one-frame run): a flow solver needs a cycle",
                                   in.seq.positions.size()),
                       "reconstruct every frame (without --frame)");
  const Json report = read_report(folder);
  apply_times(in, report, options);
  const TriangleMesh first = in.seq.frame(0);
  TopologyOptions topo;
  topo.self_intersections = false;
  const TopologyReport t = check_topology(first, topo);
  if (!t.closed())
    throw InvalidInput(ErrorCode::OpenSurface, {folder.string(), -1, 0},
                       fmt::format("the surface is open ({} boundary edges): export opens the ends itself and needs a "
                                   "closed surface to fill with a volume mesh",
                                   t.boundary_edges),
                       "reconstruct with --cap rounded (the default) or --cap flat, then choose the open ends "
                       "with export --open");
  if (!t.edge_manifold() || !t.consistently_oriented() || !t.outward())
    throw InvalidInput(ErrorCode::BadMesh, {folder.string(), -1, 0},
                       "the surface of frame 0 is not a manifold, consistently outward surface: " +
                           (t.faults.empty() ? std::string("?") : t.faults.front()));
  in.normal = refine_normal(first, report_normal(report, folder));
  return in;
}

std::vector<SurfaceEnd> export_ends(const ExportInput& input) { return find_ends(input.seq.frame(0), input.normal); }

namespace {

Json quality_json(const TetQuality& q) {
  return {{"volume_ml", q.volume_mm3 / 1000.0},
          {"min_tet_volume_mm3", q.min_volume_mm3},
          {"inverted", q.inverted},
          {"min_dihedral_deg", q.min_dihedral_deg},
          {"max_aspect_ratio", q.max_aspect_ratio}};
}

std::string report_json(const ExportInput& in, const ExportRun& run, const ExportRunOptions& o) {
  const Handoff& h = run.handoff;
  Json ends = Json::array();
  for (std::size_t i = 0; i < run.ends.size(); ++i) {
    const SurfaceEnd& e = run.ends[i];
    const auto it = std::find(run.opened.begin(), run.opened.end(), static_cast<int>(i));
    const bool open = it != run.opened.end();
    const std::size_t k = static_cast<std::size_t>(it - run.opened.begin());
    ends.push_back({{"end", i + 1},
                    {"side", e.base ? "base" : "apex"},
                    {"area_mm2", e.area_mm2},
                    {"plane_offset_mm", e.offset_mm},
                    {"border_loops", e.loops},
                    {"opened", open},
                    {"face", open ? h.surface.names[k + 1] : e.name},
                    {"border_moved_to_plane_mm", open ? h.surface.ring_moved_mm[k] : 0.0},
                    {"band_moved_mm", open ? h.surface.band_moved_mm[k] : 0.0},
                    {"band_vertices", open ? Json(h.surface.band[k]) : Json::array()},
                    {"frames_not_flat", open ? Json(h.surface.not_flat_frames[k]) : Json::array()}});
  }
  Json steps = Json::array();
  for (std::size_t i = 0; i < h.steps.times_s.size(); ++i)
    steps.push_back({{"t_s", h.steps.times_s[i]},
                     {"cavity_volume_ml", h.motion.steps[i].volume_mm3 / 1000.0},
                     {"surface_volume_ml", run.surface_volume_mm3[i] / 1000.0},
                     {"min_dihedral_deg", h.motion.steps[i].min_dihedral_deg},
                     {"max_aspect_ratio", h.motion.steps[i].max_aspect_ratio},
                     {"min_tet_volume_mm3", h.motion.steps[i].min_volume_mm3},
                     {"untangled_nodes", h.motion.untangled_step_nodes[i]}});
  Json j;
  j["tool"] = "contour4d 0.1.0";
  j["input"] = in.folder.string();
  j["targets"] = o.targets;
  j["units"] = {
      {"input", "mm"}, {"time", "s"}, {"lengths_written", o.units.empty() ? "per target (docs/export.md)" : o.units}};
  j["frames"] = {{"count", in.seq.positions.size()}, {"times_ms", in.seq.times_ms}, {"times_source", in.times_source}};
  j["stack_normal"] = {in.normal.x, in.normal.y, in.normal.z};
  j["time_steps"] = {{"period_s", h.steps.period_s},
                     {"steps_per_cycle", h.steps.steps_per_cycle},
                     {"dt_s", h.steps.dt_s},
                     {"cycles", o.steps.cycles},
                     {"outputs", h.steps.times_s.size()},
                     {"interpolation", "periodic Catmull-Rom (C1) of every vertex, as render"}};
  j["ends"] = ends;
  j["faces"] = h.surface.names;
  j["surface"] = {{"vertices", h.surface.seq.positions.front().size()}, {"triangles", h.surface.seq.triangles.size()}};
  j["cavity"] = {{"nodes", h.cavity.nodes.size()},
                 {"inner_nodes", h.cavity.nodes.size() - h.cavity.surface_nodes},
                 {"tets", h.cavity.tets.size()},
                 {"tetgen",
                  {{"radius_edge", o.cavity.radius_edge},
                   {"min_dihedral_deg", o.cavity.min_dihedral_deg},
                   {"max_volume_mm3", o.cavity.max_volume_mm3}}},
                 {"frame0", quality_json(h.motion.frame0)},
                 {"extension", h.motion.extension == Extension::Harmonic ? "harmonic" : "stiffened"},
                 {"harmonic_fault", h.motion.harmonic_fault},
                 {"untangled_nodes_per_key_frame", h.motion.untangled_key_nodes},
                 {"over_the_cycle",
                  {{"min_dihedral_deg", h.motion.min_dihedral_deg},
                   {"max_aspect_ratio", h.motion.max_aspect_ratio},
                   {"min_tet_volume_mm3", h.motion.min_volume_mm3},
                   {"inverted", 0},
                   {"max_volume_difference_to_surface", run.max_volume_difference}}}};
  j["steps"] = steps;
  return j.dump(2) + "\n";
}

// A cavity's wall that folds back on itself (two triangles sharing an edge with normals more than this apart)
// cannot be the boundary of a valid cavity at that time: it is refused before the cavity is meshed and moved. The
// interpolation between two valid key frames can fold one. The sharpest real creases of cavities stay below it
// (left-heart cycle at --edge 2: 127°; biv-me lv-endo: 88°, lv-epi 137°). It is no bound for reconstruct's own
// check: a myocardial wall's rim, where its two sheets meet at the apex, is sharper.
constexpr double kMaxFoldDeg = 150.0;

// The first key frame, then the first output time, whose wall folds (exit 31 naming it). The output times are
// measured in parallel, each into its own slot, and scanned in order.
void refuse_folds(const Handoff& h, int threads) {
  const MeshSequence& seq = h.surface.seq;
  const auto pairs = neighbour_pairs(seq.frame(0));
  const auto refuse = [](const std::string& when, const Fold& fold) {
    throw SolverError(ErrorCode::InvertedElement, {},
                      fmt::format("{}: the wall folds back on itself between triangles {} and {} ({:.1f}° between "
                                  "their normals, over {:.0f}°): no cavity mesh can follow it",
                                  when, fold.first, fold.second, fold.angle_deg, kMaxFoldDeg),
                      "nothing was written; reconstruct again (another --edge) and check the frames there with "
                      "`contour4d evaluate`");
  };
  for (std::size_t f = 0; f < seq.positions.size(); ++f) {
    const Fold fold = sharpest_fold(seq.positions[f], seq.triangles, pairs);
    if (fold.angle_deg > kMaxFoldDeg) refuse(fmt::format("frame {}", f), fold);
  }
  std::vector<Fold> folds(h.steps.times_s.size());
  const auto body = [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) folds[i] = sharpest_fold(surface_at(h, i), seq.triangles, pairs);
  };
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] { tbb::parallel_for(tbb::blocked_range<std::size_t>(0, folds.size()), body); });
  for (std::size_t i = 0; i < folds.size(); ++i)
    if (folds[i].angle_deg > kMaxFoldDeg)
      refuse(fmt::format("t = {:.4g} s (step {})", h.steps.times_s[i], i), folds[i]);
}

}  // namespace

ExportRun export_run(const ExportInput& in, const ExportRunOptions& o) {
  ExportRun run;
  run.ends = export_ends(in);
  if (run.ends.empty() && o.open != "none")
    throw InvalidInput(ErrorCode::BadMesh, {in.folder.string()},
                       "no end cap found: no contour loops lie on the slice planes of report.json's stack normal",
                       "export reads folders of `contour4d reconstruct`");
  run.opened = choose_ends(run.ends, o.open);
  Handoff& h = run.handoff;
  h.surface = open_ends(in.seq, in.normal, run.ends, run.opened, o.names);
  h.steps = make_time_steps(cycle_period(in.seq.times_ms) / 1000.0, o.steps);
  refuse_folds(h, o.threads);
  h.cavity = mesh_cavity(h.surface.seq.frame(0), o.cavity);
  h.motion = cavity_motion(h.cavity, h.surface.seq, h.steps.times_s, {o.threads});
  for (std::size_t i = 0; i < h.steps.times_s.size(); ++i) {
    const double v = signed_volume({surface_at(h, i), h.surface.seq.triangles});
    run.surface_volume_mm3.push_back(v);
    run.max_volume_difference = std::max(run.max_volume_difference, std::abs(h.motion.steps[i].volume_mm3 - v) / v);
  }
  run.report = report_json(in, run, o);
  return run;
}

void write_export(const OutputDir& out, const ExportRun& run, const ExportRunOptions& o) {
  const Handoff& h = run.handoff;
  for (const std::string& target : o.targets) {
    if (target == "svfsi")
      write_svfsi(out, "svfsi", h, length_scale(o.units.empty() ? "m" : o.units));
    else if (target == "openfoam")
      write_openfoam(out, "openfoam", h, length_scale(o.units.empty() ? "m" : o.units));
    else if (target == "vampy")
      write_vampy(out, "vampy", h, length_scale(o.units.empty() ? "mm" : o.units));
    else
      throw InvalidInput(ErrorCode::Usage, {}, "unknown --to target '" + target + "'", "use svfsi, openfoam or vampy");
  }
  // The cavity of frame 0 (mm), with each boundary triangle's face, and optionally at every step.
  VtkArray face{"FaceID", 1, {}, {}};
  for (std::uint8_t f : h.surface.face) face.ints.push_back(f);
  out.write("cavity/surface.vtp",
            format_vtp_data(h.surface.seq.positions.front(), h.surface.seq.triangles, {{}, {face}},
                            "contour4d export: the surface at t = 0 (mm), FaceID 0 wall"));
  out.write("cavity/cavity.vtu",
            format_vtu_tets(h.cavity.nodes, h.cavity.tets, {}, "contour4d export: the cavity at t = 0 (mm)"));
  if (o.cavity_steps) {
    std::vector<PvdEntry> entries;
    const int width = std::max(3, static_cast<int>(fmt::format("{}", h.steps.times_s.size() - 1).size()));
    for (std::size_t i = 0; i < h.steps.times_s.size(); ++i) {
      const std::string name = fmt::format("steps/cavity_{:0{}}.vtu", i, width);
      out.write(
          "cavity/" + name,
          format_vtu_tets(
              cavity_nodes_at(h.cavity, h.surface.seq, h.motion, step_weights(h.surface.seq, h.steps.times_s[i])),
              h.cavity.tets, {}, fmt::format("contour4d export: the cavity at t = {} s (mm)", h.steps.times_s[i])));
      entries.push_back({1000.0 * h.steps.times_s[i], name});
    }
    out.write("cavity/cavity.pvd", format_pvd(entries));
  }
  out.write("export.json", run.report);
}

}  // namespace c4d
