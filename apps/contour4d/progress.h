#pragma once
//! \file progress.h
//! \brief A one-line progress bar on stderr, drawn only when stderr is a terminal.

#include <unistd.h>

#include <cstdio>
#include <string>

namespace c4d::cli {

class ProgressBar {
 public:
  ProgressBar() : enabled_(isatty(fileno(stderr)) != 0) {}
  ~ProgressBar() { finish(); }
  void update(const std::string& stage, int done, int total) {
    if (!enabled_ || total <= 0) return;
    const int width = 30, filled = done * width / total;
    std::fprintf(stderr, "\r%-10s [%s%s] %d/%d", stage.c_str(),
                 std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(width - filled), ' ').c_str(), done, total);
    std::fflush(stderr);
    drawn_ = true;
  }
  void finish() {
    if (drawn_) std::fprintf(stderr, "\r%60s\r", "");
    drawn_ = false;
  }

 private:
  bool enabled_;
  bool drawn_ = false;
};

}  // namespace c4d::cli
