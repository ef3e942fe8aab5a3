#include "cli.h"

#include <unistd.h>

#include <cstdio>
#include <exception>
#include <iostream>
#include <new>

#include "contour4d/core/errors.h"

namespace c4d::cli {

bool stdout_is_terminal() { return isatty(fileno(stdout)) != 0; }

int run(int argc, char** argv) {
  CLI::App root{
      "contour4d turns stacks of 2D contours (cine MRI, 4D CT) into a 4D surface model: one watertight\n"
      "triangle mesh per time frame, every frame with the same vertices and triangles.\n"
      "All coordinates are millimetres in the input's patient space (LPS for DICOM-derived data).\n\n"
      "Examples:\n"
      "  contour4d phantom left-heart -o lh            # analytic phantom: contours + true surface\n"
      "  contour4d evaluate lh/truth --contours lh/contours.json\n"
      "  contour4d reconstruct lh/contours.json -o out  # 4D mesh (see `contour4d reconstruct --help`)\n"
      "  contour4d view out                            # play it (window), or `contour4d render out -o png`\n",
      "contour4d"};
  root.require_subcommand(1);
  root.set_version_flag("--version", "contour4d 0.1.0");
  std::vector<Command> commands;
  add_reconstruct_command(root, commands);
  add_extract_command(root, commands);
  add_evaluate_command(root, commands);
  add_phantom_command(root, commands);
  add_pack_command(root, commands);
  add_unpack_command(root, commands);
  add_export_command(root, commands);
  add_render_command(root, commands);
  add_view_command(root, commands);
  try {
    root.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = root.exit(e);
    return rc == 0 ? 0 : static_cast<int>(ErrorCode::Usage);
  }
  try {
    for (const Command& c : commands)
      if (c.app->parsed()) return c.run();
    return static_cast<int>(ErrorCode::Usage);
  } catch (const Error& e) {
    std::cerr << "contour4d: error: " << e.what() << "\n";
    return static_cast<int>(e.code());
  } catch (const std::bad_alloc&) {
    std::cerr << "contour4d: error: out of memory\n";
    return static_cast<int>(ErrorCode::Internal);
  } catch (const std::exception& e) {
    std::cerr << "contour4d: internal error: " << e.what() << " (please report this with the input)\n";
    return static_cast<int>(ErrorCode::Internal);
  }
}

}  // namespace c4d::cli
