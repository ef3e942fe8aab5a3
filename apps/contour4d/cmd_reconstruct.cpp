// `contour4d reconstruct`: contours in, 4D mesh out (the main job).
#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "cli.h"
#include "input_options.h"
#include "contour4d/core/errors.h"
#include "contour4d/pipeline/input.h"
#include "contour4d/io/output_dir.h"
#include "contour4d/pipeline/reconstruct_run.h"
#include "contour4d/pipeline/structures_run.h"
#include "progress.h"

namespace c4d::cli {
namespace {

struct ReconstructArgs {
  std::string input;
  std::string output;
  InputOptions in;
  std::vector<std::string> labels;  //!< --label, repeatable; "all"
  ReconstructRunOptions run;
  std::string keep_failed;
  std::string format = "vtp";
};

// The input summary: what was read, the notes of the reader and the first repairs (flushed before the work).
void print_input_summary(const ReconstructArgs& a, const InputResult& read) {
  std::cout << fmt::format("contour4d reconstruct: {} ({}), {} frames\n", a.input, read.format,
                           read.sequence.frames.size());
  for (const std::string& n : read.notes) std::cout << "  " << n << "\n";
  for (std::size_t k = 0; k < read.repairs.size() && k < 10; ++k) {
    const ContourRepair& r = read.repairs[k];
    std::cout << fmt::format("    repaired frame {}, slice {}, contour {}: {}\n", r.frame, r.slice, r.contour,
                             r.detail);
  }
  if (read.repairs.size() > 10) std::cout << fmt::format("    ... and {} more\n", read.repairs.size() - 10);
  std::cout << std::flush;
}

// Mesh size, the volume curve and EDV/ESV/EF (and the mass, for a myocardial wall).
void print_mesh_summary(const MeshSequence& result, bool wall) {
  std::vector<double> volumes;
  for (std::size_t f = 0; f < result.positions.size(); ++f) volumes.push_back(signed_volume(result.frame(f)));
  const auto ed = std::max_element(volumes.begin(), volumes.end());
  const auto es = std::min_element(volumes.begin(), volumes.end());
  const double edv = *ed, esv = *es;
  std::cout << fmt::format("  mesh: {} vertices, {} triangles, the same in all {} frames\n",
                           result.positions.front().size(), result.triangles.size(), result.positions.size());
  std::cout << "  volume per frame (ml):";
  for (double v : volumes) std::cout << fmt::format(" {:.1f}", v / 1000.0);
  std::cout << "\n";
  if (volumes.size() > 1)
    std::cout << fmt::format("  EDV {:.1f} ml (frame {}), ESV {:.1f} ml (frame {}), EF {:.1f} %\n", edv / 1000,
                             ed - volumes.begin(), esv / 1000, es - volumes.begin(), 100 * (edv - esv) / edv);
  if (wall) {
    double mean = 0.0;
    for (double v : volumes) mean += v / static_cast<double>(volumes.size());
    std::cout << fmt::format("  wall mass {:.1f} g (mean over the frames, {} g/ml)\n", mean / 1000 * kMyocardiumDensity,
                             kMyocardiumDensity);
  }
}

// The closing summary of one structure: the mesh, its volumes, where the output is.
void print_result_summary(const ReconstructArgs& a, const MeshSequence& result, double seconds) {
  print_mesh_summary(result, a.run.label == kLvWall);
  std::cout << fmt::format("  done in {:.2f} s. Output: {}/mesh.pvd (open in ParaView), frames/, report.json\n",
                           seconds, a.output);
}

// Each structure read again with its own label, so that it comes out exactly as `--label NAME` makes it (the
// stack's axes are fitted on the contours read, and a knife-edge choice downstream can follow their last bit).
// The wall (made from two labels) and a structure missing from some frames keep the split's contours, and so does
// every structure with --align-slices: one alignment for all of them, so that the wall's slices are the others'.
void read_each_on_its_own(const ReconstructArgs& a, std::vector<Structure>& structures) {
  if (a.in.align_slices) return;
  for (Structure& s : structures) {
    if (s.wall) continue;
    InputOptions own = a.in;
    own.label = s.name;
    try {
      InputResult r = read_contours(a.input, own);
      if (r.sequence.frames.size() == s.frames.size()) s.input = std::move(r);
    } catch (const Error&) {  // as split (structures.h) made it
    }
  }
}

// Several structures (--label all, or --label given more than once): each into OUTDIR/<label>/.
int run_structures(const ReconstructArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  const MeshFormats formats = parse_mesh_formats(a.format);
  InputOptions in = a.in;
  in.label = "all";  // every label (a Sunnybrook folder's epicardium too)
  const InputResult read = read_contours(a.input, in);
  OutputDir out(a.output);
  print_input_summary(a, read);
  std::vector<Structure> structures = split_structures(read, a.labels);
  read_each_on_its_own(a, structures);
  std::vector<std::string> notes;
  for (const Structure& s : structures)
    for (const std::string& n : s.input.notes) {
      if (std::find(read.notes.begin(), read.notes.end(), n) != read.notes.end()) continue;
      notes.push_back(n);
      std::cout << "  " << n << "\n";
    }
  ProgressBar bar;
  const std::vector<StructureRun> runs = reconstruct_structures(
      structures, a.input, a.run, [&bar](const char* stage, int done, int total) { bar.update(stage, done, total); },
      [&bar](const std::string& line) {
        bar.finish();  // a message on its own line, the bar redrawn by the next update
        std::cout << line << "\n" << std::flush;
      });
  bar.finish();
  const auto failed = std::find_if(runs.begin(), runs.end(), [](const StructureRun& r) { return r.error_code != 0; });
  if (std::all_of(runs.begin(), runs.end(), [](const StructureRun& r) { return r.error_code != 0; }))
    throw SolverError(static_cast<ErrorCode>(failed->error_code), Location{a.input},
                      "no structure could be reconstructed; " + failed->structure.name + ": " + failed->error,
                      "nothing was written to " + a.output);
  write_structures(out, runs, formats, structures_report(runs, a.input, notes));
  for (const StructureRun& r : runs) {
    if (r.error_code != 0) continue;
    std::cout << fmt::format("  {} (OUTDIR/{}/):\n", r.structure.name, r.structure.name);
    print_mesh_summary(r.run.result, r.structure.wall);
  }
  std::cout << fmt::format("  done in {:.2f} s. Output: {}/<structure>/mesh.pvd, {}/report.json (every structure)\n",
                           std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), a.output,
                           a.output);
  if (failed != runs.end()) {
    std::cerr << fmt::format("contour4d: error: structure {} was not written (exit code {}): {}\n",
                             failed->structure.name, failed->error_code, failed->error);
    return failed->error_code;
  }
  return 0;
}

int run_reconstruct(ReconstructArgs a) {
  if (a.labels.size() > 1 || (a.labels.size() == 1 && a.labels[0] == "all")) return run_structures(a);
  const bool wall = a.labels.size() == 1 && a.labels[0] == kLvWall;  // made from lv-endo and lv-epi
  if (a.labels.size() == 1) a.in.label = wall ? "all" : a.labels[0];
  const auto t0 = std::chrono::steady_clock::now();
  const MeshFormats formats = parse_mesh_formats(a.format);  // a bad --format stops before the work
  InputResult read = read_contours(a.input, a.in);
  if (wall) {
    std::vector<std::string> notes = std::move(read.notes);
    read = split_structures(read, {kLvWall}).front().input;
    read.notes.insert(read.notes.begin(), notes.begin(), notes.end());
  }
  OutputDir out(a.output);  // checks the destination is writable before the work starts
  a.run.label = wall ? kLvWall : a.in.label;
  print_input_summary(a, read);
  ProgressBar bar;
  const ReconstructRun run = reconstruct_run(
      read, a.input, a.run, [&bar](const char* stage, int done, int total) { bar.update(stage, done, total); },
      [&bar](const std::string& line) {
        bar.finish();  // a message on its own line, the bar redrawn by the next update
        std::cout << line << "\n" << std::flush;
      });
  bar.finish();
  write_run(out, run, formats, a.keep_failed);  // the output gate: nothing is written when a frame fails its checks
  print_result_summary(a, run.result, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  return 0;
}

}  // namespace

void add_reconstruct_command(CLI::App& root, std::vector<Command>& commands) {
  auto args = std::make_shared<ReconstructArgs>();
  CLI::App* app = root.add_subcommand(
      "reconstruct", "Contours in, 4D mesh out: one watertight mesh per frame with 1-to-1 vertex correspondence");
  app->footer(
      "Examples:\n"
      "  contour4d phantom left-heart -o lh && contour4d reconstruct lh/contours.json -o out/lh   # runs anywhere\n"
      "  contour4d reconstruct patient1/guidepoints -o out/lv          # a biv-me GPFile folder\n"
      "  contour4d reconstruct contours.json --frame 0 -o out/frame0      # one frame only\n"
      "  contour4d reconstruct contours.json --label lv-endo --edge 0.8 -o out/lv     # finer mesh (default edge 1 "
      "mm)\n"
      "  contour4d reconstruct contours.json --cap open -o out/cfd        # open ends for CFD inlets\n"
      "  contour4d reconstruct SC-HF-I-1 --label all -o out/sb   # a Sunnybrook folder: endo, epi and the wall\n"
      "  contour4d reconstruct RS.dcm --label all -o out/rois      # an RT structure set: each ROI into "
      "out/rois/<label>/\n"
      "  contour4d reconstruct RS.dcm --label \"Lung L\" -o out/lung  # one ROI, by its name, label (lung-l) or "
      "number\n"
      "  contour4d reconstruct seg.nii.gz --labels acdc --label lv -o out/lv  # label masks (nnU-Net, Slicer)\n"
      "  contour4d reconstruct seg.nii.gz --labels acdc --label myo --method carry --cycle-ms 800 -o out/myo\n"
      "                                      # a myocardial wall, every frame on its own; frames 800/N ms apart\n"
      "  contour4d reconstruct contours.json --strict -o out/lv      # refuse flawed contours instead of repairing "
      "them\n"
      "INPUT is a contour JSON file, a biv-me GPFile folder, a Sunnybrook folder, a DICOM RT structure set (a .dcm\n"
      "file or a folder holding one) or label image(s). Outputs: "
      "OUTDIR/mesh.pvd (open in ParaView),\n"
      "OUTDIR/frames/frame_NNN.vtp (.obj with --format vtp,obj), OUTDIR/report.json (summary first: volume curve, "
      "ED/ES\n"
      "frames, EDV/ESV/EF). Coordinates in mm, in the input's patient space (LPS for DICOM-derived inputs).\n"
      "Every frame is checked before anything is written; a frame that fails exits with code 26, naming it.");
  // The options a user needs first; the rest under "Advanced" (baselines of the papers, tuning, debugging).
  app->add_option("INPUT", args->input,
                  "contour JSON file, GPFile folder, Sunnybrook folder, RT structure set (.dcm) or label image(s)")
      ->required();
  app->add_option("-o,--output", args->output, "output folder (replaced atomically when complete)")->required();
  app->add_option("--edge", args->run.edge, "target edge length in mm")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 50.0));
  app->add_option("--cap", args->run.cap, "end caps: rounded, flat or open")
      ->capture_default_str()
      ->check(CLI::IsMember({"rounded", "flat", "open"}));
  add_input_options(app, args->in, &args->labels);
  app->add_option("--frame", args->run.frame, "reconstruct this frame only (0-based)");
  app->add_option("--threads", args->run.threads, "worker threads (0: all cores); the output does not depend on it");
  app->add_option("--format", args->format, "mesh files per frame: vtp (always, with mesh.pvd) and obj, e.g. vtp,obj")
      ->capture_default_str();

  const std::string advanced = "Advanced";
  app->add_option("--method", args->run.method,
                  "all frames: auto (default: every frame its own surface on one mesh, frames whose contours change "
                  "carried from the nearest rebuilt frame; rbf-project where that fails its checks or leaves poor "
                  "triangles), rebuild (every frame on one mesh, or a refusal where the contours change), "
                  "rbf-project (frame after frame, RBF then projection on each frame's own surface), carry (frame "
                  "0's mesh carried onto every frame, in parallel) or rbf (the paper's RBF only, a baseline)")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "rebuild", "carry", "rbf-project", "rbf"}))
      ->group(advanced);
  app->add_option("--tiling", args->run.tiling,
                  "surface between slices: bands (default) or delaunay (Lim et al.'s projected constrained Delaunay, "
                  "a baseline)")
      ->check(CLI::IsMember({"bands", "delaunay"}))
      ->capture_default_str()
      ->group(advanced);
  app->add_flag("--vertical-deformation", args->run.vertical,
                "Lim et al.'s sine-shaped vertical deformation where contours split or merge between frames (eq. 10, "
                "a baseline)")
      ->group(advanced);
  app->add_option("--keep-failed", args->keep_failed,
                  "a result that fails its checks exits with code 26 and writes nothing; this writes it to DIR, "
                  "marked FAILED, for debugging")
      ->group(advanced);
  app->add_option("--volume-tolerance", args->run.volume_tolerance,
                  "output check: largest accepted |mesh volume / Simpson's discs volume - 1| per frame")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0))
      ->group(advanced);
  commands.push_back({app, [args] { return run_reconstruct(*args); }});
}

}  // namespace c4d::cli
