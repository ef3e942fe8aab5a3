// `contour4d evaluate`: the papers' measures for a 4D mesh output folder (docs/evaluate.md).
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli.h"
#include "contour4d/core/errors.h"
#include "contour4d/pipeline/input.h"
#include "contour4d/io/mesh_output.h"
#include "contour4d/io/output_dir.h"
#include "contour4d/metrics/evaluation.h"

namespace c4d::cli {
namespace {
struct EvaluateArgs {
  std::string outdir;
  std::string contours;
  std::string truth;
  std::string json;
  std::string label;
  std::vector<std::string> contour_types;
  bool check = false;
  bool no_self_intersections = false;
  double step = 0.2;
  double spacing = 0.5;
};

int run_evaluate(const EvaluateArgs& a) {
  const std::filesystem::path outdir(a.outdir);
  const MeshFrames meshes = read_mesh_frames(outdir);
  if (meshes.meshes.empty())
    throw IoError(ErrorCode::BadMesh, {outdir.string()}, "no mesh frames found",
                  "pass the folder written by `contour4d reconstruct -o OUTDIR` (it holds mesh.pvd and frames/)");
  std::optional<Sequence> contours;
  if (!a.contours.empty()) {
    InputOptions in;
    in.label = a.label;
    in.contour_types = a.contour_types;
    in.contour_tolerance_mm = 0.0;  // conformity to the contours as drawn, not as smoothed
    contours = read_contours(a.contours, in).sequence;
  }
  std::optional<MeshFrames> truth;
  if (!a.truth.empty()) truth = read_mesh_frames(a.truth);

  EvaluationOptions opt;
  opt.conformity.step = a.step;
  opt.sampling.spacing = a.spacing;
  opt.topology.self_intersections = !a.no_self_intersections;
  const Evaluation ev = evaluate(meshes, contours ? &*contours : nullptr, truth ? &*truth : nullptr, opt);

  const std::filesystem::path json = a.json.empty() ? outdir / "evaluation.json" : std::filesystem::path(a.json);
  write_file_atomic(json, format_evaluation_json(ev));
  std::cout << "evaluated " << meshes.meshes.size() << " frames of " << outdir.string() << "\n\n"
            << format_evaluation_table(ev) << "\nwrote " << json.string() << "\n";
  if (a.check && ev.has_topology_fault()) {
    std::cerr << "contour4d: --check: " << ev.faults.size() << " fault(s) found (listed above)\n";
    return static_cast<int>(ErrorCode::BadMesh);
  }
  return 0;
}
}  // namespace

void add_evaluate_command(CLI::App& root, std::vector<Command>& commands) {
  CLI::App* app = root.add_subcommand(
      "evaluate",
      "Measure a 4D mesh as the papers do: per frame the surface's validity (holes, manifoldness,\n"
      "orientation, genus, self-intersections), triangle angle quality (Lim et al. Tables 3-4),\n"
      "conformity to the contours (distance from points every 0.2 mm along each contour), accuracy\n"
      "against a ground truth (mean/max/RMS both ways, Hausdorff; Table 5), the volume next to\n"
      "Simpson's discs with EDV/ESV/EF, and vertex correspondence across frames (including\n"
      "frames whose vertices look permuted). Faults are reported, not errors: the exit code is 0\n"
      "unless a file cannot be read, or --check finds a fault (exit code 25).\n"
      "Lengths mm, areas mm², volumes mm³, angles degrees.");
  app->footer(
      "Examples:\n"
      "  contour4d evaluate out                                # topology, quality, volumes\n"
      "  contour4d evaluate out --contours lv.json             # + conformity, Simpson volumes\n"
      "  contour4d evaluate out --contours lh/contours.json --truth lh/truth --json eval.json\n"
      "  contour4d evaluate out --check                        # exit code 25 on any mesh fault (CI)\n");
  auto args = std::make_shared<EvaluateArgs>();
  app->add_option("OUTDIR", args->outdir, "output folder of a reconstruction (mesh.pvd, frames/)")->required();
  app->add_option(
      "--contours", args->contours,
      "the input contours (JSON file or GPFile folder), as drawn (not smoothed): conformity, Simpson volume, "
      "creases along the contour lines, slab");
  app->add_option("--truth,--reference", args->truth,
                  "folder of reference meshes (same layout; frame i compares with frame i): a phantom's truth, each "
                  "frame's own one-frame surface, or the exact meshes of a packed model (distances both ways and "
                  "the angle of each triangle's normal to the reference's)");
  app->add_option("--json", args->json, "where to write the JSON report (default OUTDIR/evaluation.json)");
  app->add_option("--label", args->label, "use only the contours with this label");
  app->add_option("--type", args->contour_types,
                  "GPFile contour types to read (repeatable; default SAX_LV_ENDOCARDIAL), as in reconstruct");
  app->add_option("--step", args->step, "contour sampling interval for conformity (mm)")
      ->default_val(0.2)
      ->check(CLI::PositiveNumber);
  app->add_option("--sample-spacing", args->spacing, "surface sample spacing for accuracy (mm)")
      ->default_val(0.5)
      ->check(CLI::PositiveNumber);
  app->add_flag("--no-self-intersections", args->no_self_intersections,
                "skip the self-intersection test (the slowest check)");
  app->add_flag("--check", args->check, "exit with code 25 (BadMesh) when any mesh or correspondence fault is found");
  commands.push_back({app, [args] { return run_evaluate(*args); }});
}

}  // namespace c4d::cli
