// libFuzzer target: the contour JSON reader (strict, and with repairs) must answer any bytes with a result or a c4d::Error;
// any other exception, crash, leak or hang is a bug.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "contour4d/core/errors.h"
#include "contour4d/io/contours_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const c4d::Sequence seq = c4d::parse_contours_json(text, "fuzz.json");
    // A valid input must survive a write/read round trip unchanged.
    const std::string out = c4d::format_contours_json(seq);
    if (c4d::format_contours_json(c4d::parse_contours_json(out, "roundtrip.json")) != out) __builtin_trap();
  } catch (const c4d::Error&) {}
  // The default path repairs flawed contours first (contour_repair.h): it too answers with a result or an Error.
  try {
    std::vector<c4d::ContourRepair> repairs;
    c4d::parse_contours_json(text, "fuzz.json", {}, &repairs);
  } catch (const c4d::Error&) {}
  return 0;
}
