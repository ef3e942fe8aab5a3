// `contour4d reconstruct`: contours in, 4D mesh out (the main job).
#include <iostream>

#include <fmt/format.h>

#include "cli.h"
#include "contour4d/core/errors.h"
#include "contour4d/io/input.h"

namespace c4d::cli {
namespace {

struct ReconstructArgs {
  std::string input;
  std::string output;
  int frame = -1;
  std::string label;
  std::vector<std::string> types;
};

int run_reconstruct(const ReconstructArgs& a) {
  InputOptions in;
  in.label = a.label;
  in.contour_types = a.types;
  const InputResult read = read_contours(a.input, in);
  std::cout << fmt::format("read {} ({}): {} frames\n", a.input, read.format, read.sequence.frames.size());
  for (const std::string& n : read.notes) std::cout << "  " << n << "\n";
  throw Error(ErrorCode::NotImplemented, Location{a.input},
              "surface reconstruction is not available in this build yet (contours were read and validated; "
              "nothing was written)",
              "Use `contour4d extract` to inspect the contours meanwhile");
}

}  // namespace

void add_reconstruct_command(CLI::App& root, std::vector<Command>& commands) {
  auto args = std::make_shared<ReconstructArgs>();
  CLI::App* app = root.add_subcommand("reconstruct", "Contours in, 4D mesh out: one watertight mesh per frame with 1-to-1 vertex correspondence");
  app->footer(
      "Examples:\n"
      "  contour4d reconstruct ../shared/data/bivme-patient1/guidepoints -o out/lv\n"
      "  contour4d reconstruct contours.json --frame 0 -o out/frame0\n"
      "  contour4d reconstruct contours.json --label lv-endo -o out/lv\n"
      "INPUT is a contour JSON file or a biv-me GPFile folder. Outputs: OUTDIR/mesh.pvd (open in ParaView),\n"
      "OUTDIR/frames/frame_NNN.{vtp,obj}, OUTDIR/report.json. Coordinates in mm, in the input's patient space.");
  app->add_option("INPUT", args->input, "contour JSON file or GPFile folder")->required();
  app->add_option("-o,--output", args->output, "output folder (replaced atomically)")->required();
  app->add_option("--frame", args->frame, "reconstruct this frame only (0-based)");
  app->add_option("--label", args->label, "structure to reconstruct when the input holds several");
  app->add_option("--type", args->types, "GPFile contour type(s) to use (default SAX_LV_ENDOCARDIAL)");
  commands.push_back({app, [args] { return run_reconstruct(*args); }});
}

}  // namespace c4d::cli
