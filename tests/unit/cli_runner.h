#pragma once
// Test helper: runs the contour4d executable (C4D_CLI) with arguments, output discarded.
#include <sys/wait.h>

#include <cstdlib>
#include <string>

namespace c4d::test {

//! Runs `contour4d ARGS` (stdout and stderr discarded); returns its exit code, or −1 when it did not exit.
inline int run_cli(const std::string& args) {
  const std::string cmd = std::string(C4D_CLI) + " " + args + " >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace c4d::test
