// contour4d command-line tool. SPDX-License-Identifier: GPL-3.0-or-later
#include "cli.h"
#include "contour4d/core/allocator.h"
#include "contour4d/io/output_dir.h"

int main(int argc, char** argv) {
  c4d::keep_freed_memory();
  c4d::remove_stages_on_interrupt();  // Ctrl-C leaves no hidden staging folder beside the output
  return c4d::cli::run(argc, argv);
}
