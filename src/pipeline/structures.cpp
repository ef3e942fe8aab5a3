// Every structure in one run (structures.h): the input split per label, and the myocardial wall as the
// region between the endocardium and the epicardium of each slice (issue 44, "every structure of a heart").
#include "contour4d/pipeline/structures.h"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "contour4d/connect/similarity.h"
#include "contour4d/core/errors.h"
#include "contour4d/core/plane.h"

namespace c4d {
namespace {

std::vector<Vec2> in_plane(const Plane& plane, const std::vector<Vec3>& points) {
  std::vector<Vec2> out;
  for (const Vec3& p : points) out.push_back(to_plane(plane, p));
  return out;
}

bool inside(const std::vector<Vec2>& inner, const std::vector<Vec2>& outer) {
  return std::all_of(inner.begin(), inner.end(), [&](Vec2 p) { return point_in_polygon(p, outer); });
}

// One slice of the wall: outer contours, and inner ones inside them; empty when an inner one crosses.
std::vector<Contour> wall_slice(const Sequence& seq, const Slice& s, const std::string& inner, const std::string& outer,
                                const std::string& name, int frame, std::vector<std::string>& notes) {
  const Plane plane = slice_plane(seq, s);
  std::vector<Contour> outers, inners;
  for (const Contour& c : s.contours) {
    if (c.label == outer) outers.push_back(c);
    if (c.label == inner) inners.push_back(c);
  }
  if (outers.empty()) {
    if (!inners.empty())
      notes.push_back(fmt::format("{}: frame {}, slice {}: {} without {}, left out", name, frame, s.id, inner, outer));
    return {};
  }
  std::vector<std::vector<Vec2>> outer_2d;
  for (const Contour& c : outers) outer_2d.push_back(in_plane(plane, c.points));
  for (const Contour& c : inners) {
    const std::vector<Vec2> p = in_plane(plane, c.points);
    if (std::none_of(outer_2d.begin(), outer_2d.end(), [&](const std::vector<Vec2>& o) { return inside(p, o); })) {
      notes.push_back(fmt::format("{}: frame {}, slice {}: {} is not inside {} (drawn across it), slice left out", name,
                                  frame, s.id, inner, outer));
      return {};
    }
  }
  std::vector<Contour> out = outers;
  out.insert(out.end(), inners.begin(), inners.end());
  for (Contour& c : out) c.label = name;
  return out;
}

// `seq` with only the frames that hold a contour; `kept` gets their input indices.
Sequence drop_empty_frames(Sequence seq, std::vector<int>& kept) {
  std::vector<Frame> frames;
  for (std::size_t f = 0; f < seq.frames.size(); ++f) {
    auto& slices = seq.frames[f].slices;
    slices.erase(std::remove_if(slices.begin(), slices.end(), [](const Slice& s) { return s.contours.empty(); }),
                 slices.end());
    if (slices.empty()) continue;
    kept.push_back(static_cast<int>(f));
    frames.push_back(std::move(seq.frames[f]));
  }
  seq.frames = std::move(frames);
  return seq;
}

Sequence only_label(Sequence seq, const std::string& label) {
  for (Frame& f : seq.frames)
    for (Slice& s : f.slices)
      s.contours.erase(
          std::remove_if(s.contours.begin(), s.contours.end(), [&](const Contour& c) { return c.label != label; }),
          s.contours.end());
  return seq;
}

Structure make_structure(const InputResult& read, const std::string& name) {
  Structure st;
  st.name = name;
  st.wall = name == kLvWall;
  st.input.format = read.format;
  st.input.timing = read.timing;
  st.input.repairs = read.repairs;
  Sequence seq =
      st.wall ? wall_sequence(read.sequence, kLvEndo, kLvEpi, name, st.input.notes) : only_label(read.sequence, name);
  st.input.sequence = drop_empty_frames(std::move(seq), st.frames);
  if (st.frames.empty())
    throw InvalidInput(ErrorCode::UnknownLabel, Location{read.sequence.source}, "no contour of structure " + name,
                       "the labels present: " + fmt::format("{}", fmt::join(labels(read.sequence), ", ")));
  if (st.frames.size() < read.sequence.frames.size())
    st.input.notes.push_back(fmt::format("{}: {} of {} frames hold its contours; the others are left out", name,
                                         st.frames.size(), read.sequence.frames.size()));
  return st;
}

}  // namespace

Sequence wall_sequence(const Sequence& seq, const std::string& inner, const std::string& outer, const std::string& name,
                       std::vector<std::string>& notes) {
  Sequence out = seq;
  for (std::size_t f = 0; f < out.frames.size(); ++f)
    for (std::size_t k = 0; k < out.frames[f].slices.size(); ++k)
      out.frames[f].slices[k].contours =
          wall_slice(seq, seq.frames[f].slices[k], inner, outer, name, static_cast<int>(f), notes);
  return out;
}

std::vector<Structure> split_structures(const InputResult& read, const std::vector<std::string>& asked) {
  std::vector<std::string> names = asked;
  if (asked.size() == 1 && asked[0] == "all") {
    names = labels(read.sequence);
    const bool endo = std::count(names.begin(), names.end(), kLvEndo) > 0;
    const bool epi = std::count(names.begin(), names.end(), kLvEpi) > 0;
    if (endo && epi) names.push_back(kLvWall);
  }
  std::vector<Structure> out;
  for (const std::string& n : names) out.push_back(make_structure(read, n));
  return out;
}

}  // namespace c4d
