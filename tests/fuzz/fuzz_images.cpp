// libFuzzer target: label-image reader (NIfTI, NRRD, MetaImage through ITK) and extraction.
// The first byte picks the extension; the rest is the file. Any input must end in a c4d::Error
// or a valid series, never a crash, hang or leak.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "contour4d/core/errors.h"
#include "contour4d/extract/mask_contours.h"
#include "contour4d/io/images.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const char* ext[] = {".nii", ".nii.gz", ".nrrd", ".mha"};
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("c4d_fuzz_images_" + std::to_string(::getpid()) + ext[data[0] % 4]);
  {
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try {
    c4d::LabelSeries s;
    s.frames = c4d::read_label_image(file);
    s.source = file.string();
    std::size_t voxels = 0;
    for (const auto& v : s.frames) voxels += v.labels.size();
    if (voxels <= (1u << 20)) (void)c4d::extract_mask_contours(s);
  } catch (const c4d::Error&) {}
  std::error_code ec;
  std::filesystem::remove(file, ec);
  return 0;
}
