#pragma once
// Test helper shared by the readers' malformed-input corpora (tests/corpus/<reader>): every good_*
// entry must read, every bad_NN_* entry must fail with a c4d::Error of exit code NN that names it.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "contour4d/core/errors.h"

namespace c4d::test {

//! How many good_* and bad_* entries check_corpus ran.
struct CorpusCounts {
  int good = 0;
  int bad = 0;
};

//! Runs `read(path)` on each entry of C4D_CORPUS_DIR/`folder` (its sub-folders when `folders`, else
//! its files), in name order; other names (a README.md) are skipped.
template <class Read>
CorpusCounts check_corpus(const std::string& folder, Read read, bool folders = false) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(C4D_CORPUS_DIR) / folder;
  CorpusCounts n;
  EXPECT_TRUE(fs::is_directory(dir)) << "corpus folder missing: " << dir;
  if (!fs::is_directory(dir)) return n;
  std::vector<fs::path> entries;
  for (const auto& e : fs::directory_iterator(dir))
    if (folders ? e.is_directory() : e.is_regular_file()) entries.push_back(e.path());
  std::sort(entries.begin(), entries.end());
  for (const fs::path& p : entries) {
    const std::string name = p.filename().string();
    SCOPED_TRACE(name);
    if (name.rfind("good_", 0) == 0) {
      EXPECT_NO_THROW(read(p));
      ++n.good;
    } else if (name.rfind("bad_", 0) == 0) {
      const int expected = std::stoi(name.substr(4, 2));
      try {
        read(p);
        ADD_FAILURE() << "no error";
      } catch (const Error& e) {
        EXPECT_EQ(static_cast<int>(e.code()), expected) << e.what();
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << "message must name the input: " << e.what();
      }
      ++n.bad;
    }
  }
  return n;
}

}  // namespace c4d::test
