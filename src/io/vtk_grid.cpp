// VTK XML files with data arrays, by hand (VTK is not a dependency), per the VTK file format documentation
// ("VTK XML Formats": appended raw data, each block a UInt64 byte count then the bytes).
#include "contour4d/io/vtk_grid.h"

#include <cstring>

#include <fmt/format.h>

#include "raw_bytes_internal.h"

namespace c4d {
namespace {

// Collects the appended blocks and the DataArray tags that point into them.
struct Appended {
  std::string bytes;
  std::uint64_t offset() const { return bytes.size(); }

  std::string array(const std::string& type, const std::string& name, int components, const std::string& indent) {
    return fmt::format(
        "{}<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" offset=\"{}\"/>\n", indent,
        type, name, components, offset());
  }
  std::string points(const std::vector<Vec3>& p, const std::string& indent) {
    const std::string tag = array("Float64", "Points", 3, indent);
    append_raw(bytes, static_cast<std::uint64_t>(p.size() * 24));
    for (const Vec3& v : p) {
      append_raw(bytes, v.x);
      append_raw(bytes, v.y);
      append_raw(bytes, v.z);
    }
    return tag;
  }
  template <class T, class List>
  std::string int64s(const std::string& name, const List& values, const std::string& indent) {
    const std::string tag = array("Int64", name, 1, indent);
    append_raw(bytes, static_cast<std::uint64_t>(values.size() * 8));
    for (const auto& v : values) append_raw(bytes, static_cast<std::int64_t>(static_cast<T>(v)));
    return tag;
  }
  std::string data(const VtkArray& a, const std::string& indent) {
    if (!a.ints.empty()) {
      const std::string tag = array("Int32", a.name, 1, indent);
      append_raw(bytes, static_cast<std::uint64_t>(a.ints.size() * 4));
      for (std::int32_t v : a.ints) append_raw(bytes, v);
      return tag;
    }
    const std::string tag = array("Float64", a.name, a.components, indent);
    append_raw(bytes, static_cast<std::uint64_t>(a.doubles.size() * 8));
    for (double v : a.doubles) append_raw(bytes, v);
    return tag;
  }
  std::string section(const char* tag, const std::vector<VtkArray>& arrays) {
    if (arrays.empty()) return {};
    std::string s = fmt::format("      <{}>\n", tag);
    for (const VtkArray& a : arrays) s += data(a, "        ");
    return s + fmt::format("      </{}>\n", tag);
  }
};

std::string header(const char* type, const std::string& comment) {
  std::string s = "<?xml version=\"1.0\"?>\n";
  if (!comment.empty()) s += "<!-- " + comment + " -->\n";
  return s + fmt::format("<VTKFile type=\"{}\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n",
                         type);
}

std::string footer(const char* type, const Appended& a) {
  std::string s = fmt::format("    </Piece>\n  </{}>\n  <AppendedData encoding=\"raw\">\n   _", type);
  s += a.bytes;
  return s + "\n  </AppendedData>\n</VTKFile>\n";
}

}  // namespace

std::string format_vtp_data(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                            const VtkData& data, const std::string& comment) {
  Appended a;
  std::string body = a.section("PointData", data.points) + a.section("CellData", data.cells);
  body += "      <Points>\n" + a.points(points, "        ") + "      </Points>\n";
  std::vector<std::uint32_t> conn, offsets;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    conn.insert(conn.end(), triangles[t].begin(), triangles[t].end());
    offsets.push_back(static_cast<std::uint32_t>(3 * (t + 1)));
  }
  body += "      <Polys>\n" + a.int64s<std::uint32_t>("connectivity", conn, "        ") +
          a.int64s<std::uint32_t>("offsets", offsets, "        ") + "      </Polys>\n";
  return header("PolyData", comment) +
         fmt::format(
             "  <PolyData>\n    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
             "NumberOfStrips=\"0\" NumberOfPolys=\"{}\">\n",
             points.size(), triangles.size()) +
         body + footer("PolyData", a);
}

std::string format_vtu_tets(const std::vector<Vec3>& points, const std::vector<Tet>& tets, const VtkData& data,
                            const std::string& comment) {
  Appended a;
  std::string body = a.section("PointData", data.points) + a.section("CellData", data.cells);
  body += "      <Points>\n" + a.points(points, "        ") + "      </Points>\n";
  std::vector<std::uint32_t> conn, offsets;
  for (std::size_t t = 0; t < tets.size(); ++t) {
    conn.insert(conn.end(), tets[t].begin(), tets[t].end());
    offsets.push_back(static_cast<std::uint32_t>(4 * (t + 1)));
  }
  body += "      <Cells>\n" + a.int64s<std::uint32_t>("connectivity", conn, "        ") +
          a.int64s<std::uint32_t>("offsets", offsets, "        ");
  // VTK_TETRA = 10, one UInt8 per cell.
  body += a.array("UInt8", "types", 1, "        ");
  append_raw(a.bytes, static_cast<std::uint64_t>(tets.size()));
  for (std::size_t t = 0; t < tets.size(); ++t) append_raw(a.bytes, static_cast<std::uint8_t>(10));
  body += "      </Cells>\n";
  return header("UnstructuredGrid", comment) +
         fmt::format("  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", points.size(),
                     tets.size()) +
         body + footer("UnstructuredGrid", a);
}

}  // namespace c4d
