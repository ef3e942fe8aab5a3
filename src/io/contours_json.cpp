// The contour4d JSON contour format (docs/formats.md): reader with positions in messages, and a
// deterministic writer. Validation of the geometry is build_sequence's job (core/stack.cpp); this
// file only checks syntax and schema.
#include "contour4d/io/contours_json.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string_view>

#include <nlohmann/json.hpp>

#include "contour4d/core/errors.h"
#include "contour4d/io/output_dir.h"

namespace c4d {

namespace {

using nlohmann::json;

constexpr const char* kFormatName = "contour4d-contours";
constexpr int kMaxDepth = 64;               // the schema nests 5 deep; anything far deeper is not ours
constexpr long long kMaxSliceId = 1000000;  // slice ids are small plane numbers, not coordinates
constexpr const char* kSchemaHint =
    "see docs/formats.md: {\"format\": \"contour4d-contours\", \"version\": 1, \"frames\": [{\"contours\": "
    "[{\"slice\": 0, \"points\": [[x, y, z], ...]}]}]}";

//! 1-based line of byte offset `pos` in `text`.
int line_of(std::string_view text, std::size_t pos) {
  pos = std::min(pos, text.size());
  int line = 1;
  for (std::size_t i = 0; i < pos; ++i)
    if (text[i] == '\n') ++line;
  return line;
}

//! Lines where each contour object starts: lines[frame][contour]. nlohmann keeps no positions on
//! values, so the (already valid) text is scanned once more, tracking the key/index path.
std::vector<std::vector<int>> contour_lines(std::string_view text) {
  struct Level {
    bool array = false;
    bool expect_key = false;  // objects: the next string is a key
    std::string key;          // objects: current key
    long long index = 0;      // arrays: current element
  };
  std::vector<std::vector<int>> lines;
  std::vector<Level> stack;
  int line = 1;
  auto value_starts = [&](bool is_object) {
    // Path frames[i].contours[j] is: object(key frames) / array(i) / object(key contours) / array(j).
    if (!is_object || stack.size() != 4) return;
    if (stack[0].array || stack[0].key != "frames" || !stack[1].array || stack[2].array || stack[2].key != "contours" ||
        !stack[3].array)
      return;
    const auto f = static_cast<std::size_t>(stack[1].index);
    const auto c = static_cast<std::size_t>(stack[3].index);
    if (lines.size() <= f) lines.resize(f + 1);
    if (lines[f].size() <= c) lines[f].resize(c + 1, 0);
    lines[f][c] = line;
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (ch == '\n') {
      ++line;
    } else if (ch == '"') {
      std::string s;
      for (++i; i < text.size() && text[i] != '"'; ++i) {
        if (text[i] == '\\')
          ++i;
        else
          s += text[i];
      }
      if (!stack.empty() && !stack.back().array && stack.back().expect_key) {
        stack.back().key = std::move(s);
        stack.back().expect_key = false;
      }
    } else if (ch == '{' || ch == '[') {
      value_starts(ch == '{');
      stack.push_back({ch == '[', ch == '{', {}, 0});
    } else if (ch == '}' || ch == ']') {
      if (!stack.empty()) stack.pop_back();
    } else if (ch == ',' && !stack.empty()) {
      if (stack.back().array)
        ++stack.back().index;
      else
        stack.back().expect_key = true;
    }
  }
  return lines;
}

[[noreturn]] void fail(ErrorCode code, Location where, const std::string& what, const std::string& hint = kSchemaHint) {
  if (code == ErrorCode::Parse || code == ErrorCode::EmptyFile || code == ErrorCode::FileNotFound)
    throw IoError(code, where, what, hint);
  throw InvalidInput(code, where, what, hint);
}

std::string type_name(const json& j) { return j.type_name(); }

//! One coordinate; null and "NaN"/"Infinity" strings are how other tools write non-finite values.
double coordinate(const json& j, const Location& where, std::size_t point, int axis) {
  const std::string place = "point " + std::to_string(point) + ", coordinate " + "xyz"[axis];
  if (j.is_number()) {
    const double d = j.get<double>();
    if (!std::isfinite(d))
      fail(ErrorCode::NonFinite, where, place + " is not finite", "coordinates must be finite numbers (mm)");
    return d;
  }
  if (j.is_null())
    fail(ErrorCode::NonFinite, where, place + " is null (JSON writers put null for NaN or infinity)",
         "coordinates must be finite numbers (mm); fix the tool that wrote the file");
  if (j.is_string()) {
    std::string s = j.get<std::string>();
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (s == "nan" || s == "inf" || s == "-inf" || s == "+inf" || s == "infinity" || s == "-infinity" ||
        s == "+infinity")
      fail(ErrorCode::NonFinite, where, place + " is the string \"" + j.get<std::string>() + "\" (NaN or infinity)",
           "coordinates must be finite numbers (mm)");
  }
  fail(ErrorCode::Format, where, place + " is a " + type_name(j) + ", expected a number");
}

//! Formats a coordinate: fixed 6 decimals (1 nm), trailing zeros trimmed, "-0" written as "0".
void append_number(std::string& out, double d) {
  char buf[64];
  const int n = std::snprintf(buf, sizeof buf, "%.6f", d);
  std::string s(buf, n > 0 ? static_cast<std::size_t>(std::min(n, 63)) : 0);
  if (s.find('.') != std::string::npos) {
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
  }
  if (s == "-0" || s.empty()) s = "0";
  out += s;
}

std::string quoted(const std::string& s) { return json(s).dump(-1, ' ', false, json::error_handler_t::replace); }

// The parsed document; throws with the line for malformed JSON, too deep nesting and numbers that
// overflow a double.
json parse_document(const std::string& text, const Location& file_loc) {
  json doc;
  try {
    const json::parser_callback_t limit_depth = [&](int depth, json::parse_event_t, json&) {
      if (depth > kMaxDepth)
        fail(ErrorCode::Parse, file_loc, "JSON nested deeper than " + std::to_string(kMaxDepth) + " levels",
             "this is not a contour4d contour file");
      return true;
    };
    doc = json::parse(text, limit_depth);
  } catch (const json::parse_error& e) {
    Location where = file_loc;
    // e.byte is 1-based and points just past the offending character.
    where.line = line_of(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string what = e.what();
    const std::size_t p = what.find("syntax error");
    if (p != std::string::npos) what = what.substr(p);
    const bool truncated = e.byte >= text.size();
    fail(ErrorCode::Parse, where, (truncated ? "JSON ends early (truncated file?): " : "invalid JSON: ") + what,
         "check the file is complete and valid JSON");
  } catch (const json::out_of_range& e) {
    // nlohmann rejects numbers that overflow a double ("number overflow parsing '1e999'").
    Location where = file_loc;
    std::string what = e.what();
    const std::size_t q0 = what.find('\''), q1 = what.rfind('\'');
    if (q0 != std::string::npos && q1 > q0) {
      const std::string token = what.substr(q0 + 1, q1 - q0 - 1);
      const std::size_t at = text.find(token);
      if (!token.empty() && at != std::string::npos) where.line = line_of(text, at);
      fail(ErrorCode::NonFinite, where, "number " + token + " overflows to infinity",
           "coordinates must be finite numbers (mm); JSON has no NaN or Infinity");
    }
    fail(ErrorCode::Parse, where, "invalid JSON: " + what, "check the file is valid JSON");
  } catch (const json::exception& e) {
    fail(ErrorCode::Parse, file_loc, std::string("invalid JSON: ") + e.what(), "check the file is valid JSON");
  }
  return doc;
}

// Checks the top level (an object with our format, version 1, units mm, a known space); sets
// meta.space when the file gives it.
void check_header(const json& doc, const Location& file_loc, Sequence& meta) {
  if (!doc.is_object()) fail(ErrorCode::Format, file_loc, "top level is a " + type_name(doc) + ", not an object");
  const auto fmt_it = doc.find("format");
  if (fmt_it == doc.end() || !fmt_it->is_string() || fmt_it->get<std::string>() != kFormatName)
    fail(ErrorCode::Format, file_loc,
         fmt_it == doc.end() ? std::string("no \"format\" field")
                             : "\"format\" is " + fmt_it->dump(-1, ' ', false, json::error_handler_t::replace) +
                                   ", expected \"" + kFormatName + "\"");
  const auto ver_it = doc.find("version");
  if (ver_it == doc.end() || !ver_it->is_number_integer() || ver_it->get<long long>() != 1)
    fail(ErrorCode::Format, file_loc,
         ver_it == doc.end() ? std::string("no \"version\" field")
                             : "unsupported version " + ver_it->dump() + " (this build reads version 1)",
         "upgrade contour4d or write version 1");
  if (const auto it = doc.find("units"); it != doc.end()) {
    if (!it->is_string() || it->get<std::string>() != "mm")
      fail(ErrorCode::Format, file_loc,
           "\"units\" is " + it->dump(-1, ' ', false, json::error_handler_t::replace) + ", only \"mm\" is supported",
           "convert coordinates to millimetres");
  }
  if (const auto it = doc.find("space"); it != doc.end()) {
    const std::string s = it->is_string() ? it->get<std::string>() : std::string();
    if (s != "LPS" && s != "RAS" && s != "unknown")
      fail(ErrorCode::Format, file_loc, "\"space\" must be \"LPS\", \"RAS\" or \"unknown\"");
    meta.space = s;
  }
}

// The time of frame f (ms): its "time_ms", else f.
double frame_time(const json& fr, std::size_t f, const Location& floc) {
  double t = static_cast<double>(f);
  if (const auto it = fr.find("time_ms"); it != fr.end()) {
    if (!it->is_number()) fail(ErrorCode::Format, floc, "\"time_ms\" is not a number");
    t = it->get<double>();
    if (!std::isfinite(t)) fail(ErrorCode::NonFinite, floc, "\"time_ms\" is not finite");
  }
  return t;
}

// Contour c of frame f (its slice id, label and points), with its line in the file when known.
RawContour read_contour(const json& jc, std::size_t f, std::size_t c, const std::vector<std::vector<int>>& lines,
                        const Location& floc) {
  RawContour rc;
  rc.frame = static_cast<int>(f);
  rc.index = static_cast<int>(c);
  if (f < lines.size() && c < lines[f].size()) rc.line = lines[f][c];
  Location cloc = floc;
  cloc.contour = rc.index;
  if (rc.line > 0) cloc.line = rc.line;
  if (!jc.is_object()) fail(ErrorCode::Format, cloc, "contour is a " + type_name(jc) + ", not an object");
  const auto sit = jc.find("slice");
  if (sit == jc.end()) fail(ErrorCode::Format, cloc, "contour has no \"slice\" id");
  if (!sit->is_number_integer() || sit->get<long long>() < 0 || sit->get<long long>() > kMaxSliceId)
    fail(ErrorCode::Format, cloc,
         "\"slice\" is " + sit->dump() + ", expected an integer plane id in 0.." + std::to_string(kMaxSliceId));
  rc.contour.slice = static_cast<int>(sit->get<long long>());
  cloc.slice = rc.contour.slice;
  if (const auto it = jc.find("label"); it != jc.end()) {
    if (!it->is_string()) fail(ErrorCode::Format, cloc, "\"label\" is not a string");
    rc.contour.label = it->get<std::string>();
  }
  const auto pit = jc.find("points");
  if (pit == jc.end() || !pit->is_array())
    fail(ErrorCode::Format, cloc, pit == jc.end() ? "contour has no \"points\" array" : "\"points\" is not an array");
  rc.contour.points.reserve(pit->size());
  for (std::size_t p = 0; p < pit->size(); ++p) {
    const json& jp = (*pit)[p];
    if (!jp.is_array() || jp.size() != 3)
      fail(ErrorCode::Format, cloc, "point " + std::to_string(p) + " is not an [x, y, z] array");
    rc.contour.points.push_back(
        {coordinate(jp[0], cloc, p, 0), coordinate(jp[1], cloc, p, 1), coordinate(jp[2], cloc, p, 2)});
  }
  return rc;
}

}  // namespace

Sequence parse_contours_json(const std::string& text, const std::string& source, const StackOptions& options,
                             std::vector<ContourRepair>* repairs) {
  Location file_loc;
  file_loc.file = source;
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    fail(ErrorCode::EmptyFile, file_loc, "file is empty",
         "write contours with `contour4d extract` or see docs/formats.md");
  const json doc = parse_document(text, file_loc);
  Sequence meta;
  check_header(doc, file_loc, meta);
  const auto frames_it = doc.find("frames");
  if (frames_it == doc.end() || !frames_it->is_array())
    fail(ErrorCode::Format, file_loc, frames_it == doc.end() ? "no \"frames\" array" : "\"frames\" is not an array");

  const std::vector<std::vector<int>> lines = contour_lines(text);
  const json& frames = *frames_it;
  std::vector<RawContour> raw;
  std::vector<double> times;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    Location floc = file_loc;
    floc.frame = static_cast<int>(f);
    const json& fr = frames[f];
    if (!fr.is_object()) fail(ErrorCode::Format, floc, "frame is a " + type_name(fr) + ", not an object");
    times.push_back(frame_time(fr, f, floc));
    const auto cit = fr.find("contours");
    if (cit == fr.end() || !cit->is_array())
      fail(ErrorCode::Format, floc,
           cit == fr.end() ? "frame has no \"contours\" array" : "\"contours\" is not an array");
    for (std::size_t c = 0; c < cit->size(); ++c) raw.push_back(read_contour((*cit)[c], f, c, lines, floc));
  }
  if (repairs) *repairs = repair_contours(raw);
  Sequence seq = build_sequence(raw, static_cast<int>(frames.size()), times, source, options);
  seq.space = meta.space;
  return seq;
}

Sequence read_contours_json(const std::filesystem::path& path, const StackOptions& options,
                            std::vector<ContourRepair>* repairs) {
  return parse_contours_json(read_file(path), path.string(), options, repairs);
}

std::string format_contours_json(const Sequence& seq) {
  std::string out;
  out += "{\n  \"format\": \"contour4d-contours\",\n  \"version\": 1,\n  \"units\": ";
  out += quoted(seq.units.empty() ? std::string("mm") : seq.units);
  out += ",\n  \"space\": ";
  out += quoted(seq.space.empty() ? std::string("unknown") : seq.space);
  out += ",\n  \"frames\": [";
  for (std::size_t f = 0; f < seq.frames.size(); ++f) {
    const Frame& fr = seq.frames[f];
    out += f ? ",\n" : "\n";
    out += "    {\"time_ms\": ";
    append_number(out, fr.time_ms);
    out += ", \"contours\": [";
    bool first = true;
    for (const Slice& s : fr.slices) {
      for (const Contour& c : s.contours) {
        out += first ? "\n" : ",\n";
        first = false;
        out += "      {";
        if (!c.label.empty()) out += "\"label\": " + quoted(c.label) + ", ";
        out += "\"slice\": " + std::to_string(c.slice) + ", \"points\": [";
        for (std::size_t i = 0; i < c.points.size(); ++i) {
          out += i ? ", [" : "[";
          append_number(out, c.points[i].x);
          out += ", ";
          append_number(out, c.points[i].y);
          out += ", ";
          append_number(out, c.points[i].z);
          out += "]";
        }
        out += "]}";
      }
    }
    out += first ? "]}" : "\n    ]}";
  }
  out += seq.frames.empty() ? "]\n}\n" : "\n  ]\n}\n";
  return out;
}

}  // namespace c4d
