// libFuzzer target: the RT structure set reader (DCMTK parses the file) on any bytes, as a file, read with
// repairs and strictly (every ROI, and the first by number). The answer is a result or a c4d::Error; any other
// exception, crash, leak or hang is a bug. Seed corpus: tests/corpus/rtstruct.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "contour4d/core/errors.h"
#include "contour4d/io/rtstruct.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // DCMTK reads files (values over 4 kB on access), so the input goes through one.
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("c4d_fuzz_rtstruct_" + std::to_string(::getpid()) + ".dcm");
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    (void)c4d::read_rtstruct(file);
  } catch (const c4d::Error&) {}
  try {
    c4d::RtStructOptions strict;
    strict.repair = false;
    strict.label = "1";
    (void)c4d::read_rtstruct(file, strict);
  } catch (const c4d::Error&) {}
  return 0;
}
