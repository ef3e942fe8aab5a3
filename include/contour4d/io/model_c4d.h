#pragma once
//! \file model_c4d.h
//! \brief The model.c4d file: a CompactModel (temporal/compact.h) in one little-endian binary file
//! with a magic, a version and an FNV-1a 64 checksum of the payload. docs/compact.md gives the layout.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "contour4d/temporal/compact.h"

namespace c4d {

//! Current format version written by serialize_model_c4d (2: header flag bit 0 = surface
//! corrections, CompactError::Surface). Version 1 files are read too.
constexpr std::uint32_t kModelC4dVersion = 2;

//! FNV-1a 64-bit hash of a byte string (the file's checksum).
std::uint64_t fnv1a64(std::string_view bytes);

//! The bytes of a model.c4d file.
std::string serialize_model_c4d(const CompactModel& model);

//! Parses the bytes of a model.c4d file; `name` is used in error messages.
//! \throw IoError (Format) on a wrong magic or version, (Parse) on a truncated file or checksum mismatch.
CompactModel parse_model_c4d(std::string_view bytes, const std::string& name = "model.c4d");

//! Writes model.c4d atomically. \throw IoError (OutputNotWritable).
void write_model_c4d(const std::filesystem::path& path, const CompactModel& model);

//! Reads a model.c4d file. \throw IoError (FileNotFound, Format, Parse).
CompactModel read_model_c4d(const std::filesystem::path& path);

}  // namespace c4d
