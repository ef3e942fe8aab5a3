// `contour4d export`: a reconstruction to the inputs of flow solvers (docs/export.md).
#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>
#include <sstream>

#include <fmt/format.h>

#include "cli.h"
#include "contour4d/core/errors.h"
#include "contour4d/io/output_dir.h"
#include "contour4d/pipeline/export_run.h"
#include "contour4d/temporal/interpolate.h"

namespace c4d::cli {
namespace {

struct ExportArgs {
  std::string input;
  std::string output;
  std::string names;
  bool list_ends = false;
  ExportRunOptions run;
};

void print_ends(const std::vector<SurfaceEnd>& ends, const std::vector<int>& opened) {
  for (std::size_t i = 0; i < ends.size(); ++i) {
    const SurfaceEnd& e = ends[i];
    const bool open = std::find(opened.begin(), opened.end(), static_cast<int>(i)) != opened.end();
    std::cout << fmt::format("  end {}: {} side, {} ({:.1f} mm², {} border loop{}, plane at {:.2f} mm){}\n", i + 1,
                             e.base ? "base" : "apex", e.name, e.area_mm2, e.loops, e.loops == 1 ? "" : "s",
                             e.offset_mm, open ? ": opened" : "");
  }
}

int run_export(ExportArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!a.names.empty()) {
    std::stringstream in(a.names);
    std::string item;
    while (std::getline(in, item, ',')) a.run.names.push_back(item);
  }
  const ExportInput input = load_export_input(a.input, a.run);
  std::cout << fmt::format("contour4d export: {} ({} frames, {} vertices; times from {}, cycle {:.1f} ms)\n", a.input,
                           input.seq.positions.size(), input.seq.positions.front().size(), input.times_source,
                           cycle_period(input.seq.times_ms));
  if (a.list_ends) {
    const auto ends = export_ends(input);
    print_ends(ends, choose_ends(ends, a.run.open));
    return 0;
  }
  if (a.output.empty()) throw InvalidInput(ErrorCode::Usage, {}, "no output folder", "give -o DIR");
  if (a.run.targets.empty()) throw InvalidInput(ErrorCode::Usage, {}, "no target", "give --to svfsi|openfoam|vampy");
  const ExportRun run = export_run(input, a.run);
  const Handoff& h = run.handoff;
  print_ends(run.ends, run.opened);
  std::cout << fmt::format("  faces:");
  for (const std::string& n : h.surface.names) std::cout << " " << n;
  std::cout << fmt::format("\n  time: {} steps of {:.6g} s per cycle of {:.6g} s, {} output times\n",
                           h.steps.steps_per_cycle, h.steps.dt_s, h.steps.period_s, h.steps.times_s.size());
  std::cout << fmt::format(
      "  cavity: {} nodes ({} inside), {} tets; {} extension, no inverted tet at any step; over the cycle: min "
      "dihedral {:.2f}°, max aspect ratio {:.2f}; cavity volume = surface volume within {:.2g} %\n",
      h.cavity.nodes.size(), h.cavity.nodes.size() - h.cavity.surface_nodes, h.cavity.tets.size(),
      h.motion.extension == Extension::Harmonic ? "harmonic" : "stiffened", h.motion.min_dihedral_deg,
      h.motion.max_aspect_ratio, 100.0 * run.max_volume_difference);
  OutputDir out(a.output);
  write_export(out, run, a.run);
  out.commit();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << fmt::format("  done in {:.2f} s. Output: {}/ (", seconds, a.output);
  for (std::size_t i = 0; i < a.run.targets.size(); ++i) std::cout << (i ? ", " : "") << a.run.targets[i] << "/";
  std::cout << ", cavity/, export.json)\n";
  return 0;
}

}  // namespace

void add_export_command(CLI::App& root, std::vector<Command>& commands) {
  CLI::App* app = root.add_subcommand(
      "export",
      "Hand a reconstruction to flow solvers: the cycle resampled to the solver's steps (periodic C1\n"
      "interpolation, seconds), the chosen ends as flat named faces, a tetrahedral cavity mesh that moves\n"
      "with the wall (no inverted tet at any step), and the files of svFSI / svMultiPhysics, OpenFOAM and\n"
      "VaMPy / OasisMove (docs/export.md). Nothing is written when a check fails.");
  app->footer(
      "Examples:\n"
      "  contour4d export out --to openfoam -o cfd                 # LV: the base opened as one face\n"
      "  contour4d export out --to svfsi --to vampy --steps 1000 -o cfd\n"
      "  contour4d export out --list-ends                          # the ends and their numbers\n"
      "  contour4d export bivme --cycle-ms 1000 --to openfoam --dt 0.001 --cycles 2 -o cfd\n");
  auto args = std::make_shared<ExportArgs>();
  app->add_option("OUTDIR", args->input, "output folder of `contour4d reconstruct` (mesh.pvd, report.json)")
      ->required();
  app->add_option("-o,--output", args->output, "export folder (replaced atomically when complete)");
  app->add_option("--to", args->run.targets, "svfsi, openfoam or vampy; repeat for several")
      ->check(CLI::IsMember({"svfsi", "openfoam", "vampy"}));
  app->add_option("--steps", args->run.steps.steps, "solver steps per cycle (default 100)");
  app->add_option("--dt", args->run.steps.dt_s, "solver step in seconds (must divide the cycle)");
  app->add_option("--cycles", args->run.steps.cycles, "cycles to write")->default_val(1);
  app->add_option("--frame-ms", args->run.frame_ms, "time between frames (ms), for folders without real times");
  app->add_option("--cycle-ms", args->run.cycle_ms, "cycle length (ms), for folders without real times");
  app->add_option("--open", args->run.open, "ends made flat faces: base, apex, all, none or end numbers (1,3)")
      ->default_val("base");
  app->add_option("--names", args->names, "names of the opened ends, in order (e.g. inlet,outlet)");
  app->add_option("--units", args->run.units,
                  "length unit written for every target: m, cm or mm (default: m for svfsi and openfoam, mm for vampy)")
      ->check(CLI::IsMember({"m", "cm", "mm"}));
  app->add_flag("--list-ends", args->list_ends, "list the ends found and exit");
  app->add_option("--threads", args->run.threads, "worker threads (0: all cores); the output does not depend on it");
  const char* advanced = "Advanced";
  app->add_option("--tet-radius-edge", args->run.cavity.radius_edge, "TetGen -q radius-edge bound")
      ->default_val(1.5)
      ->group(advanced);
  app->add_option("--tet-min-dihedral", args->run.cavity.min_dihedral_deg, "TetGen -q smallest dihedral angle (deg)")
      ->default_val(12.0)
      ->group(advanced);
  app->add_option("--max-tet-volume", args->run.cavity.max_volume_mm3, "TetGen -a largest tet (mm³); 0: none")
      ->default_val(0.0)
      ->group(advanced);
  app->add_flag("--cavity-steps", args->run.cavity_steps, "also write the moving cavity at every step (cavity/)")
      ->group(advanced);
  commands.push_back({app, [args] { return run_export(*args); }});
}

}  // namespace c4d::cli
