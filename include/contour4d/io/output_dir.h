#pragma once
//! \file output_dir.h
//! \brief Atomic outputs: a file is written under a temporary name and renamed when complete; a
//! folder of outputs is staged beside its destination and swapped in whole, so a failed run
//! leaves nothing behind (DEVELOPERS.md rule 3).

#include <filesystem>
#include <string>
#include <string_view>

namespace c4d {

//! Writes `content` to `path` through `path.tmp-PID` and a rename.
//! \throw IoError (ErrorCode::OutputNotWritable) naming the path.
void write_file_atomic(const std::filesystem::path& path, std::string_view content);

//! Reads a whole file. \throw IoError (FileNotFound) naming the path.
std::string read_file(const std::filesystem::path& path);

//! On SIGINT or SIGTERM, removes the staging folders of every live OutputDir (and the half-written files
//! of write_file_atomic are left as NAME.tmp-PID only until the next run), then ends the process with the
//! signal. For command-line tools; call once at start.
void remove_stages_on_interrupt();

//! A staging folder for the outputs of one run. Files go to `path(rel)`; `commit()` replaces the
//! destination folder by the staged one; the destructor removes an uncommitted stage.
class OutputDir {
 public:
  //! Creates `.NAME.c4d-tmp-PID` beside `destination`.
  //! \throw IoError (OutputNotWritable) when the parent cannot be created or written.
  explicit OutputDir(std::filesystem::path destination);
  ~OutputDir();
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  //! Path inside the stage for a relative output path (parent folders are created).
  std::filesystem::path path(const std::filesystem::path& relative) const;
  //! Writes a file inside the stage.
  void write(const std::filesystem::path& relative, std::string_view content) const;
  //! Moves the stage to the destination (an existing destination folder is replaced).
  //! \throw IoError (OutputNotWritable).
  void commit();
  const std::filesystem::path& destination() const { return destination_; }

 private:
  std::filesystem::path destination_;
  std::filesystem::path stage_;
  bool committed_ = false;
  int slot_ = -1;  //!< this stage's entry in the list removed on SIGINT/SIGTERM
};

}  // namespace c4d
