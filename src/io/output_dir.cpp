#include "contour4d/io/output_dir.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <csignal>
#include <cstring>
#include <fstream>
#include <system_error>

#include "contour4d/core/errors.h"

namespace c4d {
namespace fs = std::filesystem;

namespace {
[[noreturn]] void fail_output(const fs::path& p, const std::string& what) {
  throw IoError(ErrorCode::OutputNotWritable, Location{p.string()}, what,
                "Choose an output folder you can write to (check the path and its permissions)");
}
std::string tmp_suffix() { return ".tmp-" + std::to_string(static_cast<long>(::getpid())); }

// The live staging folders, in fixed storage a signal handler can read without locking.
constexpr std::size_t kStageSlots = 16;
constexpr std::size_t kStagePathBytes = 4096;
std::array<std::atomic<bool>, kStageSlots> g_stage_used{};
std::array<std::array<char, kStagePathBytes>, kStageSlots> g_stage_path{};

int claim_stage_slot(const fs::path& stage) {
  const std::string s = fs::absolute(stage).string();
  if (s.size() >= kStagePathBytes) return -1;
  for (std::size_t i = 0; i < kStageSlots; ++i) {
    bool expected = false;
    if (!g_stage_used[i].compare_exchange_strong(expected, true)) continue;
    std::memcpy(g_stage_path[i].data(), s.c_str(), s.size() + 1);
    return static_cast<int>(i);
  }
  return -1;  // more live stages than slots: that one is not removed on a signal
}

void release_stage_slot(int slot) {
  if (slot >= 0) g_stage_used[static_cast<std::size_t>(slot)].store(false);
}

extern "C" void remove_stages_and_reraise(int sig) {
  for (std::size_t i = 0; i < kStageSlots; ++i) {
    if (!g_stage_used[i].load()) continue;
    std::error_code ec;
    fs::remove_all(fs::path(g_stage_path[i].data()), ec);
  }
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}
}  // namespace

void remove_stages_on_interrupt() {
  std::signal(SIGINT, remove_stages_and_reraise);
  std::signal(SIGTERM, remove_stages_and_reraise);
}

void write_file_atomic(const fs::path& path, std::string_view content) {
  std::error_code ec;
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) fail_output(path, "cannot create folder " + path.parent_path().string() + ": " + ec.message());
  }
  const fs::path tmp = path.string() + tmp_suffix();
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) fail_output(path, "cannot open a file for writing");
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) {
      out.close();
      fs::remove(tmp, ec);
      fail_output(path, "write failed (disk full?)");
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignore;
    fs::remove(tmp, ignore);
    fail_output(path, "cannot rename the finished file into place: " + ec.message());
  }
}

std::string read_file(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec))
    throw IoError(ErrorCode::FileNotFound, Location{path.string()}, "file not found", "Check the path");
  if (fs::is_directory(path, ec))
    throw IoError(ErrorCode::FileNotFound, Location{path.string()}, "is a folder, expected a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(ErrorCode::FileNotFound, Location{path.string()}, "cannot open file", "Check its permissions");
  std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw IoError(ErrorCode::FileNotFound, Location{path.string()}, "read error");
  return s;
}

OutputDir::OutputDir(fs::path destination) : destination_(std::move(destination)) {
  std::error_code ec;
  if (destination_.empty()) fail_output(destination_, "no output folder given");
  // A trailing slash would leave an empty filename; normalise it away.
  if (!destination_.has_filename()) destination_ = destination_.parent_path();
  if (fs::exists(destination_, ec) && !fs::is_directory(destination_, ec))
    fail_output(destination_, "exists and is not a folder");
  const fs::path parent = destination_.has_parent_path() ? destination_.parent_path() : fs::path(".");
  fs::create_directories(parent, ec);
  if (ec) fail_output(destination_, "cannot create parent folder: " + ec.message());
  stage_ = parent / ("." + destination_.filename().string() + ".c4d" + tmp_suffix());
  fs::remove_all(stage_, ec);
  fs::create_directory(stage_, ec);
  if (ec || !fs::is_directory(stage_)) fail_output(destination_, "cannot create a staging folder beside it");
  slot_ = claim_stage_slot(stage_);
  // Probe writability now, before any work is done.
  const fs::path probe = stage_ / ".probe";
  std::ofstream(probe).put('x');
  if (!fs::exists(probe, ec)) {
    release_stage_slot(slot_);
    fs::remove_all(stage_, ec);
    fail_output(destination_, "folder is not writable");
  }
  fs::remove(probe, ec);
}

OutputDir::~OutputDir() {
  release_stage_slot(slot_);
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(stage_, ec);
  }
}

fs::path OutputDir::path(const fs::path& relative) const {
  const fs::path p = stage_ / relative;
  std::error_code ec;
  fs::create_directories(p.parent_path(), ec);
  if (ec) fail_output(destination_ / relative, "cannot create folder: " + ec.message());
  return p;
}

void OutputDir::write(const fs::path& relative, std::string_view content) const {
  write_file_atomic(path(relative), content);
}

void OutputDir::commit() {
  std::error_code ec;
  const fs::path old = destination_.string() + ".c4d-old" + tmp_suffix();
  const bool had_old = fs::exists(destination_, ec);
  if (had_old) {
    fs::rename(destination_, old, ec);
    if (ec) fail_output(destination_, "cannot replace the existing folder: " + ec.message());
  }
  fs::rename(stage_, destination_, ec);
  if (ec) {
    std::error_code ignore;
    if (had_old) fs::rename(old, destination_, ignore);
    fail_output(destination_, "cannot move the finished output into place: " + ec.message());
  }
  committed_ = true;
  release_stage_slot(slot_);
  slot_ = -1;
  if (had_old) fs::remove_all(old, ec);
}

}  // namespace c4d
