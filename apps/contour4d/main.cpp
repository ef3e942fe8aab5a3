// contour4d command-line tool. SPDX-License-Identifier: GPL-3.0-or-later
#include "cli.h"

int main(int argc, char** argv) { return c4d::cli::run(argc, argv); }
