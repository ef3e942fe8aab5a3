// contour4d command-line tool. SPDX-License-Identifier: GPL-3.0-or-later
#include "cli.h"
#include "contour4d/core/allocator.h"

int main(int argc, char** argv) {
  c4d::keep_freed_memory();
  return c4d::cli::run(argc, argv);
}
