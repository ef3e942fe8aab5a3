// Compact 4D model and model.c4d: error bound, round trips, rigid-motion invariance, corrupt files.
#include "contour4d/temporal/compact.h"

#include <gtest/gtest.h>
#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "contour4d/core/errors.h"
#include "contour4d/temporal/model_c4d.h"
#include "contour4d/temporal/displacement_map.h"
#include "contour4d/temporal/sequence.h"
#include "corpus_check.h"
#include "temporal_fixtures.h"

namespace c4d {
namespace {

// Distance from p to triangle abc by projection and edge clamping (test-local, independent of the
// library's implementation).
double tri_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = cross(b - a, c - a);
  const double nn = dot(n, n);
  if (nn > 0) {
    const Vec3 q = p - (dot(p - a, n) / nn) * n;
    const double u = dot(cross(c - b, q - b), n), v = dot(cross(a - c, q - c), n), w = dot(cross(b - a, q - a), n);
    if (u >= 0 && v >= 0 && w >= 0) return distance(p, q);
  }
  auto seg = [&](const Vec3& x, const Vec3& y) {
    const Vec3 d = y - x;
    const double t = dot(d, d) > 0 ? std::clamp(dot(p - x, d) / dot(d, d), 0.0, 1.0) : 0.0;
    return distance(p, x + t * d);
  };
  return std::min({seg(a, b), seg(b, c), seg(c, a)});
}

double surface_distance(const Vec3& p, const std::vector<Vec3>& pos, const std::vector<Triangle>& tris) {
  double best = 1e300;
  for (const Triangle& t : tris) best = std::min(best, tri_distance(p, pos[t[0]], pos[t[1]], pos[t[2]]));
  return best;
}

// The beating shape with per-vertex noise: mostly along the surface (as vertices of a
// reconstruction slide), a little across it.
MeshSequence noisy_beating(int subdivisions, std::size_t frames) {
  MeshSequence seq = synthetic_beating_mesh(subdivisions, frames);
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  for (std::size_t f = 1; f < frames; ++f)
    for (Vec3& p : seq.positions[f]) {
      const Vec3 n = normalized(Vec3{p.x / 900.0, p.y / 900.0, p.z / 2025.0});
      Vec3 r{g(rng), g(rng), g(rng)};
      r = r - dot(r, n) * n;
      p += 0.3 * r + 0.03 * g(rng) * n;
    }
  return seq;
}

double max_error(const MeshSequence& in, const MeshSequence& out, const std::vector<std::uint32_t>& order) {
  double e = 0.0;
  for (std::size_t f = 0; f < in.positions.size(); ++f)
    for (std::size_t v = 0; v < order.size(); ++v)
      e = std::max(e, distance(out.positions[f][v], in.positions[f][order[v]]));
  return e;
}

TEST(Compact, DecodedWithinToleranceAndSameConnectivity) {
  const MeshSequence seq = synthetic_beating_mesh(4, 12);  // 5120 triangles
  std::vector<std::uint32_t> order;
  CompactStats st;
  CompactOptions opt;
  const CompactModel m = compact_encode(seq, opt, &order, &st);
  const MeshSequence out = compact_decode(m);
  ASSERT_EQ(out.positions.size(), seq.positions.size());
  ASSERT_EQ(out.triangles.size(), seq.triangles.size());
  EXPECT_LE(max_error(seq, out, order), opt.tolerance);
  EXPECT_NEAR(st.max_error, max_error(seq, out, order), 1e-9);
  EXPECT_LE(st.max_error, m.tolerance);
  EXPECT_LE(st.normal_p99, opt.normal_p99);
  EXPECT_EQ(out.times_ms, seq.times_ms);
  // Same triangles up to the vertex permutation (and triangle order): compare as sorted sets.
  std::vector<std::array<std::uint32_t, 3>> a, b;
  for (const Triangle& t : seq.triangles) {
    std::array<std::uint32_t, 3> x = t;
    std::rotate(x.begin(), std::min_element(x.begin(), x.end()), x.end());
    a.push_back(x);
  }
  for (const Triangle& t : out.triangles) {
    std::array<std::uint32_t, 3> x{order[t[0]], order[t[1]], order[t[2]]};
    std::rotate(x.begin(), std::min_element(x.begin(), x.end()), x.end());
    b.push_back(x);
  }
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  // Orientation kept: the volume of each frame matches.
  for (std::size_t f = 0; f < seq.positions.size(); ++f)
    EXPECT_NEAR(signed_volume(out.frame(f)), signed_volume(seq.frame(f)), 1e-3 * signed_volume(seq.frame(f)));
}

TEST(Compact, TighterToleranceHolds) {
  const MeshSequence seq = synthetic_beating_mesh(3, 8);
  for (double tol : {0.2, 0.05, 0.01}) {
    CompactOptions opt;
    opt.tolerance = tol;
    std::vector<std::uint32_t> order;
    const MeshSequence out = compact_decode(compact_encode(seq, opt, &order));
    EXPECT_LE(max_error(seq, out, order), tol) << "tolerance " << tol;
  }
}

TEST(Compact, WithoutReorderKeepsIds) {
  const MeshSequence seq = synthetic_beating_mesh(3, 6);
  CompactOptions opt;
  opt.reorder = false;
  const MeshSequence out = compact_decode(compact_encode(seq, opt));
  // The index codec may rotate a triangle's corners (winding kept) but keeps the triangle order.
  ASSERT_EQ(out.triangles.size(), seq.triangles.size());
  for (std::size_t t = 0; t < seq.triangles.size(); ++t) {
    Triangle a = seq.triangles[t], b = out.triangles[t];
    std::rotate(a.begin(), std::min_element(a.begin(), a.end()), a.end());
    std::rotate(b.begin(), std::min_element(b.begin(), b.end()), b.end());
    EXPECT_EQ(a, b) << t;
  }
  for (std::size_t f = 0; f < seq.positions.size(); ++f)
    for (std::size_t v = 0; v < seq.positions[f].size(); ++v)
      EXPECT_LE(distance(out.positions[f][v], seq.positions[f][v]), opt.tolerance);
}

TEST(Compact, RigidMotionInvariantError) {
  MeshSequence seq = synthetic_beating_mesh(3, 6);
  MeshSequence moved = seq;
  const double c = std::cos(0.7), s = std::sin(0.7);
  for (auto& frame : moved.positions)
    for (Vec3& p : frame) p = Vec3{c * p.x - s * p.z + 100.0, p.y - 50.0, s * p.x + c * p.z + 7.0};
  for (const MeshSequence* q : {&seq, &moved}) {
    std::vector<std::uint32_t> order;
    const MeshSequence out = compact_decode(compact_encode(*q, {}, &order));
    EXPECT_LE(max_error(*q, out, order), 0.05);
  }
}

TEST(Compact, DeterministicBytes) {
  const MeshSequence seq = synthetic_beating_mesh(3, 5);
  EXPECT_EQ(serialize_model_c4d(compact_encode(seq)), serialize_model_c4d(compact_encode(seq)));
}

TEST(Compact, FileRoundTripAndCorruption) {
  const MeshSequence seq = synthetic_beating_mesh(2, 4);
  const CompactModel m = compact_encode(seq);
  const std::string bytes = serialize_model_c4d(m);
  const CompactModel back = parse_model_c4d(bytes);
  EXPECT_EQ(serialize_model_c4d(back), bytes);
  // Every truncated prefix fails cleanly.
  for (std::size_t n = 0; n < bytes.size(); n += 7) EXPECT_THROW(parse_model_c4d(bytes.substr(0, n)), IoError) << n;
  // A flipped payload bit fails the checksum.
  std::string bad = bytes;
  bad[bad.size() / 2] = static_cast<char>(bad[bad.size() / 2] ^ 0x10);
  EXPECT_THROW(parse_model_c4d(bad), IoError);
  std::string wrong = bytes;
  wrong[0] = 'X';
  try {
    parse_model_c4d(wrong);
    FAIL();
  } catch (const IoError& e) {
    EXPECT_EQ(e.code(), ErrorCode::Format);
  }
}

// --- model.c4d: the payload as one zstd frame (flag bit 1) ------------------------------------------

// Little-endian field of a file's bytes.
std::uint64_t le(const std::string& b, std::size_t at, int bytes) {
  std::uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= static_cast<std::uint64_t>(static_cast<unsigned char>(b[at + i])) << (8 * i);
  return v;
}
void put_le(std::string& s, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) s.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

// A model.c4d around `stored` with a correct size and checksum.
std::string with_header(std::uint32_t version, std::uint32_t flags, std::string_view stored) {
  std::string out = "C4DMODEL";
  put_le(out, version, 4);
  put_le(out, flags, 4);
  put_le(out, stored.size(), 8);
  put_le(out, fnv1a64(stored), 8);
  out.append(stored);
  return out;
}
std::string stored_payload(const std::string& file) { return file.substr(kModelC4dHeaderBytes); }

// A zstd frame (magic, frame header with a window descriptor, one last empty raw block) that declares
// `content` bytes (8-byte field), or no size at all when `content` is negative.
std::string zstd_frame_declaring(long long content) {
  std::string f("\x28\xb5\x2f\xfd", 4);
  if (content < 0) {
    f += std::string("\x00\x00", 2);  // FHD: no content size, not single segment; window 1 KiB
  } else {
    f += std::string("\xc0\x00", 2);  // FHD: 8-byte content size, not single segment; window 1 KiB
    put_le(f, static_cast<std::uint64_t>(content), 8);
  }
  f += std::string("\x01\x00\x00", 3);  // last block, raw, 0 bytes
  return f;
}

// `payload` as one zstd frame at level 19, as the writer stores it.
std::string zstd_compress(std::string_view payload) {
  std::string z(ZSTD_compressBound(payload.size()), '\0');
  const std::size_t n = ZSTD_compress(z.data(), z.size(), payload.data(), payload.size(), 19);
  EXPECT_FALSE(ZSTD_isError(n));
  z.resize(ZSTD_isError(n) ? 0 : n);
  return z;
}

void expect_same_model(const CompactModel& a, const CompactModel& b) {
  EXPECT_EQ(a.vertex_count, b.vertex_count);
  EXPECT_EQ(a.triangle_count, b.triangle_count);
  EXPECT_EQ(a.frame_count, b.frame_count);
  EXPECT_EQ(a.times_ms, b.times_ms);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(a.origin[i], b.origin[i]);
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.tolerance, b.tolerance);
  EXPECT_EQ(a.indices, b.indices);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.motion, b.motion);
}

// The code of the IoError that parsing `bytes` throws; fails the test on success or another exception.
ErrorCode parse_error(const std::string& bytes, const std::string& name = "model.c4d") {
  try {
    parse_model_c4d(bytes, name);
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << "message must name the file: " << e.what();
    return e.code();
  }
  ADD_FAILURE() << "no IoError";
  return ErrorCode::Internal;
}

ModelC4dWriteOptions uncompressed() {
  ModelC4dWriteOptions o;
  o.compress = false;
  return o;
}

TEST(CompactFile, CompressedRoundTripEqualsUncompressed) {
  const MeshSequence seq = synthetic_beating_mesh(3, 6);
  const CompactModel m = compact_encode(seq);
  const std::string z = serialize_model_c4d(m);
  const std::string raw = serialize_model_c4d(m, uncompressed());
  EXPECT_EQ(le(z, 8, 4), kModelC4dVersion);
  EXPECT_EQ(kModelC4dVersion, 4u);
  EXPECT_EQ(le(z, 12, 4), 2u);  // bit 1: zstd
  EXPECT_EQ(le(raw, 8, 4), 4u);
  EXPECT_EQ(le(raw, 12, 4), 0u);
  EXPECT_EQ(le(z, 16, 8), z.size() - kModelC4dHeaderBytes);
  EXPECT_LT(z.size(), raw.size());
  EXPECT_EQ(serialize_model_c4d(m), z);  // byte-identical when written twice
  const CompactModel from_z = parse_model_c4d(z), from_raw = parse_model_c4d(raw);
  expect_same_model(from_z, from_raw);
  expect_same_model(from_z, m);
  EXPECT_EQ(serialize_model_c4d(from_z), z);
}

// Versions 1–3 (the control-vertex model of earlier builds) are refused with a message that says to pack
// again; unknown versions and flags are refused; a raw payload flagged as zstd and the reverse fail cleanly.
TEST(CompactFile, RefusesOlderVersionsAndUnknownFlags) {
  const CompactModel m = compact_encode(synthetic_beating_mesh(2, 4));
  const std::string payload = stored_payload(serialize_model_c4d(m, uncompressed()));
  const std::string zstored = stored_payload(serialize_model_c4d(m));
  expect_same_model(parse_model_c4d(with_header(4, 2, zstored)), m);
  expect_same_model(parse_model_c4d(with_header(4, 0, payload)), m);
  for (std::uint32_t old : {1u, 2u, 3u}) {
    EXPECT_EQ(parse_error(with_header(old, 0, payload)), ErrorCode::Format);
    try {
      parse_model_c4d(with_header(old, 2, zstored));
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find("contour4d pack"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(parse_error(with_header(4, 1, payload)), ErrorCode::Format);  // bit 0 (surface corrections) is gone
  EXPECT_EQ(parse_error(with_header(4, 4, payload)), ErrorCode::Format);  // unknown bit 2
  EXPECT_EQ(parse_error(with_header(4, 0x80000000u, payload)), ErrorCode::Format);
  EXPECT_EQ(parse_error(with_header(0, 0, payload)), ErrorCode::Format);
  EXPECT_EQ(parse_error(with_header(5, 0, payload)), ErrorCode::Format);
  EXPECT_EQ(parse_error(with_header(4, 2, payload)), ErrorCode::Parse);
  EXPECT_EQ(parse_error(with_header(4, 0, zstored)), ErrorCode::Parse);
}

// Bytes flipped inside the zstd frame, with a recomputed (valid) checksum: the decompressor or the
// payload parser catches them; nothing but IoError escapes, and nothing crashes.
TEST(CompactFile, CorruptZstdFrameWithValidChecksum) {
  const CompactModel m = compact_encode(synthetic_beating_mesh(2, 4));
  const std::string zstored = stored_payload(serialize_model_c4d(m));
  std::size_t rejected = 0, tried = 0;
  for (std::size_t i = 0; i < zstored.size(); ++i)
    for (unsigned char mask : {0x01, 0x10, 0xff}) {
      std::string bad = zstored;
      bad[i] = static_cast<char>(bad[i] ^ mask);
      ++tried;
      try {
        parse_model_c4d(with_header(4, 2, bad));
      } catch (const IoError& e) {
        EXPECT_EQ(e.code(), ErrorCode::Parse) << e.what();
        ++rejected;
      }
    }
  // zstd frames carry no checksum of their own (the header's FNV covers the stored bytes): many flips
  // decode to another payload that parses (about 3 in 4 here, in entropy-coded literals and in the
  // meshopt and varint blocks, which the parser does not interpret); the others fail cleanly.
  EXPECT_GT(rejected, tried / 10) << rejected << " of " << tried;
  // The frame's magic, a frame cut short, and bytes after the frame always fail.
  std::string bad = zstored;
  bad[0] = static_cast<char>(bad[0] ^ 0x01);
  EXPECT_EQ(parse_error(with_header(4, 2, bad)), ErrorCode::Parse);
  for (std::size_t n = 0; n < zstored.size(); n += 5)
    EXPECT_EQ(parse_error(with_header(4, 2, zstored.substr(0, n))), ErrorCode::Parse) << n;
  EXPECT_EQ(parse_error(with_header(4, 2, zstored + std::string("\0", 1))), ErrorCode::Parse);
  EXPECT_EQ(parse_error(with_header(4, 2, zstored + zstored)), ErrorCode::Parse);
  // A valid frame around a damaged payload: the payload parser rejects it as it would uncompressed.
  const std::string payload = stored_payload(serialize_model_c4d(m, uncompressed()));
  EXPECT_EQ(zstd_compress(payload), zstored);  // the writer's frame is ZSTD_compress at level 19
  for (std::size_t n = 0; n < payload.size(); n += 3)
    EXPECT_EQ(parse_error(with_header(4, 2, zstd_compress(payload.substr(0, n)))), ErrorCode::Parse) << n;
  EXPECT_EQ(parse_error(with_header(4, 2, zstd_compress(payload + "x"))), ErrorCode::Parse);
}

// A frame declaring more than 1 GiB, more than its length can hold, or no size: refused up front.
TEST(CompactFile, RefusesImplausibleZstdContentSize) {
  for (long long declared : {1LL << 40, (1LL << 30) + 1, -1LL, 1LL << 29, 1000LL}) {
    SCOPED_TRACE(declared);
    EXPECT_EQ(parse_error(with_header(4, 2, zstd_frame_declaring(declared)), "huge.c4d"), ErrorCode::Parse);
  }
  try {
    parse_model_c4d(with_header(4, 2, zstd_frame_declaring(1LL << 40)), "huge.c4d");
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("1099511627776"), std::string::npos) << e.what();
  }
  // The hand-made frame itself is valid: declaring 0 bytes, it decompresses to an empty payload,
  // which the payload parser reports as truncated.
  EXPECT_EQ(parse_error(with_header(4, 2, zstd_frame_declaring(0))), ErrorCode::Parse);
}

// Counts that the streams cannot hold (vertices, triangles) and damaged meshopt streams: compact_decode
// answers InvalidInput (BadMesh) before allocating for them; nothing else escapes.
TEST(CompactFile, DecodeRefusesImplausibleCountsAndDamagedStreams) {
  const CompactModel m = compact_encode(synthetic_beating_mesh(2, 4));
  CompactModel big = m;
  big.vertex_count = 0xffffffffu;
  EXPECT_THROW(compact_decode(big), InvalidInput);
  big = m;
  big.triangle_count = 0xfffffffu;
  EXPECT_THROW(compact_decode(big), InvalidInput);
  big = m;
  big.vertex_count = 1u << 27;  // 4 frames: 2^29 vertex-frames, more than a model may decode to
  EXPECT_THROW(compact_decode(big), InvalidInput);
  std::size_t tried = 0;
  for (std::size_t i = 0; i < m.positions.size(); i += 3)
    for (const std::size_t block : {std::size_t{0}, std::size_t{1}}) {
      CompactModel bad = m;
      std::vector<std::uint8_t>& b = block == 0 ? bad.positions : bad.motion[0];
      if (i >= b.size()) continue;
      b[i] ^= 0xa5;
      ++tried;
      try {
        const MeshSequence out = compact_decode(bad);
        EXPECT_EQ(out.positions.size(), m.frame_count);
      } catch (const InvalidInput& e) {
        EXPECT_EQ(e.code(), ErrorCode::BadMesh);
      }
    }
  EXPECT_GT(tried, 10u);
  CompactModel cut = m;
  cut.positions.resize(cut.positions.size() / 2);
  EXPECT_THROW(compact_decode(cut), InvalidInput);
  cut = m;
  cut.motion.pop_back();
  EXPECT_THROW(compact_decode(cut), InvalidInput);
}

TEST(CompactFile, TruncationsFail) {
  const CompactModel m = compact_encode(synthetic_beating_mesh(2, 4));
  for (const std::string& bytes : {serialize_model_c4d(m), serialize_model_c4d(m, uncompressed())}) {
    for (std::size_t n = 0; n < bytes.size(); ++n) {
      EXPECT_EQ(parse_error(bytes.substr(0, n)), n == 0 ? ErrorCode::EmptyFile : ErrorCode::Parse) << n;
    }
  }
}

// tests/corpus/model_c4d: bad_NN_* must fail with ErrorCode NN and name the file, good_* read.
// The files come from CompactFile.WriteCorpus (see the folder's README.md).
TEST(CompactFile, Corpus) {
  const test::CorpusCounts n =
      test::check_corpus("model_c4d", [](const std::filesystem::path& p) { read_model_c4d_sequence(p); });
  EXPECT_GE(n.bad, 8);
  EXPECT_GE(n.good, 3);
}

// Regenerates tests/corpus/model_c4d into $C4D_WRITE_MODEL_C4D_CORPUS (skipped when it is unset):
//   C4D_WRITE_MODEL_C4D_CORPUS=tests/corpus/model_c4d build-zstd/tests/compact_test --gtest_filter=CompactFile.WriteCorpus
TEST(CompactFile, WriteCorpus) {
  const char* out = std::getenv("C4D_WRITE_MODEL_C4D_CORPUS");
  if (out == nullptr) GTEST_SKIP() << "set C4D_WRITE_MODEL_C4D_CORPUS to a folder to write the corpus";
  namespace fs = std::filesystem;
  fs::create_directories(out);
  auto write = [&](const std::string& name, const std::string& bytes) {
    std::ofstream(fs::path(out) / name, std::ios::binary) << bytes;
  };
  // A tiny model: the 42-vertex beating shape over 3 frames.
  const MeshSequence seq = synthetic_beating_mesh(1, 3);
  const CompactModel mv = compact_encode(seq);
  const std::string z = serialize_model_c4d(mv), raw = serialize_model_c4d(mv, uncompressed());
  const std::string zstored = stored_payload(z), payload = stored_payload(raw);
  write("good_v4_zstd.c4d", z);
  write("good_v4_uncompressed.c4d", raw);
  CompactOptions coarse;
  coarse.step = 0.2;
  coarse.normal_p99 = 90.0;
  write("good_v4_coarse_grid.c4d", serialize_model_c4d(compact_encode(seq, coarse)));
  std::string magic = z;
  magic[3] = 'X';
  write("bad_13_bad_magic.c4d", magic);
  write("bad_11_empty.c4d", "");
  write("bad_12_truncated_magic.c4d", "C4DMO");
  write("bad_13_version_5.c4d", with_header(5, 2, zstored));
  write("bad_13_version_0.c4d", with_header(0, 0, payload));
  write("bad_13_version_3_older_model.c4d", with_header(3, 2, zstored));
  write("bad_13_surface_flag_bit0.c4d", with_header(4, 3, zstored));
  write("bad_13_unknown_flag_bit2.c4d", with_header(4, 6, zstored));
  write("bad_12_truncated_header.c4d", z.substr(0, kModelC4dHeaderBytes - 3));
  write("bad_12_truncated_payload.c4d", z.substr(0, z.size() - 10));
  std::string sum = z;
  sum[sum.size() - 7] = static_cast<char>(sum[sum.size() - 7] ^ 0x04);
  write("bad_12_checksum_mismatch.c4d", sum);
  write("bad_12_zstd_frame_cut_short.c4d", with_header(4, 2, zstored.substr(0, zstored.size() - 6)));
  write("bad_12_zstd_trailing_bytes.c4d", with_header(4, 2, zstored + "\x01\x02"));
  write("bad_12_zstd_huge_content_size.c4d", with_header(4, 2, zstd_frame_declaring(1LL << 40)));
  write("bad_12_zstd_unknown_content_size.c4d", with_header(4, 2, zstd_frame_declaring(-1)));
  write("bad_12_zstd_flag_on_raw_payload.c4d", with_header(4, 2, payload));
  write("bad_12_raw_flag_on_zstd_payload.c4d", with_header(4, 0, zstored));
  // A flip inside the frame (after its header) that the decompressor itself rejects, checksum fixed.
  for (std::size_t i = zstored.size() / 2; i < zstored.size(); ++i) {
    std::string bad = zstored;
    bad[i] = static_cast<char>(bad[i] ^ 0xff);
    try {
      parse_model_c4d(with_header(4, 2, bad));
    } catch (const IoError& e) {
      if (std::string(e.what()).find("does not decompress") == std::string::npos) continue;
      write("bad_12_zstd_corrupt_frame.c4d", with_header(4, 2, bad));
      break;
    }
  }
  // Valid frames whose content is a damaged payload: one byte too many; a vertex count the position stream
  // cannot hold (the first u32); a damaged position stream (its first bytes after the block length).
  write("bad_12_zstd_payload_trailing_byte.c4d", with_header(4, 2, zstd_compress(payload + "x")));
  std::string counts = payload;
  for (std::size_t i = 0; i < 4; ++i) counts[i] = static_cast<char>(0xff);
  write("bad_12_zstd_payload_too_many_vertices.c4d", with_header(4, 2, zstd_compress(counts)));
  write("bad_12_payload_too_many_vertices.c4d", with_header(4, 0, counts));
  const std::size_t positions = 12 + 8 * 5 + 8 * static_cast<std::size_t>(mv.frame_count) + 8 + mv.indices.size() + 8;
  std::string stream = payload;
  for (std::size_t i = 0; i < 6; ++i) stream[positions + i] = static_cast<char>(0xff);
  write("bad_12_damaged_position_stream.c4d", with_header(4, 0, stream));
}

// The facet normals follow the input (a vertex-noisy shape, and the same shape 20 times smaller, whose
// 0.1 mm triangles make the encoder refine its grid), checked here independently of the encoder's measure.
TEST(Compact, NormalsStayWithinTheBoundAndSmallTrianglesRefineTheGrid) {
  for (const double scale : {1.0, 0.05}) {
    SCOPED_TRACE(scale);
    MeshSequence seq = noisy_beating(3, 6);
    for (auto& frame : seq.positions)
      for (Vec3& p : frame) p = scale * p;
    CompactOptions opt;
    std::vector<std::uint32_t> order;
    CompactStats st;
    const CompactModel m = compact_encode(seq, opt, &order, &st);
    const MeshSequence out = compact_decode(parse_model_c4d(serialize_model_c4d(m)));
    double worst_p99 = 0.0;
    for (std::size_t f = 0; f < seq.positions.size(); ++f) {
      std::vector<double> angles;
      for (const Triangle& t : out.triangles) {
        const Vec3 a =
            cross(out.positions[f][t[1]] - out.positions[f][t[0]], out.positions[f][t[2]] - out.positions[f][t[0]]);
        const std::vector<Vec3>& in = seq.positions[f];
        const Vec3 b = cross(in[order[t[1]]] - in[order[t[0]]], in[order[t[2]]] - in[order[t[0]]]);
        angles.push_back(std::acos(std::clamp(dot(a, b) / (norm(a) * norm(b)), -1.0, 1.0)) * 180.0 / M_PI);
      }
      std::sort(angles.begin(), angles.end());
      worst_p99 = std::max(worst_p99, angles[static_cast<std::size_t>(0.99 * static_cast<double>(angles.size()))]);
    }
    EXPECT_LE(worst_p99, opt.normal_p99);
    EXPECT_NEAR(worst_p99, st.normal_p99, 0.05);
    EXPECT_LE(max_error(seq, out, order), m.tolerance + 1e-12);
    if (scale < 1.0) {
      EXPECT_LT(m.step, opt.step);  // small triangles: a finer grid
    }
  }
}

// Base mesh + displacement maps: the displaced lattice samples lie on the fine surface (they are
// its intersections with the patch normals), the smooth PN patches alone do not; the CPU
// tessellation has level² triangles per base triangle and shares edge vertices.
TEST(DisplacementMap, SamplesLieOnTheFineSurface) {
  const auto [seq, po, pm] = test::beating_patches(3, 3, 80, 4);
  ASSERT_GT(pm.triangles.size(), 40u);
  EXPECT_EQ(pm.missed, 0u);
  EXPECT_EQ(pm.displacement.size(), seq.positions.size() * pm.triangles.size() * patch_samples(po.grid));
  double on = 0.0, off = 0.0;
  for (std::size_t f = 0; f < seq.positions.size(); ++f)
    for (std::size_t t = 0; t < pm.triangles.size(); t += 3)
      for (int j = 0; j <= po.grid; ++j)
        for (int i = 0; i + j <= po.grid; ++i) {
          const double b1 = double(i) / po.grid, b2 = double(j) / po.grid;
          on = std::max(on, surface_distance(patch_point(pm, f, t, b1, b2), seq.positions[f], seq.triangles));
          off = std::max(off, surface_distance(patch_point(pm, f, t, b1, b2, false), seq.positions[f], seq.triangles));
        }
  EXPECT_LT(on, 1e-3);
  EXPECT_GT(off, 10 * on);
  const MeshSequence tess = tessellate_patches(pm, 3);
  EXPECT_EQ(tess.triangles.size(), pm.triangles.size() * 9);
  // Closed base mesh: V - E + F = 2 with shared edge vertices (E = 3F/2).
  const long long F = static_cast<long long>(tess.triangles.size()),
                  V = static_cast<long long>(tess.positions[0].size());
  EXPECT_EQ(V - 3 * F / 2 + F, 2);
  EXPECT_THROW(build_patch_mesh(seq, PatchOptions{80, 0, 4.0}), InvalidInput);
}

TEST(Compact, RejectsInconsistentFrames) {
  MeshSequence seq = synthetic_beating_mesh(1, 3);
  seq.positions[2].pop_back();
  EXPECT_THROW(compact_encode(seq), InvalidInput);
  MeshFrames frames;
  const MeshSequence good = synthetic_beating_mesh(1, 2);
  frames.meshes = {good.frame(0), good.frame(1)};
  frames.meshes[1].triangles[0] = {0, 2, 1};
  frames.times_ms = {0, 1};
  EXPECT_THROW(to_mesh_sequence(frames, "x"), InvalidInput);
}

}  // namespace
}  // namespace c4d
