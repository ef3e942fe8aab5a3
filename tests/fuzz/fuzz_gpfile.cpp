// libFuzzer target: the GPFile reader on one frame text and one SliceInfoFile text. The input is
// split at the first NUL byte (GPFile text before it, SliceInfoFile text after it); without a NUL,
// a fixed valid SliceInfoFile is used. Only c4d::Error may escape the reader.
#include <cstddef>
#include <cstdint>
#include <string>

#include "contour4d/core/errors.h"
#include "contour4d/io/gpfile.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string kInfo =
      "a.dcm\tsliceID: \t2\tImagePositionPatient\t0\t0\t0\tImageOrientationPatient\t1\t0\t0\t0\t1\t0\t"
      "PixelSpacing\t1\t1\n"
      "b.dcm\tsliceID: \t3\tImagePositionPatient\t0\t0\t10\tImageOrientationPatient\t1\t0\t0\t0\t1\t0\t"
      "PixelSpacing\t1\t1\n";
  const std::string all(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = all.find('\0');
  const std::string frame = all.substr(0, nul);
  const std::string info = nul == std::string::npos ? kInfo : all.substr(nul + 1);
  c4d::GpFileOptions options;
  options.contour_types = {"SAX_LV_ENDOCARDIAL", "SAX_LV_EPICARDIAL"};
  try {
    c4d::parse_gpfile_texts({frame, frame}, info, "fuzz", options);
  } catch (const c4d::Error&) {}
  return 0;
}
