// VTK XML PolyData and PVD, written by hand (VTK is not a dependency). Layout per the VTK file
// format documentation ("VTK XML Formats": appended raw data, UInt64 block headers).
#include "contour4d/io/vtk_xml.h"

#include <cstdint>
#include <cstring>
#include <limits>
#include <string_view>

#include <fmt/format.h>

#include "raw_bytes_internal.h"

#include "contour4d/core/errors.h"

namespace c4d {
namespace {

[[noreturn]] void bad(const std::string& source, const std::string& what) {
  throw IoError(ErrorCode::BadMesh, Location{source}, what,
                "The file is not a VTK XML PolyData file as contour4d writes it; re-create it");
}

// Value of attribute `name` inside the tag that starts at `tag_begin` (up to the next '>').
std::string attribute(std::string_view text, std::size_t tag_begin, std::string_view name) {
  const std::size_t tag_end = text.find('>', tag_begin);
  const std::string_view tag =
      text.substr(tag_begin, tag_end == std::string_view::npos ? text.npos : tag_end - tag_begin);
  const std::string key = " " + std::string(name) + "=\"";
  const std::size_t k = tag.find(key);
  if (k == std::string_view::npos) return {};
  const std::size_t v = k + key.size();
  const std::size_t e = tag.find('"', v);
  if (e == std::string_view::npos) return {};
  return std::string(tag.substr(v, e - v));
}

std::uint64_t to_count(const std::string& s, const std::string& source, const char* what) {
  if (s.empty() || s.size() > 18 || s.find_first_not_of("0123456789") != std::string::npos)
    bad(source, std::string("missing or invalid ") + what);
  return std::stoull(s);
}

struct ArrayRef {
  std::string type;
  std::uint64_t offset = 0;
};

ArrayRef find_array(std::string_view text, std::string_view name, const std::string& source) {
  std::size_t pos = 0;
  while ((pos = text.find("<DataArray", pos)) != std::string_view::npos) {
    if (attribute(text, pos, "Name") == name) {
      if (attribute(text, pos, "format") != "appended")
        bad(source, "DataArray " + std::string(name) + " is not appended");
      return {attribute(text, pos, "type"), to_count(attribute(text, pos, "offset"), source, "offset")};
    }
    pos += 10;
  }
  bad(source, "no DataArray named " + std::string(name));
}

// Reads the appended block at `offset`: a UInt64 byte count then the bytes.
std::string_view block(std::string_view data, std::uint64_t offset, const std::string& source) {
  if (offset > data.size() || data.size() - offset < 8) bad(source, "appended data truncated");
  std::uint64_t n = 0;
  std::memcpy(&n, data.data() + offset, 8);
  if (n > data.size() - offset - 8) bad(source, "appended data truncated");
  return data.substr(offset + 8, n);
}

template <class T>
std::vector<T> decode(std::string_view bytes, const std::string& source, const char* what) {
  if (bytes.size() % sizeof(T) != 0) bad(source, std::string("bad byte count in ") + what);
  std::vector<T> v(bytes.size() / sizeof(T));
  if (!v.empty()) std::memcpy(v.data(), bytes.data(), bytes.size());
  return v;
}

}  // namespace

std::string format_vtp(const TriangleMesh& mesh) {
  const std::uint64_t np = mesh.positions.size(), nt = mesh.triangles.size();
  const std::uint64_t points_bytes = np * 3 * 8, conn_bytes = nt * 3 * 8, off_bytes = nt * 8;
  const std::uint64_t off_conn = 8 + points_bytes, off_offs = off_conn + 8 + conn_bytes;
  std::string out = fmt::format(
      "<?xml version=\"1.0\"?>\n"
      "<!-- contour4d mesh: coordinates in mm, patient space of the input (LPS for DICOM-derived data) -->\n"
      "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      "  <PolyData>\n"
      "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
      "NumberOfPolys=\"{}\">\n"
      "      <Points>\n"
      "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"appended\" "
      "offset=\"0\"/>\n"
      "      </Points>\n"
      "      <Polys>\n"
      "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\"{}\"/>\n"
      "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"appended\" offset=\"{}\"/>\n"
      "      </Polys>\n"
      "    </Piece>\n"
      "  </PolyData>\n"
      "  <AppendedData encoding=\"raw\">\n   _",
      np, nt, off_conn, off_offs);
  out.reserve(out.size() + 24 + points_bytes + conn_bytes + off_bytes + 40);
  append_raw(out, points_bytes);
  for (const Vec3& p : mesh.positions) {
    append_raw(out, p.x);
    append_raw(out, p.y);
    append_raw(out, p.z);
  }
  append_raw(out, conn_bytes);
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t i : t) append_raw(out, static_cast<std::int64_t>(i));
  append_raw(out, off_bytes);
  for (std::uint64_t i = 1; i <= nt; ++i) append_raw(out, static_cast<std::int64_t>(3 * i));
  out += "\n  </AppendedData>\n</VTKFile>\n";
  return out;
}

TriangleMesh parse_vtp(const std::string& content, const std::string& source) {
  const std::string_view text(content);
  if (text.find("<VTKFile") == std::string_view::npos || attribute(text, text.find("<VTKFile"), "type") != "PolyData")
    bad(source, "not a VTK XML PolyData file");
  const std::size_t vtk = text.find("<VTKFile");
  if (attribute(text, vtk, "header_type") != "UInt64") bad(source, "header_type must be UInt64");
  if (attribute(text, vtk, "byte_order") != "LittleEndian") bad(source, "byte_order must be LittleEndian");
  const std::size_t piece = text.find("<Piece");
  if (piece == std::string_view::npos) bad(source, "no <Piece>");
  const std::uint64_t np = to_count(attribute(text, piece, "NumberOfPoints"), source, "NumberOfPoints");
  const std::uint64_t nt = to_count(attribute(text, piece, "NumberOfPolys"), source, "NumberOfPolys");
  const std::size_t app = text.find("<AppendedData");
  if (app == std::string_view::npos) bad(source, "no <AppendedData>");
  const std::size_t underscore = text.find('_', text.find('>', app));
  if (underscore == std::string_view::npos) bad(source, "appended data marker '_' missing");
  const std::string_view data = text.substr(underscore + 1);
  const std::string_view header = text.substr(0, app);

  const ArrayRef pts = find_array(header, "Points", source);
  const ArrayRef conn = find_array(header, "connectivity", source);
  const ArrayRef offs = find_array(header, "offsets", source);
  if (pts.type != "Float64" || conn.type != "Int64" || offs.type != "Int64")
    bad(source, "expected Float64 points and Int64 connectivity/offsets");
  const auto p = decode<double>(block(data, pts.offset, source), source, "Points");
  const auto c = decode<std::int64_t>(block(data, conn.offset, source), source, "connectivity");
  const auto o = decode<std::int64_t>(block(data, offs.offset, source), source, "offsets");
  if (p.size() != 3 * np) bad(source, "Points has the wrong size for NumberOfPoints");
  if (o.size() != nt) bad(source, "offsets has the wrong size for NumberOfPolys");

  TriangleMesh mesh;
  mesh.positions.resize(np);
  for (std::uint64_t i = 0; i < np; ++i) mesh.positions[i] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
  std::int64_t start = 0;
  for (std::uint64_t i = 0; i < nt; ++i) {
    const std::int64_t end = o[i];
    if (end - start != 3) bad(source, fmt::format("polygon {} is not a triangle", i));
    if (end > static_cast<std::int64_t>(c.size())) bad(source, "connectivity truncated");
    Triangle t{};
    for (int k = 0; k < 3; ++k) {
      const std::int64_t v = c[static_cast<std::size_t>(start + k)];
      if (v < 0 || static_cast<std::uint64_t>(v) >= np)
        bad(source, fmt::format("polygon {} has vertex index {} out of range", i, v));
      t[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(v);
    }
    mesh.triangles.push_back(t);
    start = end;
  }
  return mesh;
}

std::string format_pvd(const std::vector<PvdEntry>& entries) {
  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<!-- contour4d 4D mesh: timestep in ms; coordinates in mm -->\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
  for (const PvdEntry& e : entries)
    out += fmt::format("    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", e.time_ms, e.file);
  out += "  </Collection>\n</VTKFile>\n";
  return out;
}

std::vector<PvdEntry> parse_pvd(const std::string& content, const std::string& source) {
  const std::string_view text(content);
  const std::size_t vtk = text.find("<VTKFile");
  if (vtk == std::string_view::npos || attribute(text, vtk, "type") != "Collection")
    throw IoError(ErrorCode::BadMesh, Location{source}, "not a ParaView .pvd collection");
  std::vector<PvdEntry> entries;
  std::size_t pos = 0;
  while ((pos = text.find("<DataSet", pos)) != std::string_view::npos) {
    PvdEntry e;
    e.file = attribute(text, pos, "file");
    const std::string ts = attribute(text, pos, "timestep");
    try {
      std::size_t used = 0;
      e.time_ms = ts.empty() ? 0.0 : std::stod(ts, &used);
      if (used != ts.size()) throw std::invalid_argument(ts);
    } catch (const std::exception&) {
      throw IoError(ErrorCode::BadMesh, Location{source},
                    "DataSet " + std::to_string(entries.size()) + " has an invalid timestep");
    }
    if (e.file.empty())
      throw IoError(ErrorCode::BadMesh, Location{source}, "DataSet " + std::to_string(entries.size()) + " has no file");
    entries.push_back(e);
    pos += 8;
  }
  if (entries.empty()) throw IoError(ErrorCode::BadMesh, Location{source}, "the collection lists no DataSet");
  return entries;
}

}  // namespace c4d
