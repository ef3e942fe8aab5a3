// libFuzzer target: the model.c4d reader must answer any bytes with a model or a c4d::Error; any
// other exception, crash, leak or hang is a bug. The checksum would stop most mutations before the
// decompressor and the payload parser, so each input is also parsed behind valid headers: the body
// (the input, or what follows a model.c4d header in it) as a raw payload, as the content of a zstd
// frame, and as a stored zstd frame itself. A model that parses must survive a write/read round trip, and
// decoding it (the meshopt streams, the counts) must also end in a mesh sequence or a c4d::Error.
#include <zstd.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "contour4d/core/errors.h"
#include "contour4d/temporal/compact.h"
#include "contour4d/temporal/model_c4d.h"

namespace {

void put_le(std::string& s, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) s.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

// A current-version model.c4d around `stored` with a correct size and checksum.
std::string with_header(std::uint32_t flags, std::string_view stored) {
  std::string out = "C4DMODEL";
  put_le(out, c4d::kModelC4dVersion, 4);
  put_le(out, flags, 4);
  put_le(out, stored.size(), 8);
  put_le(out, c4d::fnv1a64(stored), 8);
  out.append(stored);
  return out;
}

void parse_and_round_trip(const std::string& bytes) {
  try {
    const c4d::CompactModel m = c4d::parse_model_c4d(bytes, "fuzz.c4d");
    c4d::ModelC4dWriteOptions raw;
    raw.compress = false;
    const std::string out = c4d::serialize_model_c4d(m, raw);
    if (c4d::serialize_model_c4d(c4d::parse_model_c4d(out, "roundtrip.c4d"), raw) != out) __builtin_trap();
    c4d::ModelC4dWriteOptions fast;
    fast.level = 1;  // the format does not depend on the level; level 19 would slow the fuzzer down
    if (c4d::serialize_model_c4d(c4d::parse_model_c4d(c4d::serialize_model_c4d(m, fast), "roundtrip.c4d"), raw) != out)
      __builtin_trap();
    c4d::compact_decode(m);
  } catch (const c4d::Error&) {}
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  parse_and_round_trip(input);
  const bool has_header = size >= c4d::kModelC4dHeaderBytes && std::memcmp(data, "C4DMODEL", 8) == 0;
  const std::string body = has_header ? input.substr(c4d::kModelC4dHeaderBytes) : input;
  parse_and_round_trip(with_header(0u, body));  // raw payload
  std::string z(ZSTD_compressBound(body.size()), '\0');
  const std::size_t n = ZSTD_compress(z.data(), z.size(), body.data(), body.size(), 1);
  if (ZSTD_isError(n)) __builtin_trap();
  z.resize(n);
  parse_and_round_trip(with_header(2u, z));     // the body as the content of a zstd frame
  parse_and_round_trip(with_header(2u, body));  // the body as a stored zstd frame
  return 0;
}
