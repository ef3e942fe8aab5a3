#include "cli.h"

#include <iostream>

#include "contour4d/core/errors.h"

namespace c4d::cli {

void add_evaluate_command(CLI::App& root, std::vector<Command>& commands) {
  CLI::App* app = root.add_subcommand("evaluate", "(not available yet)");
  commands.push_back({app, [] {
                        throw Error(ErrorCode::NotImplemented, {}, "'evaluate' is not available yet");
                        return 0;
                      }});
}

}  // namespace c4d::cli
