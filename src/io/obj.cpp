#include "contour4d/io/obj.h"

#include <charconv>
#include <cstdint>
#include <string_view>

#include <fmt/format.h>

#include "contour4d/core/errors.h"

namespace c4d {

std::string format_obj(const TriangleMesh& mesh, const std::string& comment) {
  std::string out = "# contour4d mesh; units: mm\n";
  if (!comment.empty()) out += "# " + comment + "\n";
  out += fmt::format("# {} vertices, {} triangles\n", mesh.positions.size(), mesh.triangles.size());
  // Shortest round-trip representation: exact and deterministic.
  for (const Vec3& p : mesh.positions) out += fmt::format("v {} {} {}\n", p.x, p.y, p.z);
  for (const Triangle& t : mesh.triangles) out += fmt::format("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
  return out;
}

namespace {

std::string_view next_token(std::string_view& s) {
  const std::size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) {
    s = {};
    return {};
  }
  s.remove_prefix(b);
  const std::size_t e = s.find_first_of(" \t\r");
  const std::string_view tok = s.substr(0, e);
  s.remove_prefix(e == std::string_view::npos ? s.size() : e);
  return tok;
}

}  // namespace

TriangleMesh parse_obj(const std::string& content, const std::string& source) {
  TriangleMesh mesh;
  std::string_view text(content);
  int line_no = 0;
  std::vector<std::int64_t> face;
  while (!text.empty()) {
    const std::size_t nl = text.find('\n');
    std::string_view line = text.substr(0, nl);
    text.remove_prefix(nl == std::string_view::npos ? text.size() : nl + 1);
    ++line_no;
    auto fail = [&](const std::string& what) -> void {
      Location where{source};
      where.line = line_no;
      throw IoError(ErrorCode::BadMesh, where, what, "Fix or re-export the OBJ file");
    };
    const std::string_view kind = next_token(line);
    if (kind == "v") {
      double c[3];
      for (double& x : c) {
        const std::string_view tok = next_token(line);
        const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), x);
        if (tok.empty() || r.ec != std::errc() || r.ptr != tok.data() + tok.size()) fail("invalid vertex coordinate");
      }
      mesh.positions.push_back({c[0], c[1], c[2]});
    } else if (kind == "f") {
      face.clear();
      for (std::string_view tok = next_token(line); !tok.empty(); tok = next_token(line)) {
        tok = tok.substr(0, tok.find('/'));
        std::int64_t idx = 0;
        const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), idx);
        if (r.ec != std::errc() || r.ptr != tok.data() + tok.size() || idx == 0) fail("invalid face index");
        const auto n = static_cast<std::int64_t>(mesh.positions.size());
        if (idx < 0) idx = n + idx + 1;  // relative indices count back from the last vertex
        if (idx < 1 || idx > n) fail("face index out of range");
        face.push_back(idx - 1);
      }
      if (face.size() < 3) fail("face with fewer than 3 vertices");
      for (std::size_t k = 1; k + 1 < face.size(); ++k)
        mesh.triangles.push_back({static_cast<std::uint32_t>(face[0]), static_cast<std::uint32_t>(face[k]),
                                  static_cast<std::uint32_t>(face[k + 1])});
    }
  }
  return mesh;
}

}  // namespace c4d
