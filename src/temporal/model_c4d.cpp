// model.c4d: the compact 4D model on disk (docs/compact.md). Explicit little-endian fields, so the
// file is the same on every machine; the checksum catches truncation and bit rot before decoding; the
// payload is one zstd frame (flag bit 1), decompressed into a buffer of its declared size.
#include "contour4d/temporal/model_c4d.h"

#include <zstd.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <memory>

#include "contour4d/core/errors.h"
#include "contour4d/io/output_dir.h"

namespace c4d {
namespace {

constexpr char kMagic[8] = {'C', '4', 'D', 'M', 'O', 'D', 'E', 'L'};
constexpr std::size_t kHeader = kModelC4dHeaderBytes;
constexpr std::uint32_t kFlagZstd = 2u;  // bit 1: the stored payload is one zstd frame
// Every zstd block yields at most ZSTD_BLOCKSIZE_MAX bytes and takes at least 4 (3-byte header + 1
// byte of an RLE block), so a frame of n bytes cannot hold more than this many bytes per byte of it.
constexpr std::uint64_t kMaxZstdRatio = ZSTD_BLOCKSIZE_MAX / 4;

[[noreturn]] void damaged(const std::string& name, const std::string& what) {
  throw IoError(ErrorCode::Parse, {name}, what, "the file is damaged: run `contour4d pack` again");
}

// A decompressed payload (not zero-filled first: a bogus frame that fails early touches little memory).
struct Buffer {
  std::unique_ptr<char[]> data;
  std::size_t size = 0;
};

// The payload inside a stored zstd frame: exactly one frame, its content size declared,
// plausible for its length and at most kModelC4dMaxPayload; decompressed to exactly that size.
Buffer decompress_payload(std::string_view stored, const std::string& name) {
  const unsigned long long content = ZSTD_getFrameContentSize(stored.data(), stored.size());
  if (content == ZSTD_CONTENTSIZE_ERROR) damaged(name, "the compressed payload has an invalid zstd frame header");
  if (content == ZSTD_CONTENTSIZE_UNKNOWN) damaged(name, "the zstd frame of the payload does not declare its size");
  if (content > kModelC4dMaxPayload)
    throw IoError(ErrorCode::Parse, {name},
                  "the zstd frame declares a payload of " + std::to_string(content) +
                      " bytes, more than this build reads (" + std::to_string(kModelC4dMaxPayload) + ")",
                  "the file is damaged or not from `contour4d pack`: run `contour4d pack` again");
  const std::size_t frame = ZSTD_findFrameCompressedSize(stored.data(), stored.size());
  if (ZSTD_isError(frame))
    damaged(name, std::string("the compressed payload is not a valid zstd frame (") + ZSTD_getErrorName(frame) + ")");
  if (frame != stored.size())
    damaged(name,
            "the compressed payload has " + std::to_string(stored.size() - frame) + " bytes after its zstd frame");
  if (content > static_cast<std::uint64_t>(stored.size()) * kMaxZstdRatio)
    damaged(name, "the zstd frame declares " + std::to_string(content) + " bytes, impossible in " +
                      std::to_string(stored.size()) + " compressed bytes");
  Buffer out{std::make_unique_for_overwrite<char[]>(static_cast<std::size_t>(content)),
             static_cast<std::size_t>(content)};
  const std::size_t got = ZSTD_decompress(out.data.get(), out.size, stored.data(), stored.size());
  if (ZSTD_isError(got))
    damaged(name, std::string("the compressed payload does not decompress (") + ZSTD_getErrorName(got) + ")");
  if (got != out.size)
    damaged(name, "the compressed payload decompresses to " + std::to_string(got) + " bytes, its frame declares " +
                      std::to_string(out.size));
  return out;
}

void put_u32(std::string& s, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
void put_u64(std::string& s, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) s.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
void put_f64(std::string& s, double d) {
  std::uint64_t v;
  std::memcpy(&v, &d, 8);
  put_u64(s, v);
}
void put_block(std::string& s, const std::vector<std::uint8_t>& b) {
  put_u64(s, b.size());
  s.append(reinterpret_cast<const char*>(b.data()), b.size());
}

struct Reader {
  std::string_view s;
  std::size_t pos = 0;
  std::string name;
  void need(std::size_t n) {
    if (n > s.size() - pos)
      throw IoError(ErrorCode::Parse, {name}, "truncated model file (at byte " + std::to_string(pos) + ")",
                    "the file is incomplete: run `contour4d pack` again");
  }
  std::uint64_t u(int bytes) {
    need(static_cast<std::size_t>(bytes));
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= static_cast<std::uint64_t>(static_cast<unsigned char>(s[pos + i])) << (8 * i);
    pos += static_cast<std::size_t>(bytes);
    return v;
  }
  std::uint32_t u32() { return static_cast<std::uint32_t>(u(4)); }
  double f64() {
    const std::uint64_t v = u(8);
    double d;
    std::memcpy(&d, &v, 8);
    return d;
  }
  std::vector<std::uint8_t> block() {
    const std::uint64_t n = u(8);
    need(n <= s.size() ? static_cast<std::size_t>(n) : std::numeric_limits<std::size_t>::max());
    std::vector<std::uint8_t> b(reinterpret_cast<const std::uint8_t*>(s.data() + pos),
                                reinterpret_cast<const std::uint8_t*>(s.data() + pos + n));
    pos += static_cast<std::size_t>(n);
    return b;
  }
};

}  // namespace

std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  return h;
}

std::string serialize_model_c4d(const CompactModel& m, const ModelC4dWriteOptions& options) {
  std::string p;
  put_u32(p, m.vertex_count);
  put_u32(p, m.triangle_count);
  put_u32(p, m.frame_count);
  for (double o : m.origin) put_f64(p, o);
  put_f64(p, m.step);
  put_f64(p, m.tolerance);
  for (double t : m.times_ms) put_f64(p, t);
  put_block(p, m.indices);
  put_block(p, m.positions);
  for (const auto& b : m.motion) put_block(p, b);

  std::uint32_t flags = 0u;
  if (options.compress) {  // one zstd frame (ZSTD_compress: single-threaded, content size in the header)
    std::string z(ZSTD_compressBound(p.size()), '\0');
    const std::size_t n = ZSTD_compress(z.data(), z.size(), p.data(), p.size(), options.level);
    if (ZSTD_isError(n))
      throw Error(ErrorCode::Internal, {}, std::string("zstd compression failed: ") + ZSTD_getErrorName(n),
                  "please report this bug");
    z.resize(n);
    p = std::move(z);
    flags |= kFlagZstd;
  }
  std::string out(kMagic, 8);
  put_u32(out, kModelC4dVersion);
  put_u32(out, flags);
  put_u64(out, p.size());
  put_u64(out, fnv1a64(p));
  out += p;
  return out;
}

CompactModel parse_model_c4d(std::string_view bytes, const std::string& name) {
  if (bytes.empty())
    throw IoError(ErrorCode::EmptyFile, {name}, "the file is empty", "pass a model.c4d written by `contour4d pack`");
  if (std::memcmp(bytes.data(), kMagic, std::min<std::size_t>(bytes.size(), 8)) != 0)
    throw IoError(ErrorCode::Format, {name}, "not a contour4d model file (bad magic)",
                  "pass a model.c4d written by `contour4d pack`");
  if (bytes.size() < kHeader)
    throw IoError(ErrorCode::Parse, {name},
                  "truncated model file (header of " + std::to_string(bytes.size()) + " of " + std::to_string(kHeader) +
                      " bytes)",
                  "the file is incomplete: run `contour4d pack` again");
  Reader h{bytes, 8, name};
  const std::uint32_t version = h.u32();
  if (version >= 1 && version < kModelC4dVersion)
    throw IoError(ErrorCode::Format, {name},
                  "model.c4d version " + std::to_string(version) +
                      " holds the control-vertex model of an older contour4d, which this build no longer reads",
                  "pack the reconstruction's output folder again: contour4d pack OUTDIR");
  if (version != kModelC4dVersion)
    throw IoError(ErrorCode::Format, {name},
                  "model.c4d version " + std::to_string(version) + " is not supported (this build reads version " +
                      std::to_string(kModelC4dVersion) + ")",
                  "pack the 4D mesh again with this contour4d");
  const std::uint32_t flags = h.u32();
  if ((flags & ~kFlagZstd) != 0)
    throw IoError(ErrorCode::Format, {name}, "model.c4d flags " + std::to_string(flags) + " are not supported",
                  "pack the 4D mesh again with this contour4d");
  const std::uint64_t size = h.u(8);
  const std::uint64_t sum = h.u(8);
  if (size != bytes.size() - kHeader)
    throw IoError(
        ErrorCode::Parse, {name},
        "payload is " + std::to_string(bytes.size() - kHeader) + " bytes, header says " + std::to_string(size),
        "the file is truncated or padded: run `contour4d pack` again");
  const std::string_view stored = bytes.substr(kHeader);
  if (fnv1a64(stored) != sum) damaged(name, "checksum mismatch");
  Buffer decompressed;
  if (flags & kFlagZstd) decompressed = decompress_payload(stored, name);
  const std::string_view payload =
      (flags & kFlagZstd) ? std::string_view(decompressed.data.get(), decompressed.size) : stored;
  Reader r{payload, 0, name};
  CompactModel m;
  m.vertex_count = r.u32();
  m.triangle_count = r.u32();
  m.frame_count = r.u32();
  for (double& o : m.origin) o = r.f64();
  m.step = r.f64();
  m.tolerance = r.f64();
  if (m.frame_count == 0) damaged(name, "the model has no frames");
  r.need(static_cast<std::size_t>(m.frame_count) * 8);
  for (std::uint32_t f = 0; f < m.frame_count; ++f) m.times_ms.push_back(r.f64());
  m.indices = r.block();
  m.positions = r.block();
  r.need(static_cast<std::size_t>(m.frame_count - 1) * 8);  // one length per motion block at least
  for (std::uint32_t f = 1; f < m.frame_count; ++f) m.motion.push_back(r.block());
  if (r.pos != payload.size()) damaged(name, "trailing bytes after the last frame");
  return m;
}

void write_model_c4d(const std::filesystem::path& path, const CompactModel& model,
                     const ModelC4dWriteOptions& options) {
  write_file_atomic(path, serialize_model_c4d(model, options));
}

CompactModel read_model_c4d(const std::filesystem::path& path) {
  return parse_model_c4d(read_file(path), path.string());
}

MeshSequence decode_model_c4d(const CompactModel& model, const std::string& name) {
  try {
    return compact_decode(model);
  } catch (const InvalidInput& e) {
    Location where{name};
    where.frame = e.where().frame;
    throw IoError(ErrorCode::Parse, where, e.detail(), e.hint());
  }
}

MeshSequence read_model_c4d_sequence(const std::filesystem::path& path) {
  return decode_model_c4d(read_model_c4d(path), path.string());
}

}  // namespace c4d
