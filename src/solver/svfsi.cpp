// The svFSI / svMultiPhysics hand-off (SimVascular's svFSI, C. Zhu, V. Vedula et al., JOSS 2022; its C++ port
// svMultiPhysics): the mesh-complete folder SimVascular writes (volume .vtu and one .vtp per face, bound by
// GlobalNodeID / GlobalElementID) and, per face, the "Temporal and spatial values file" a General Dirichlet
// condition reads (svFSI's read_temp_spat_values: "ndof ntimes nnodes", the times from 0, then each node's
// 1-based global id followed by its values at every time; the last time is the period).
#include "contour4d/solver/svfsi.h"

#include <fstream>

#include <fmt/format.h>

#include "contour4d/core/errors.h"
#include "contour4d/io/vtk_grid.h"

namespace c4d {
namespace {

// A face's .vtp: its triangles with local points, each point's global node id, each triangle's tet and face id.
std::string face_vtp(const Handoff& h, const std::vector<int>& faces, double scale, const std::string& what) {
  std::vector<char> want(h.surface.names.size(), 0);
  for (int f : faces) want[static_cast<std::size_t>(f)] = 1;
  const auto& tris = h.surface.seq.triangles;
  std::vector<std::int32_t> local(h.cavity.surface_nodes, -1);
  std::vector<Vec3> points;
  VtkArray node{"GlobalNodeID", 1, {}, {}}, element{"GlobalElementID", 1, {}, {}}, face{"ModelFaceID", 1, {}, {}};
  std::vector<Triangle> out;
  for (std::uint32_t t = 0; t < tris.size(); ++t) {
    if (!want[h.surface.face[t]]) continue;
    Triangle lt{};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = tris[t][k];
      if (local[v] < 0) {
        local[v] = static_cast<std::int32_t>(points.size());
        points.push_back(scale * h.cavity.nodes[v]);
        node.ints.push_back(static_cast<std::int32_t>(v + 1));
      }
      lt[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(local[v]);
    }
    out.push_back(lt);
    element.ints.push_back(static_cast<std::int32_t>(h.cavity.boundary_tet[t] + 1));
    face.ints.push_back(h.surface.face[t] + 1);
  }
  return format_vtp_data(points, out, {{node}, {element, face}}, what);
}

std::string solver_xml(const Handoff& h, double scale) {
  const double unit_m = 1e-3 / scale;                        // the length unit in metres
  const double density = 1060.0 * unit_m * unit_m * unit_m;  // 1060 kg/m³ in kg per unit³
  const double viscosity = 0.0035 * unit_m;                  // 0.0035 Pa·s = kg/(m·s) in kg/(unit·s)
  std::string faces, mesh_bcs, fluid_bcs;
  for (std::size_t f = 0; f < h.surface.names.size(); ++f) {
    const std::string& n = h.surface.names[f];
    faces += fmt::format(
        "    <Add_face name=\"{0}\">\n      <Face_file_path> mesh-complete/mesh-surfaces/{0}.vtp </Face_file_path>\n"
        "    </Add_face>\n",
        n);
    mesh_bcs += fmt::format(
        "    <Add_BC name=\"{0}\">\n      <Type> Dir </Type>\n      <Time_dependence> General </Time_dependence>\n"
        "      <Temporal_and_spatial_values_file_path> {0}_displacement.dat </Temporal_and_spatial_values_file_path>\n"
        "    </Add_BC>\n",
        n);
    if (f == 0)
      fluid_bcs += fmt::format(
          "    <Add_BC name=\"{0}\">\n      <Type> Dir </Type>\n      <Time_dependence> Steady </Time_dependence>\n"
          "      <Value> 0.0 </Value>\n    </Add_BC>\n",
          n);
    else
      fluid_bcs += fmt::format(
          "    <Add_BC name=\"{0}\">\n      <Type> Neu </Type>\n      <Time_dependence> Steady </Time_dependence>\n"
          "      <Value> 0.0 </Value>\n      <Backflow_stabilization_coefficient> 0.2 "
          "</Backflow_stabilization_coefficient>\n"
          "    </Add_BC>\n",
          n);
  }
  return fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\" ?>\n"
      "<!-- contour4d export: a minimal svMultiPhysics (svFSIplus) input. The cavity's fluid moves with its wall\n"
      "     (ALE: the FSI equation with a fluid domain only, and the mesh equation driven by the prescribed\n"
      "     displacement of every face). Lengths in {} mm, times in s; blood: density {} , viscosity {} (SI values\n"
      "     1060 kg/m3 and 0.0035 Pa s in these units). The wall is no-slip relative to its own motion; each opened\n"
      "     end is a zero-traction opening. Adjust to your study. -->\n"
      "<svMultiPhysicsFile version=\"0.1\">\n"
      "  <GeneralSimulationParameters>\n"
      "    <Continue_previous_simulation> false </Continue_previous_simulation>\n"
      "    <Number_of_spatial_dimensions> 3 </Number_of_spatial_dimensions>\n"
      "    <Number_of_time_steps> {} </Number_of_time_steps>\n"
      "    <Time_step_size> {:.17g} </Time_step_size>\n"
      "    <Spectral_radius_of_infinite_time_step> 0.50 </Spectral_radius_of_infinite_time_step>\n"
      "    <Searched_file_name_to_trigger_stop> STOP_SIM </Searched_file_name_to_trigger_stop>\n"
      "    <Save_results_to_VTK_format> true </Save_results_to_VTK_format>\n"
      "    <Name_prefix_of_saved_VTK_files> result </Name_prefix_of_saved_VTK_files>\n"
      "    <Increment_in_saving_VTK_files> {} </Increment_in_saving_VTK_files>\n"
      "    <Start_saving_after_time_step> 1 </Start_saving_after_time_step>\n"
      "    <Verbose> true </Verbose>\n"
      "    <Warning> false </Warning>\n"
      "    <Debug> false </Debug>\n"
      "  </GeneralSimulationParameters>\n"
      "  <Add_mesh name=\"cavity\">\n"
      "    <Mesh_file_path> mesh-complete/mesh-complete.mesh.vtu </Mesh_file_path>\n"
      "{}"
      "    <Domain> 0 </Domain>\n"
      "  </Add_mesh>\n"
      "  <Add_equation type=\"FSI\">\n"
      "    <Coupled> true </Coupled>\n"
      "    <Min_iterations> 1 </Min_iterations>\n"
      "    <Max_iterations> 10 </Max_iterations>\n"
      "    <Tolerance> 1e-6 </Tolerance>\n"
      "    <Domain id=\"0\">\n"
      "      <Equation> fluid </Equation>\n"
      "      <Density> {} </Density>\n"
      "      <Viscosity model=\"Constant\">\n        <Value> {} </Value>\n      </Viscosity>\n"
      "      <Backflow_stabilization_coefficient> 0.2 </Backflow_stabilization_coefficient>\n"
      "    </Domain>\n"
      "    <LS type=\"GMRES\">\n"
      "      <Linear_algebra type=\"fsils\">\n        <Preconditioner> fsils </Preconditioner>\n      "
      "</Linear_algebra>\n"
      "      <Tolerance> 1e-6 </Tolerance>\n      <Max_iterations> 100 </Max_iterations>\n"
      "    </LS>\n"
      "    <Output type=\"Spatial\">\n      <Velocity> true </Velocity>\n      <Pressure> true </Pressure>\n"
      "      <Displacement> true </Displacement>\n    </Output>\n"
      "{}"
      "  </Add_equation>\n"
      "  <Add_equation type=\"mesh\">\n"
      "    <Coupled> true </Coupled>\n"
      "    <Min_iterations> 1 </Min_iterations>\n"
      "    <Max_iterations> 5 </Max_iterations>\n"
      "    <Tolerance> 1e-6 </Tolerance>\n"
      "    <Poisson_ratio> 0.3 </Poisson_ratio>\n"
      "    <LS type=\"CG\">\n"
      "      <Linear_algebra type=\"fsils\">\n        <Preconditioner> fsils </Preconditioner>\n      "
      "</Linear_algebra>\n"
      "      <Tolerance> 1e-6 </Tolerance>\n"
      "    </LS>\n"
      "    <Output type=\"Spatial\">\n      <Displacement> true </Displacement>\n    </Output>\n"
      "{}"
      "  </Add_equation>\n"
      "</svMultiPhysicsFile>\n",
      1.0 / scale, density, viscosity, h.steps.times_s.size() - 1, h.steps.dt_s,
      std::max<std::size_t>(1, h.steps.steps_per_cycle / 20), faces, density, viscosity, fluid_bcs, mesh_bcs);
}

}  // namespace

void write_svfsi_displacement(const std::filesystem::path& path, const Handoff& h,
                              const std::vector<std::uint32_t>& vertices, double scale) {
  std::ofstream file(path, std::ios::binary);
  if (!file) throw IoError(ErrorCode::OutputNotWritable, {path.string()}, "cannot write the displacement file");
  const std::vector<TimeWeights> weights = all_step_weights(h);
  const int decimals = length_decimals(scale);
  fmt::memory_buffer buf;
  fmt::format_to(std::back_inserter(buf), "3 {} {}\n", weights.size(), vertices.size());
  for (double t : h.steps.times_s) fmt::format_to(std::back_inserter(buf), "{:.12g}\n", t);
  const auto& frames = h.surface.seq.positions;
  for (std::uint32_t v : vertices) {
    fmt::format_to(std::back_inserter(buf), "{}\n", v + 1);
    const Vec3 x0 = frames[0][v];
    for (const TimeWeights& w : weights) {
      const Vec3 d = scale * (combine_vertex(frames, w, v) - x0);
      fmt::format_to(std::back_inserter(buf), "{:.{}f} {:.{}f} {:.{}f}\n", d.x, decimals, d.y, decimals, d.z, decimals);
    }
    if (buf.size() > (1u << 20)) {
      file.write(buf.data(), static_cast<std::streamsize>(buf.size()));
      buf.clear();
    }
  }
  file.write(buf.data(), static_cast<std::streamsize>(buf.size()));
  if (!file) throw IoError(ErrorCode::OutputNotWritable, {path.string()}, "writing the displacement file failed");
}

void write_svfsi(const OutputDir& out, const std::string& folder, const Handoff& h, double scale) {
  const std::string mc = folder + "/mesh-complete/";
  VtkArray node{"GlobalNodeID", 1, {}, {}}, element{"GlobalElementID", 1, {}, {}}, region{"ModelRegionID", 1, {}, {}};
  std::vector<Vec3> nodes;
  nodes.reserve(h.cavity.nodes.size());
  for (std::size_t v = 0; v < h.cavity.nodes.size(); ++v) {
    nodes.push_back(scale * h.cavity.nodes[v]);
    node.ints.push_back(static_cast<std::int32_t>(v + 1));
  }
  for (std::size_t t = 0; t < h.cavity.tets.size(); ++t) {
    element.ints.push_back(static_cast<std::int32_t>(t + 1));
    region.ints.push_back(1);
  }
  const std::string units = fmt::format("lengths in {} mm", 1.0 / scale);
  out.write(mc + "mesh-complete.mesh.vtu", format_vtu_tets(nodes, h.cavity.tets, {{node}, {element, region}},
                                                           "contour4d export: the cavity, " + units));
  std::vector<int> all;
  for (std::size_t f = 0; f < h.surface.names.size(); ++f) all.push_back(static_cast<int>(f));
  out.write(mc + "mesh-complete.exterior.vtp", face_vtp(h, all, scale, "contour4d export: every face, " + units));
  out.write(mc + "walls_combined.vtp", face_vtp(h, {0}, scale, "contour4d export: the wall, " + units));
  for (std::size_t f = 0; f < h.surface.names.size(); ++f) {
    const std::string& n = h.surface.names[f];
    out.write(mc + "mesh-surfaces/" + n + ".vtp",
              face_vtp(h, {static_cast<int>(f)}, scale, "contour4d export: face " + n + ", " + units));
    write_svfsi_displacement(out.path(folder + "/" + n + "_displacement.dat"), h,
                             face_part(h, static_cast<int>(f)).vertices, scale);
  }
  out.write(folder + "/solver.xml", solver_xml(h, scale));
}

}  // namespace c4d
