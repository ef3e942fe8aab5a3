#pragma once
//! \file model_c4d.h
//! \brief The model.c4d file: a CompactModel (temporal/compact.h) in one little-endian binary file
//! with a magic, a version and an FNV-1a 64 checksum of the stored payload, which is zstd-compressed
//! by default. docs/compact.md gives the layout.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "contour4d/core/mesh.h"
#include "contour4d/temporal/compact.h"

namespace c4d {

//! The format version written and read: 4 (frame 0 and every frame's move on one grid; header flag bit 1 =
//! the stored payload is one zstd frame). Versions 1–3 (the control-vertex model) are refused with a
//! message asking to pack again.
constexpr std::uint32_t kModelC4dVersion = 4;

//! Largest decompressed payload the reader accepts (1 GiB); a zstd frame declaring more is refused
//! before anything is allocated.
constexpr std::uint64_t kModelC4dMaxPayload = std::uint64_t{1} << 30;

//! How serialize_model_c4d / write_model_c4d store the payload.
struct ModelC4dWriteOptions {
  bool compress = true;  //!< true (default): one zstd frame, flag bit 1 set; false: raw payload, bit 1 clear
  int level = 19;        //!< zstd level (default 19, 1–22); single-threaded, so a given libzstd writes the same
                         //!< bytes on every run and machine
};

//! Bytes of the model.c4d header (magic, version, flags, stored payload size, checksum).
constexpr std::size_t kModelC4dHeaderBytes = 8 + 4 + 4 + 8 + 8;

//! FNV-1a 64-bit hash of a byte string (the file's checksum).
std::uint64_t fnv1a64(std::string_view bytes);

//! The bytes of a model.c4d file (version kModelC4dVersion).
std::string serialize_model_c4d(const CompactModel& model, const ModelC4dWriteOptions& options = {});

//! Parses the bytes of a model.c4d file; `name` is used in error messages.
//! \throw IoError (Format) on a wrong magic, version or flags, (Parse) on a truncated file, a checksum
//! mismatch, a damaged zstd frame or one declaring more than kModelC4dMaxPayload bytes.
CompactModel parse_model_c4d(std::string_view bytes, const std::string& name = "model.c4d");

//! Writes model.c4d atomically. \throw IoError (OutputNotWritable).
void write_model_c4d(const std::filesystem::path& path, const CompactModel& model,
                     const ModelC4dWriteOptions& options = {});

//! Reads a model.c4d file. \throw IoError (FileNotFound, Format, Parse).
CompactModel read_model_c4d(const std::filesystem::path& path);

//! compact_decode for a model read from `name`: a stream that does not decode is an IoError (Parse) naming it.
MeshSequence decode_model_c4d(const CompactModel& model, const std::string& name);

//! Reads and decodes a model.c4d file to its mesh sequence. \throw IoError (FileNotFound, Format, Parse).
MeshSequence read_model_c4d_sequence(const std::filesystem::path& path);

}  // namespace c4d
