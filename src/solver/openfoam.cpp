// The OpenFOAM hand-off (OpenFOAM v1912, www.openfoam.com): the polyMesh format of the OpenFOAM user guide
// ("Mesh description": points, faces, owner, neighbour, boundary; internal faces first in upper-triangular
// order, each face's normal by the right-hand rule pointing out of its owner cell), and the case of a
// dynamicMotionSolverFvMesh whose displacementLaplacian solver takes every patch's point displacement from
// constant/boundaryData (timeVaryingMappedFixedValue, nearest-point mapping onto the same points).
#include "contour4d/solver/openfoam.h"

#include <algorithm>
#include <array>

#include <fmt/format.h>

namespace c4d {
namespace {

std::string header(const char* cls, const char* location, const char* object, const std::string& note = {}) {
  return fmt::format(
      "/*--------------------------------*- C++ -*----------------------------------*\\\n"
      "  written by contour4d export (OpenFOAM v1912 format)\n"
      "\\*---------------------------------------------------------------------------*/\n"
      "FoamFile\n{{\n    version     2.0;\n    format      ascii;\n    class       {};\n{}"
      "    location    \"{}\";\n    object      {};\n}}\n\n",
      cls, note.empty() ? std::string() : "    note        \"" + note + "\";\n", location, object);
}

struct Face {
  std::array<std::uint32_t, 3> v;
  std::uint32_t owner = 0;
  std::uint32_t neighbour = 0;
};

// A tet's outward faces, the one opposite each node (positively oriented tets).
std::array<std::array<std::uint32_t, 3>, 4> outward_faces(const Tet& q) {
  return {{{q[1], q[2], q[3]}, {q[0], q[3], q[2]}, {q[0], q[1], q[3]}, {q[0], q[2], q[1]}}};
}

// Internal faces: each shared by two tets, owner the lower, oriented out of it; sorted by owner then neighbour.
std::vector<Face> internal_faces(const TetMesh& mesh) {
  struct Entry {
    std::array<std::uint32_t, 3> key;
    std::uint32_t tet;
    std::uint8_t local;
  };
  std::vector<Entry> entries;
  entries.reserve(mesh.tets.size() * 4);
  for (std::uint32_t t = 0; t < mesh.tets.size(); ++t) {
    const auto faces = outward_faces(mesh.tets[t]);
    for (std::uint8_t k = 0; k < 4; ++k) {
      auto key = faces[k];
      std::sort(key.begin(), key.end());
      entries.push_back({key, t, k});
    }
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.key != b.key ? a.key < b.key : a.tet < b.tet; });
  std::vector<Face> faces;
  for (std::size_t i = 0; i + 1 < entries.size(); ++i)
    if (entries[i].key == entries[i + 1].key) {
      const Entry& own = entries[i];  // the lower tet
      faces.push_back({outward_faces(mesh.tets[own.tet])[own.local], own.tet, entries[i + 1].tet});
      ++i;
    }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) {
    return a.owner != b.owner ? a.owner < b.owner : a.neighbour < b.neighbour;
  });
  return faces;
}

std::string vectors(const std::vector<Vec3>& p, double scale) {
  fmt::memory_buffer b;
  fmt::format_to(std::back_inserter(b), "{}\n(\n", p.size());
  for (const Vec3& v : p)
    fmt::format_to(std::back_inserter(b), "({:.17g} {:.17g} {:.17g})\n", scale * v.x, scale * v.y, scale * v.z);
  fmt::format_to(std::back_inserter(b), ")\n");
  return fmt::to_string(b);
}

void write_poly_mesh(const OutputDir& out, const std::string& dir, const Handoff& h, double scale) {
  const TetMesh& m = h.cavity;
  const std::vector<Face> internal = internal_faces(m);
  std::vector<Face> faces = internal;
  std::vector<std::size_t> start, count;
  for (std::size_t patch = 0; patch < h.surface.names.size(); ++patch) {
    start.push_back(faces.size());
    for (std::size_t t = 0; t < m.boundary.size(); ++t)
      if (h.surface.face[t] == patch) faces.push_back({m.boundary[t], m.boundary_tet[t], 0});
    count.push_back(faces.size() - start.back());
  }
  const std::string note = fmt::format("nPoints:{}  nCells:{}  nFaces:{}  nInternalFaces:{}", m.nodes.size(),
                                       m.tets.size(), faces.size(), internal.size());
  out.write(dir + "/points", header("vectorField", "constant/polyMesh", "points") + vectors(m.nodes, scale));
  fmt::memory_buffer f, o, n;
  fmt::format_to(std::back_inserter(f), "{}\n(\n", faces.size());
  fmt::format_to(std::back_inserter(o), "{}\n(\n", faces.size());
  fmt::format_to(std::back_inserter(n), "{}\n(\n", internal.size());
  for (std::size_t i = 0; i < faces.size(); ++i) {
    fmt::format_to(std::back_inserter(f), "3({} {} {})\n", faces[i].v[0], faces[i].v[1], faces[i].v[2]);
    fmt::format_to(std::back_inserter(o), "{}\n", faces[i].owner);
    if (i < internal.size()) fmt::format_to(std::back_inserter(n), "{}\n", faces[i].neighbour);
  }
  for (auto* b : {&f, &o, &n}) fmt::format_to(std::back_inserter(*b), ")\n");
  out.write(dir + "/faces", header("faceList", "constant/polyMesh", "faces") + fmt::to_string(f));
  out.write(dir + "/owner", header("labelList", "constant/polyMesh", "owner", note) + fmt::to_string(o));
  out.write(dir + "/neighbour", header("labelList", "constant/polyMesh", "neighbour", note) + fmt::to_string(n));
  std::string boundary =
      header("polyBoundaryMesh", "constant/polyMesh", "boundary") + fmt::format("{}\n(\n", h.surface.names.size());
  for (std::size_t p = 0; p < h.surface.names.size(); ++p)
    boundary += fmt::format(
        "    {}\n    {{\n        type            {};\n{}        nFaces          {};\n        startFace       {};\n    "
        "}}\n",
        h.surface.names[p], p == 0 ? "wall" : "patch", p == 0 ? "        inGroups        List<word> 1(wall);\n" : "",
        count[p], start[p]);
  out.write(dir + "/boundary", boundary + ")\n");
}

// boundaryData: each patch's points at t = 0 and their displacement at every output time.
void write_boundary_data(const OutputDir& out, const std::string& dir, const Handoff& h, double scale) {
  std::vector<FacePart> parts;
  for (std::size_t p = 0; p < h.surface.names.size(); ++p) {
    parts.push_back(face_part(h, static_cast<int>(p)));
    std::vector<Vec3> x0;
    for (std::uint32_t v : parts.back().vertices) x0.push_back(h.surface.seq.positions[0][v]);
    // boundaryData files are raw lists: v1912's point-patch reader takes no FoamFile header.
    out.write(dir + "/" + h.surface.names[p] + "/points", "// written by contour4d export: the points of patch " +
                                                              h.surface.names[p] + " at t = 0\n" + vectors(x0, scale));
  }
  const int decimals = length_decimals(scale);
  for (std::size_t i = 0; i < h.steps.times_s.size(); ++i) {
    const std::vector<Vec3> x = surface_at(h, i);
    const std::string time = fmt::format("{:.12g}", h.steps.times_s[i]);
    for (std::size_t p = 0; p < parts.size(); ++p) {
      fmt::memory_buffer b;
      fmt::format_to(std::back_inserter(b), "{}\n(\n", parts[p].vertices.size());
      for (std::uint32_t v : parts[p].vertices) {
        const Vec3 d = scale * (x[v] - h.surface.seq.positions[0][v]);
        fmt::format_to(std::back_inserter(b), "({:.{}f} {:.{}f} {:.{}f})\n", d.x, decimals, d.y, decimals, d.z,
                       decimals);
      }
      fmt::format_to(std::back_inserter(b), ")\n");
      out.write(dir + "/" + h.surface.names[p] + "/" + time + "/pointDisplacement",
                "// written by contour4d export: displacement from t = 0 at t = " + time + " s\n" + fmt::to_string(b));
    }
  }
}

std::string patch_fields(const Handoff& h, const std::string& wall, const std::string& end) {
  std::string s;
  for (std::size_t p = 0; p < h.surface.names.size(); ++p)
    s += fmt::format("    {}\n    {{\n{}    }}\n", h.surface.names[p], p == 0 ? wall : end);
  return s;
}

void write_case(const OutputDir& out, const std::string& dir, const Handoff& h) {
  const double end_time = h.steps.times_s.back();
  const std::size_t write_every = std::max<std::size_t>(1, h.steps.steps_per_cycle / 20);
  out.write(dir + "/system/controlDict",
            header("dictionary", "system", "controlDict") +
                fmt::format("application     pimpleFoam;\nstartFrom       startTime;\nstartTime       0;\n"
                            "stopAt          endTime;\nendTime         {:.17g};\ndeltaT          {:.17g};\n"
                            "writeControl    timeStep;\nwriteInterval   {};\npurgeWrite      0;\n"
                            "writeFormat     ascii;\nwritePrecision  16;\nwriteCompression off;\n"
                            "timeFormat      general;\ntimePrecision   12;\nrunTimeModifiable false;\n",
                            end_time, h.steps.dt_s, write_every));
  out.write(dir + "/system/fvSchemes",
            header("dictionary", "system", "fvSchemes") +
                "ddtSchemes\n{\n    default         Euler;\n}\n"
                "gradSchemes\n{\n    default         Gauss linear;\n}\n"
                "divSchemes\n{\n    default         none;\n    div(phi,U)      Gauss linearUpwind grad(U);\n"
                "    div((nuEff*dev2(T(grad(U))))) Gauss linear;\n}\n"
                "laplacianSchemes\n{\n    default         Gauss linear limited corrected 0.5;\n}\n"
                "interpolationSchemes\n{\n    default         linear;\n}\n"
                "snGradSchemes\n{\n    default         limited corrected 0.5;\n}\n");
  out.write(
      dir + "/system/fvSolution",
      header("dictionary", "system", "fvSolution") +
          "solvers\n{\n"
          "    \"cellDisplacement(|Final)\"\n    {\n        solver          PCG;\n        preconditioner  DIC;\n"
          "        tolerance       1e-10;\n        relTol          0;\n    }\n"
          "    \"(p|pcorr)\"\n    {\n        solver          GAMG;\n        smoother        GaussSeidel;\n"
          "        tolerance       1e-7;\n        relTol          0.01;\n    }\n"
          "    \"(p|pcorr)Final\"\n    {\n        $p;\n        relTol          0;\n    }\n"
          "    \"(U|UFinal)\"\n    {\n        solver          smoothSolver;\n        smoother        symGaussSeidel;\n"
          "        tolerance       1e-7;\n        relTol          0;\n    }\n}\n"
          "PIMPLE\n{\n    nOuterCorrectors 1;\n    nCorrectors     2;\n    nNonOrthogonalCorrectors 1;\n"
          "    correctPhi      yes;\n    moveMeshOuterCorrectors no;\n}\n");
  out.write(
      dir + "/constant/dynamicMeshDict",
      header("dictionary", "constant", "dynamicMeshDict") +
          "dynamicFvMesh   dynamicMotionSolverFvMesh;\nmotionSolverLibs (\"libfvMotionSolvers.so\");\n"
          "motionSolver    displacementLaplacian;\n"
          "// uniform: on these tet meshes fewer cells invert than with (quadratic) inverseDistance (docs/export.md)\n"
          "displacementLaplacianCoeffs\n{\n    diffusivity     uniform;\n}\n");
  out.write(dir + "/constant/transportProperties",
            header("dictionary", "constant", "transportProperties") +
                "// blood as a Newtonian fluid: 0.0035 Pa s / 1060 kg/m3 (kinematic, m2/s: lengths in metres)\n"
                "transportModel  Newtonian;\nnu              3.3e-06;\n");
  out.write(dir + "/constant/turbulenceProperties",
            header("dictionary", "constant", "turbulenceProperties") + "simulationType  laminar;\n");
  out.write(dir + "/0/pointDisplacement",
            header("pointVectorField", "0", "pointDisplacement") +
                "dimensions      [0 1 0 0 0 0 0];\ninternalField   uniform (0 0 0);\nboundaryField\n{\n" +
                patch_fields(h,
                             "        type            timeVaryingMappedFixedValue;\n        setAverage      false;\n"
                             "        mapMethod       nearest;\n",
                             "        type            timeVaryingMappedFixedValue;\n        setAverage      false;\n"
                             "        mapMethod       nearest;\n") +
                "}\n");
  out.write(dir + "/0/U",
            header("volVectorField", "0", "U") +
                "dimensions      [0 1 -1 0 0 0 0];\ninternalField   uniform (0 0 0);\nboundaryField\n{\n" +
                patch_fields(h,
                             "        type            movingWallVelocity;\n        value           "
                             "uniform (0 0 0);\n",
                             "        type            pressureInletOutletVelocity;\n        value        "
                             "   uniform (0 0 0);\n") +
                "}\n");
  out.write(dir + "/0/p",
            header("volScalarField", "0", "p") +
                "dimensions      [0 2 -2 0 0 0 0];\ninternalField   uniform 0;\nboundaryField\n{\n" +
                patch_fields(h, "        type            zeroGradient;\n",
                             "        type            fixedValue;\n        value           uniform 0;\n") +
                "}\n");
}

}  // namespace

void write_openfoam(const OutputDir& out, const std::string& folder, const Handoff& h, double scale) {
  write_poly_mesh(out, folder + "/constant/polyMesh", h, scale);
  write_boundary_data(out, folder + "/constant/boundaryData", h, scale);
  write_case(out, folder, h);
}

}  // namespace c4d
