// Reader of biv-me / Cardiac Atlas guide-point folders ("GPFile"). The format has no written spec;
// what is accepted follows biv-me's own files (UOA Heart Mechanics Research, biv-me, example
// guidepoints): a tab-separated table per frame whose fifth column names the slice ("frameID" in
// older files, "sliceID" in newer), and SliceInfoFile.txt giving each slice's DICOM plane. Column 7
// (time frame) is unreliable, so the frame is the file's position in file-number order.
#include "contour4d/io/gpfile.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

#include "contour4d/core/errors.h"
#include "contour4d/io/output_dir.h"

namespace c4d {

namespace {

namespace fs = std::filesystem;

constexpr long long kMaxSliceId = 1000000;
constexpr std::size_t kMaxFrames = 100000;
constexpr const char* kGpHint =
    "a GPFile line is: x<TAB>y<TAB>z<TAB>contour type<TAB>slice id[<TAB>weight<TAB>time frame] (see docs/formats.md)";
constexpr const char* kInfoHint =
    "a SliceInfoFile.txt line is: <dicom name><TAB>sliceID: <TAB><id><TAB>ImagePositionPatient<TAB>x<TAB>y<TAB>z"
    "<TAB>ImageOrientationPatient<TAB>6 numbers<TAB>PixelSpacing<TAB>2 numbers";

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> out;
  if (line.find('\t') != std::string_view::npos) {
    std::size_t start = 0;
    while (true) {
      const std::size_t tab = line.find('\t', start);
      out.push_back(line.substr(start, tab == std::string_view::npos ? std::string_view::npos : tab - start));
      if (tab == std::string_view::npos) break;
      start = tab + 1;
    }
  } else {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ')) ++i;
      const std::size_t j = std::min(line.find(' ', i), line.size());
      if (j > i) out.push_back(line.substr(i, j - i));
      i = j;
    }
  }
  for (std::string_view& f : out) {
    while (!f.empty() && (f.front() == ' ' || f.front() == '\r')) f.remove_prefix(1);
    while (!f.empty() && (f.back() == ' ' || f.back() == '\r')) f.remove_suffix(1);
  }
  return out;
}

//! Lines of a text with their 1-based numbers; '\r' is stripped by split_fields.
template <class F>
void for_each_line(const std::string& text, F&& f) {
  std::size_t start = 0;
  int line = 1;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    f(std::string_view(text).substr(start, end - start), line);
    start = end + 1;
    ++line;
  }
}

enum class NumberStatus { Ok, NotANumber, NonFinite };

NumberStatus parse_double(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  if (ec == std::errc::result_out_of_range) {
    // from_chars leaves `out` unset: overflow is infinite, underflow (tiny) is fine.
    if (end != s.data() + s.size()) return NumberStatus::NotANumber;
    out = std::strtod(std::string(s).c_str(), nullptr);
    return std::isfinite(out) ? NumberStatus::Ok : NumberStatus::NonFinite;
  }
  if (ec != std::errc() || end != s.data() + s.size() || s.empty()) return NumberStatus::NotANumber;
  return std::isfinite(out) ? NumberStatus::Ok : NumberStatus::NonFinite;
}

bool parse_id(std::string_view s, int& out) {
  long long v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty() || v < 0 || v > kMaxSliceId) return false;
  out = static_cast<int>(v);
  return true;
}

std::string show(std::string_view s) {
  std::string out;
  for (char c : s.substr(0, 40))
    out += (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) ? '?' : c;
  return "\"" + out + (s.size() > 40 ? "...\"" : "\"");
}

[[noreturn]] void parse_fail(ErrorCode code, const std::string& file, int line, const std::string& what,
                             const std::string& hint) {
  Location where;
  where.file = file;
  where.line = line;
  if (code == ErrorCode::NonFinite) throw InvalidInput(code, where, what, hint);
  throw IoError(code, where, what, hint);
}

std::map<int, GpFileSlice> parse_slice_info(const std::string& text, const std::string& file) {
  std::map<int, GpFileSlice> slices;
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    parse_fail(ErrorCode::EmptyFile, file, -1, "SliceInfoFile.txt is empty", kInfoHint);
  for_each_line(text, [&](std::string_view line, int n) {
    const std::vector<std::string_view> f = split_fields(line);
    if (f.empty() || (f.size() == 1 && f[0].empty())) return;
    auto key = [&](std::string_view k) -> std::size_t {
      for (std::size_t i = 0; i < f.size(); ++i)
        if (f[i] == k) return i;
      return f.size();
    };
    auto numbers = [&](std::string_view k, std::size_t count, double* out) {
      const std::size_t at = key(k);
      if (at + count >= f.size())
        parse_fail(ErrorCode::Parse, file, n, std::string(k) + " with " + std::to_string(count) + " numbers not found",
                   kInfoHint);
      for (std::size_t i = 0; i < count; ++i) {
        const NumberStatus st = parse_double(f[at + 1 + i], out[i]);
        if (st == NumberStatus::NonFinite)
          parse_fail(ErrorCode::NonFinite, file, n, std::string(k) + " has a non-finite value", kInfoHint);
        if (st != NumberStatus::Ok)
          parse_fail(ErrorCode::Parse, file, n, std::string(k) + " value " + show(f[at + 1 + i]) + " is not a number",
                     kInfoHint);
      }
    };
    GpFileSlice s;
    const std::size_t id_at = std::min(key("sliceID:"), key("sliceID"));
    if (id_at + 1 >= f.size() || !parse_id(f[id_at + 1], s.id))
      parse_fail(ErrorCode::Parse, file, n,
                 "no valid \"sliceID:\" field (an integer 0.." + std::to_string(kMaxSliceId) + ")", kInfoHint);
    s.image = std::string(f[0]);
    double ipp[3], iop[6];
    numbers("ImagePositionPatient", 3, ipp);
    numbers("ImageOrientationPatient", 6, iop);
    s.position = {ipp[0], ipp[1], ipp[2]};
    s.row = {iop[0], iop[1], iop[2]};
    s.column = {iop[3], iop[4], iop[5]};
    const Vec3 nrm = cross(s.row, s.column);
    if (!(norm(nrm) > 0.5))
      parse_fail(ErrorCode::Parse, file, n, "ImageOrientationPatient directions are not two orthogonal unit vectors",
                 kInfoHint);
    s.normal = normalized(nrm);
    if (key("PixelSpacing") + 2 < f.size()) {
      double ps[2];
      numbers("PixelSpacing", 2, ps);
      if (ps[0] > 0.0 && ps[1] > 0.0) s.pixel_mm = 0.5 * (ps[0] + ps[1]);
    }
    if (slices.count(s.id))
      parse_fail(ErrorCode::Parse, file, n, "slice id " + std::to_string(s.id) + " is listed twice", kInfoHint);
    slices[s.id] = s;
  });
  return slices;
}

//! One guide point as read.
struct GuidePoint {
  Vec3 p;
  std::string type;
  int slice = 0;
  int line = 0;
};

std::vector<GuidePoint> parse_frame(const std::string& text, const std::string& file) {
  std::vector<GuidePoint> pts;
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    parse_fail(ErrorCode::EmptyFile, file, -1, "GPFile is empty", kGpHint);
  bool first = true;
  for_each_line(text, [&](std::string_view line, int n) {
    const std::vector<std::string_view> f = split_fields(line);
    if (f.empty() || (f.size() == 1 && f[0].empty())) return;
    double x = 0;
    if (first) {
      first = false;
      if (parse_double(f[0], x) == NumberStatus::NotANumber) {
        // Header: "x y z contour type frameID|sliceID weight time frame"; columns are taken by position.
        if (f.size() < 5)
          parse_fail(ErrorCode::Parse, file, n,
                     "header has " + std::to_string(f.size()) + " columns, expected at least 5", kGpHint);
        return;
      }
    }
    if (f.size() < 5)
      parse_fail(ErrorCode::Parse, file, n, "line has " + std::to_string(f.size()) + " columns, expected at least 5",
                 kGpHint);
    GuidePoint g;
    g.line = n;
    for (int k = 0; k < 3; ++k) {
      const NumberStatus st = parse_double(f[k], g.p[k]);
      if (st == NumberStatus::NonFinite)
        parse_fail(ErrorCode::NonFinite, file, n,
                   std::string("coordinate ") + "xyz"[k] + " is not finite (" + show(f[k]) + ")",
                   "coordinates must be finite numbers (mm)");
      if (st != NumberStatus::Ok)
        parse_fail(ErrorCode::Parse, file, n,
                   std::string("coordinate ") + "xyz"[k] + " " + show(f[k]) + " is not a number", kGpHint);
    }
    if (f[3].empty()) parse_fail(ErrorCode::Parse, file, n, "empty contour type", kGpHint);
    g.type = std::string(f[3]);
    if (!parse_id(f[4], g.slice))
      parse_fail(ErrorCode::Parse, file, n,
                 "slice id " + show(f[4]) + " is not an integer 0.." + std::to_string(kMaxSliceId), kGpHint);
    pts.push_back(std::move(g));
  });
  return pts;
}

std::string join_ids(const std::vector<int>& ids) {
  std::string s;
  for (int id : ids) s += (s.empty() ? "" : ", ") + std::to_string(id);
  return s.empty() ? "none" : s;
}

//! The error `e` again, placed in a GPFile (file, line) instead of the folder.
[[noreturn]] void relocate(const Error& e, const std::string& file, int line) {
  std::string msg = e.what();
  const std::string prefix = e.where().format() + ": ";
  if (msg.rfind(prefix, 0) == 0) msg = msg.substr(prefix.size());
  const std::string suffix = e.hint().empty() ? std::string() : ". " + e.hint();
  if (!suffix.empty() && msg.size() >= suffix.size() &&
      msg.compare(msg.size() - suffix.size(), suffix.size(), suffix) == 0)
    msg.resize(msg.size() - suffix.size());
  Location where = e.where();
  where.file = file;
  where.line = line > 0 ? line : -1;
  throw InvalidInput(e.code(), where, msg, e.hint());
}

// The file name of frame f: its given name, else GPFile_<f>.txt in the folder.
std::string frame_file_name(const std::vector<std::string>& frame_names, const std::string& source, std::size_t f) {
  if (f < frame_names.size()) return frame_names[f];
  char buf[32];
  std::snprintf(buf, sizeof buf, "GPFile_%03zu.txt", f);
  return source + "/" + buf;
}

//! The guide points of all frames that are kept, with what was seen.
struct FramePoints {
  std::vector<std::vector<GuidePoint>> points;  // per frame: wanted types and the septum
  std::set<std::string> present_types;          // every contour type seen
  std::map<int, int> count_by_slice;            // wanted points per slice, all frames
  std::vector<GuideCurve> long_axis;            // every LAX_* contour, one per (frame, slice, type)
};

// A long-axis point goes to its frame's curve of the same slice and type (points in file order).
void add_long_axis_point(const GuidePoint& g, std::size_t frame,
                         std::map<std::pair<int, std::string>, std::size_t>& index, std::vector<GuideCurve>& curves) {
  const auto [it, added] = index.try_emplace({g.slice, g.type}, curves.size());
  if (added) curves.push_back({static_cast<int>(frame), g.slice, gpfile_label(g.type), {}});
  curves[it->second].points.push_back(g.p);
}

// Reads every frame; keeps the wanted types (and the septum, to close the epicardium). Throws on a
// kept point whose slice is not in SliceInfoFile.txt.
FramePoints read_frames(const std::vector<std::string>& frames, const std::vector<std::string>& files,
                        const std::map<int, GpFileSlice>& info, const std::set<std::string>& wanted) {
  const bool want_epi = wanted.count("SAX_LV_EPICARDIAL") > 0;
  FramePoints fp;
  fp.points.resize(frames.size());
  for (std::size_t f = 0; f < frames.size(); ++f) {
    std::map<std::pair<int, std::string>, std::size_t> long_axis_index;
    for (GuidePoint& g : parse_frame(frames[f], files[f])) {
      fp.present_types.insert(g.type);
      if (g.type.rfind("LAX_", 0) == 0) add_long_axis_point(g, f, long_axis_index, fp.long_axis);
      const bool keep = wanted.count(g.type) || (want_epi && g.type == "SAX_RV_SEPTUM");
      if (!keep) continue;
      if (!info.count(g.slice))
        parse_fail(ErrorCode::Format, files[f], g.line,
                   "slice id " + std::to_string(g.slice) + " is not in SliceInfoFile.txt",
                   "the fifth column must be a slice id listed in SliceInfoFile.txt");
      if (wanted.count(g.type)) ++fp.count_by_slice[g.slice];
      fp.points[f].push_back(std::move(g));
    }
  }
  return fp;
}

// Throws when one of the chosen contour types has no point in any frame.
void check_types_present(const std::vector<std::string>& types, const std::set<std::string>& present_types,
                         const Location& folder) {
  for (const std::string& t : types) {
    if (!present_types.count(t)) {
      std::string list;
      for (const std::string& p : present_types) list += (list.empty() ? "" : ", ") + p;
      throw InvalidInput(ErrorCode::UnknownLabel, folder, "no point has the contour type " + t,
                         "contour types present: " + (list.empty() ? std::string("none") : list));
    }
  }
}

// Short-axis reference: the slice carrying wanted points whose plane is parallel to the most such
// slices (ties: the smallest id); -1 when there is none.
int reference_slice(const std::map<int, GpFileSlice>& info, const std::map<int, int>& count_by_slice, double cos_tol) {
  int best_ref = -1;
  std::size_t best_size = 0;
  for (const auto& [id, n] : count_by_slice) {
    std::size_t size = 0;
    for (const auto& [id2, n2] : count_by_slice)
      if (std::abs(dot(info.at(id).normal, info.at(id2).normal)) >= cos_tol) ++size;
    if (size > best_size) {
      best_size = size;
      best_ref = id;
    }
  }
  return best_ref;
}

// Lists every slice in result.slices, used (parallel to the reference) or with a note why not, and
// fills result.slices_used and slices_skipped; returns the used ids.
std::set<int> choose_slices(const std::map<int, GpFileSlice>& info, const std::map<int, int>& count_by_slice,
                            int best_ref, double cos_tol, GpFileResult& result) {
  std::set<int> used;
  for (auto [id, s] : info) {
    if (!count_by_slice.count(id)) {
      s.note = "no points of the chosen contour types";
    } else {
      const double c = std::min(1.0, std::abs(dot(s.normal, info.at(best_ref).normal)));
      if (c >= cos_tol) {
        s.used = true;
        used.insert(id);
        result.slices_used.push_back(id);
      } else {
        std::ostringstream os;
        os.precision(3);
        os << "image plane " << std::acos(c) * 180.0 / std::numbers::pi << " degrees from the short-axis planes "
           << "(long-axis view)";
        s.note = os.str();
        result.slices_skipped.push_back(id);
      }
    }
    result.slices.push_back(s);
  }
  return used;
}

constexpr const char* kRvFreeWall = "SAX_RV_FREEWALL";
constexpr const char* kRvSeptum = "SAX_RV_SEPTUM";
constexpr const char* kRvEndoLabel = "rv-endo";

//! How the contours were closed, for the notes.
struct ClosingStats {
  int closed_epi = 0, straight_epi = 0;
  int joined_rv = 0;                      // free wall + septum joined into one RV endocardium
  std::map<std::string, int> open_types;  // type -> contours with a closing gap
};

// Appends the septum's points to the open arc c, in the direction that joins the open ends with the shorter
// gaps. Septum ends may overshoot the arc's open ends; points that lead away from the end they join are
// dropped, or the joint folds over itself.
void append_septum(std::vector<Vec3>& c, const std::vector<const GuidePoint*>& septum) {
  const Vec3 s0 = septum.front()->p, s1 = septum.back()->p;
  const bool reverse =
      distance(c.back(), s1) + distance(s0, c.front()) < distance(c.back(), s0) + distance(s1, c.front());
  std::vector<Vec3> s;
  for (const GuidePoint* g : septum) s.push_back(g->p);
  if (reverse) std::reverse(s.begin(), s.end());
  std::size_t b = 0, e = s.size();
  while (e - b > 1 && distance(s[b + 1], c.back()) < distance(s[b], c.back())) ++b;
  while (e - b > 1 && distance(s[e - 2], c.front()) < distance(s[e - 1], c.front())) --e;
  c.insert(c.end(), s.begin() + static_cast<std::ptrdiff_t>(b), s.begin() + static_cast<std::ptrdiff_t>(e));
}

// biv-me's open arcs (the epicardium without its septal part, the RV free wall) are stored as loops whose
// opening, the largest gap, is not necessarily between the last and first points: rotates it to the ends of c.
// Returns true when the opening is wider than 4 × the median point spacing (the arc is open).
bool rotate_opening_to_ends(std::vector<Vec3>& c) {
  std::vector<double> gaps;
  std::size_t widest = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    gaps.push_back(distance(c[i], c[(i + 1) % c.size()]));
    if (gaps[i] > gaps[widest]) widest = i;
  }
  const double gap = gaps[widest];
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  std::rotate(c.begin(), c.begin() + static_cast<std::ptrdiff_t>((widest + 1) % c.size()), c.end());
  return gap > 4.0 * gaps[gaps.size() / 2];
}

// The epicardium's opening closed with the septum points where there are some (`septum` null: none).
void close_epicardium(std::vector<Vec3>& c, const std::vector<const GuidePoint*>* septum, ClosingStats& stats) {
  if (!rotate_opening_to_ends(c)) {
    // already closed
  } else if (septum != nullptr && !septum->empty()) {
    // The septal wall's RV side completes the LV epicardium (as biv-me fits it).
    append_septum(c, *septum);
    ++stats.closed_epi;
  } else {
    ++stats.straight_epi;
  }
}

// Counts contour c (at least 3 points) of `type` as open when its closing gap exceeds 4x the
// median point spacing.
void note_open_contour(const std::vector<Vec3>& c, const std::string& type, ClosingStats& stats) {
  std::vector<double> gaps;
  for (std::size_t i = 0; i + 1 < c.size(); ++i) gaps.push_back(distance(c[i], c[i + 1]));
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  if (distance(c.back(), c.front()) > 4.0 * gaps[gaps.size() / 2] + 1e-9) ++stats.open_types[type];
}

// Appends frame f's contours to raw, one per (slice, type) on the used slices, points in file order;
// returns false when the frame has none.
bool frame_contours(const std::vector<GuidePoint>& points, std::size_t f, const std::set<int>& used,
                    const std::set<std::string>& wanted, std::vector<RawContour>& raw, ClosingStats& stats) {
  std::map<std::pair<int, std::string>, std::vector<const GuidePoint*>> groups;
  for (const GuidePoint& g : points)
    if (used.count(g.slice)) groups[{g.slice, g.type}].push_back(&g);
  int index = 0;
  bool any = false;
  const bool join_rv = wanted.count(kRvFreeWall) && wanted.count(kRvSeptum);
  for (const auto& [key, pts] : groups) {
    if (!wanted.count(key.second)) continue;  // the septum only closes the epicardium
    // The RV endocardium is the free wall and the septum's RV side joined: the septum goes in with the free
    // wall on slices that have both.
    if (join_rv && key.second == kRvSeptum && groups.count({key.first, kRvFreeWall})) continue;
    any = true;
    RawContour rc;
    rc.frame = static_cast<int>(f);
    rc.index = index++;
    rc.line = pts.front()->line;
    rc.contour.slice = key.first;
    rc.contour.label = gpfile_label(key.second);
    for (const GuidePoint* g : pts) rc.contour.points.push_back(g->p);
    std::vector<Vec3>& c = rc.contour.points;
    if (join_rv && (key.second == kRvFreeWall || key.second == kRvSeptum)) {
      rc.contour.label = kRvEndoLabel;
      const auto sep = groups.find({key.first, kRvSeptum});
      if (key.second == kRvFreeWall && sep != groups.end() && !sep->second.empty() && c.size() >= 3) {
        rotate_opening_to_ends(c);
        append_septum(c, sep->second);
        ++stats.joined_rv;
      }
    } else if (key.second == "SAX_LV_EPICARDIAL" && c.size() >= 3) {
      const auto sep = groups.find({key.first, "SAX_RV_SEPTUM"});
      close_epicardium(c, sep != groups.end() ? &sep->second : nullptr, stats);
    } else if (c.size() >= 3) {
      note_open_contour(c, key.second, stats);
    }
    raw.push_back(std::move(rc));
  }
  return any;
}

// Throws for a frame without any contour of the chosen types on the short-axis slices.
[[noreturn]] void throw_empty_frame(const std::string& file, std::size_t f, const std::vector<std::string>& types,
                                    const std::vector<int>& slices_used) {
  Location where;
  where.file = file;
  where.frame = static_cast<int>(f);
  std::string t;
  for (const std::string& x : types) t += (t.empty() ? "" : ", ") + x;
  throw InvalidInput(ErrorCode::EmptyFrame, where,
                     "no " + t + " points on the short-axis slices (" + join_ids(slices_used) + ")",
                     "every frame needs at least one contour; choose other contour types with --type");
}

// build_sequence over the contours; an error in a frame is placed at its GPFile (and line).
Sequence build_in_files(const std::vector<RawContour>& raw, const std::vector<std::string>& files,
                        const std::string& source, const StackOptions& stack) {
  try {
    return build_sequence(raw, static_cast<int>(files.size()), {}, source, stack);
  } catch (const Error& e) {
    const int f = e.where().frame;
    if (f < 0 || static_cast<std::size_t>(f) >= files.size()) throw;
    int line = -1;
    if (e.where().contour >= 0)
      for (const RawContour& rc : raw)
        if (rc.frame == f && rc.index == e.where().contour) line = rc.line;
    relocate(e, files[static_cast<std::size_t>(f)], line);
  }
}

// The notes on what was read, chosen and closed.
void add_notes(GpFileResult& result, const std::vector<std::string>& types, const std::map<int, int>& count_by_slice,
               const ClosingStats& stats, std::size_t frame_count) {
  std::string t;
  for (const std::string& x : types) t += (t.empty() ? "" : ", ") + x + " -> \"" + gpfile_label(x) + "\"";
  result.notes.push_back("contour types: " + t);
  result.notes.push_back("slices used (short-axis): " + join_ids(result.slices_used));
  if (!result.slices_skipped.empty()) {
    std::string s;
    for (const GpFileSlice& sl : result.slices)
      if (!sl.used && count_by_slice.count(sl.id))
        s += (s.empty() ? "" : "; ") + std::to_string(sl.id) + ": " + sl.note;
    result.notes.push_back("slices skipped: " + s);
  }
  std::vector<int> empty_ids;
  for (const GpFileSlice& sl : result.slices)
    if (!count_by_slice.count(sl.id)) empty_ids.push_back(sl.id);
  if (!empty_ids.empty()) result.notes.push_back("slices without the chosen contour types: " + join_ids(empty_ids));
  result.notes.push_back("frames: " + std::to_string(frame_count) +
                         " files in file-number order; time = frame index x 1 ms "
                         "(column 7 of the GPFiles is not used)");
  if (stats.closed_epi)
    result.notes.push_back("SAX_LV_EPICARDIAL closed with the SAX_RV_SEPTUM points in " +
                           std::to_string(stats.closed_epi) + " contours");
  if (stats.straight_epi)
    result.notes.push_back("SAX_LV_EPICARDIAL is open and had no SAX_RV_SEPTUM points in " +
                           std::to_string(stats.straight_epi) +
                           " contours: closed with a straight edge (septum shape lost there)");
  if (stats.joined_rv)
    result.notes.push_back("SAX_RV_FREEWALL and SAX_RV_SEPTUM joined into \"" + std::string(kRvEndoLabel) + "\" in " +
                           std::to_string(stats.joined_rv) + " contours");
  for (const auto& [type, n] : stats.open_types)
    result.notes.push_back(type + " looks open in " + std::to_string(n) +
                           " contours (closing gap > 4x the median point spacing): closed with a straight edge");
}

}  // namespace

std::string gpfile_label(const std::string& contour_type) {
  std::string s;
  for (char c : contour_type) s += c == '_' ? '-' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (s.rfind("sax-", 0) == 0) s = s.substr(4);
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"endocardial", "endo"}, {"epicardial", "epi"}}) {
    const std::size_t at = s.find(from);
    if (at != std::string::npos) s.replace(at, from.size(), to);
  }
  return s;
}

GpFileResult parse_gpfile_texts(const std::vector<std::string>& frames, const std::string& slice_info,
                                const std::string& source, const GpFileOptions& options,
                                const std::vector<std::string>& frame_names) {
  GpFileResult result;
  Location folder;
  folder.file = source;
  if (frames.empty()) throw IoError(ErrorCode::FileNotFound, folder, "no GPFile_*.txt frames", kGpHint);
  if (frames.size() > kMaxFrames)
    throw IoError(ErrorCode::Format, folder, "more than " + std::to_string(kMaxFrames) + " frames", kGpHint);
  for (std::size_t f = 0; f < frames.size(); ++f) result.frame_files.push_back(frame_file_name(frame_names, source, f));
  const std::vector<std::string>& files = result.frame_files;

  const std::map<int, GpFileSlice> info = parse_slice_info(slice_info, source + "/SliceInfoFile.txt");
  std::vector<std::string> types = options.contour_types;
  if (types.empty()) types = {"SAX_LV_ENDOCARDIAL"};
  const std::set<std::string> wanted(types.begin(), types.end());
  FramePoints fp = read_frames(frames, files, info, wanted);
  check_types_present(types, fp.present_types, folder);

  // Short-axis selection: the largest group of mutually parallel image planes among the slices
  // carrying wanted points (ties: the group of the smallest id).
  const double cos_tol = std::cos(options.parallel_tolerance_deg * std::numbers::pi / 180.0);
  const int best_ref = reference_slice(info, fp.count_by_slice, cos_tol);
  const std::set<int> used = choose_slices(info, fp.count_by_slice, best_ref, cos_tol, result);

  // One contour per (slice, type) per frame, points in file order.
  std::vector<RawContour> raw;
  ClosingStats stats;
  for (std::size_t f = 0; f < frames.size(); ++f)
    if (!frame_contours(fp.points[f], f, used, wanted, raw, stats))
      throw_empty_frame(files[f], f, types, result.slices_used);

  if (options.repair) result.repairs = repair_contours(raw);
  result.sequence = build_in_files(raw, files, source, options.stack);
  result.sequence.space = "LPS";
  add_notes(result, types, fp.count_by_slice, stats, frames.size());
  result.long_axis = std::move(fp.long_axis);
  return result;
}

GpFileResult read_gpfile(const fs::path& folder, const GpFileOptions& options) {
  Location where;
  where.file = folder.string();
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw IoError(ErrorCode::FileNotFound, where, "not a folder", "give the folder holding GPFile_*.txt");
  std::vector<std::pair<long long, fs::path>> files;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("GPFile_", 0) != 0 || name.size() < 12 || name.compare(name.size() - 4, 4, ".txt") != 0) continue;
    const std::string digits = name.substr(7, name.size() - 11);
    long long n = 0;
    const auto [end, err] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
    if (err != std::errc() || end != digits.data() + digits.size()) continue;
    files.emplace_back(n, entry.path());
  }
  if (ec) throw IoError(ErrorCode::FileNotFound, where, "cannot list the folder: " + ec.message());
  if (files.empty())
    throw IoError(ErrorCode::FileNotFound, where, "no GPFile_*.txt files in the folder",
                  "give a biv-me guide-point folder (GPFile_000.txt, ..., SliceInfoFile.txt)");
  std::sort(files.begin(), files.end());
  const fs::path info = folder / "SliceInfoFile.txt";
  if (!fs::exists(info, ec))
    throw IoError(ErrorCode::MissingCompanion, where, "SliceInfoFile.txt is missing beside the GPFiles",
                  "a GPFile folder needs " + info.string() + " (slice planes); copy it from the biv-me export");
  std::vector<std::string> texts, names;
  for (const auto& [n, p] : files) {
    texts.push_back(read_file(p));
    names.push_back(p.string());
  }
  GpFileResult r = parse_gpfile_texts(texts, read_file(info), folder.string(), options, names);
  bool contiguous = true;
  for (std::size_t i = 0; i < files.size(); ++i) contiguous = contiguous && files[i].first == static_cast<long long>(i);
  if (!contiguous)
    r.notes.push_back("GPFile numbers are not 0.." + std::to_string(files.size() - 1) +
                      ": frames are the files in number order");
  return r;
}

}  // namespace c4d
