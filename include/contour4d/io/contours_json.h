#pragma once
//! \file contours_json.h
//! \brief The contour4d JSON contour format (docs/formats.md):
//!   {"format": "contour4d-contours", "version": 1, "units": "mm",
//!    "frames": [ {"time_ms": 0.0, "contours": [ {"label": "lv", "slice": 0, "points": [[x,y,z], ...]} ]} ]}

#include <filesystem>
#include <string>

#include "contour4d/core/contour_repair.h"
#include "contour4d/core/stack.h"

namespace c4d {

//! Parses and validates contour JSON text; `source` names the file in messages.
//! \throw IoError / InvalidInput with the file, line, frame, slice and contour.
//! `repairs`: when given, contour flaws are fixed (contour_repair.h) and listed there instead of refused.
Sequence parse_contours_json(const std::string& text, const std::string& source, const StackOptions& options = {},
                             std::vector<ContourRepair>* repairs = nullptr);

//! Reads and validates a contour JSON file. \throw as parse_contours_json, plus FileNotFound / EmptyFile.
Sequence read_contours_json(const std::filesystem::path& path, const StackOptions& options = {},
                            std::vector<ContourRepair>* repairs = nullptr);

//! Formats a sequence as contour JSON (deterministic: fixed precision, input order).
std::string format_contours_json(const Sequence& seq);

}  // namespace c4d
