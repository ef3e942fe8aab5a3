// glTF 2.0 export with morph targets (Khronos glTF 2.0 §3.7.2.2 morph targets, §3.11 animations):
// plain float attributes by default, KHR_mesh_quantization on request. Debian's tinygltf is a compiled library: TINYGLTF_IMPLEMENTATION is not
// defined here, the .so provides it.
#include "contour4d/io/gltf.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>
#include <utility>

#include <tiny_gltf.h>

#include "contour4d/core/errors.h"
#include "contour4d/core/normals.h"
#include "contour4d/io/output_dir.h"

namespace c4d {
namespace {

Vec3 to_gltf(Vec3 p, bool rotate) { return rotate ? Vec3{p.x, p.z, -p.y} : p; }

template <class T>
int add_view(tinygltf::Model& m, const std::vector<T>& data, int target) {
  tinygltf::Buffer& buf = m.buffers[0];
  while (buf.data.size() % 4) buf.data.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buf.data.size();
  view.byteLength = data.size() * sizeof(T);
  view.target = target;
  const auto* p = reinterpret_cast<const unsigned char*>(data.data());
  buf.data.insert(buf.data.end(), p, p + view.byteLength);
  m.bufferViews.push_back(view);
  return static_cast<int>(m.bufferViews.size() - 1);
}

int add_accessor(tinygltf::Model& m, int view, int component, int type, std::size_t count, std::vector<double> mn,
                 std::vector<double> mx) {
  tinygltf::Accessor a;
  a.bufferView = view;
  a.componentType = component;
  a.type = type;
  a.count = count;
  a.minValues = std::move(mn);
  a.maxValues = std::move(mx);
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size() - 1);
}

// Throws unless seq is non-empty, every frame has frame 0's vertex count and every index is in range.
void check_sequence(const MeshSequence& seq) {
  if (seq.positions.empty() || seq.positions[0].empty() || seq.triangles.empty())
    throw InvalidInput(ErrorCode::BadMesh, {}, "nothing to export: the mesh sequence is empty",
                       "reconstruct a 4D mesh first");
  const std::size_t nv = seq.positions[0].size(), nf = seq.positions.size();
  for (std::size_t f = 0; f < nf; ++f)
    if (seq.positions[f].size() != nv)
      throw InvalidInput(ErrorCode::BadMesh, {{}, -1, static_cast<int>(f)}, "frames differ in vertex count",
                         "all frames of a 4D mesh must share vertices and triangles");
  for (const Triangle& t : seq.triangles)
    for (auto i : t)
      if (i >= nv)
        throw InvalidInput(ErrorCode::BadMesh, {}, "triangle index out of range", "the triangle list is corrupt");
}

//! Quantisation grid (mm) in glTF axes: base uint16, displacements int16, same step.
struct Grid {
  Vec3 lo;
  double step = 0.0;
};

// The grid over all frames' vertices (glTF axes); throws on a non-finite vertex.
Grid quantisation_grid(const MeshSequence& seq, bool rotate) {
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const auto& frame : seq.positions)
    for (const Vec3& p0 : frame) {
      const Vec3 p = to_gltf(p0, rotate);
      if (!is_finite(p)) throw InvalidInput(ErrorCode::NonFinite, {}, "non-finite vertex", "check the reconstruction");
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], p[c]);
        hi[c] = std::max(hi[c], p[c]);
      }
    }
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-9});
  return {lo, extent / 32767.0};  // any displacement fits int16, any position uint16
}

// A model with the asset, one empty buffer and, when quantised, the quantisation extension.
tinygltf::Model empty_model(bool quantized) {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "contour4d";
  if (quantized) {
    m.extensionsUsed = {"KHR_mesh_quantization"};
    m.extensionsRequired = {"KHR_mesh_quantization"};
  }
  m.buffers.resize(1);
  return m;
}

// Frame f's positions (metres) and unit normals in glTF axes, as floats, three per vertex.
struct PlainFrame {
  std::vector<float> position, normal;
};

PlainFrame plain_frame(const MeshSequence& seq, std::size_t f, bool rotate) {
  const std::vector<Vec3>& p = seq.positions[f];
  const std::vector<Vec3> n = area_weighted_normals(p, seq.triangles, Vec3{0, 0, 1});
  PlainFrame out;
  out.position.reserve(3 * p.size());
  out.normal.reserve(3 * p.size());
  for (std::size_t v = 0; v < p.size(); ++v) {
    const Vec3 q = to_gltf(0.001 * p[v], rotate), m = to_gltf(n[v], rotate);
    if (!is_finite(q))
      throw InvalidInput(ErrorCode::NonFinite, {{}, -1, static_cast<int>(f)}, "non-finite vertex",
                         "check the reconstruction");
    for (int c = 0; c < 3; ++c) {
      out.position.push_back(static_cast<float>(q[c]));
      out.normal.push_back(static_cast<float>(m[c]));
    }
  }
  return out;
}

// Per-component minimum and maximum of float triples (glTF requires them on POSITION accessors).
std::pair<std::vector<double>, std::vector<double>> bounds(const std::vector<float>& xyz) {
  std::vector<double> mn(3, 0.0), mx(3, 0.0);
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    const int c = static_cast<int>(i % 3);
    mn[c] = i < 3 ? xyz[i] : std::min<double>(mn[c], xyz[i]);
    mx[c] = i < 3 ? xyz[i] : std::max<double>(mx[c], xyz[i]);
  }
  return {mn, mx};
}

// A float VEC3 accessor of `xyz` (with bounds when `with_bounds`).
int add_vec3(tinygltf::Model& m, const std::vector<float>& xyz, bool with_bounds) {
  const int view = add_view(m, xyz, TINYGLTF_TARGET_ARRAY_BUFFER);
  auto [mn, mx] = with_bounds ? bounds(xyz) : std::pair<std::vector<double>, std::vector<double>>{};
  return add_accessor(m, view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, xyz.size() / 3, std::move(mn),
                      std::move(mx));
}

// The plain geometry: frame 0's float positions and normals, the indices, and one morph target per frame
// (float position and normal displacements from frame 0); returns the targets' names.
tinygltf::Value::Array add_plain_geometry(tinygltf::Model& m, const MeshSequence& seq, bool rotate,
                                          tinygltf::Primitive& prim) {
  const std::size_t nv = seq.positions[0].size(), nf = seq.positions.size();
  const PlainFrame base = plain_frame(seq, 0, rotate);
  prim.attributes["POSITION"] = add_vec3(m, base.position, true);
  prim.attributes["NORMAL"] = add_vec3(m, base.normal, false);
  std::vector<std::uint32_t> idx;
  idx.reserve(seq.triangles.size() * 3);
  for (const Triangle& t : seq.triangles) idx.insert(idx.end(), t.begin(), t.end());
  const int view = add_view(m, idx, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  prim.indices = add_accessor(m, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, idx.size(), {0},
                              {static_cast<double>(nv - 1)});
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Value::Array target_names;
  for (std::size_t f = 0; f < nf; ++f) {
    PlainFrame d = f == 0 ? base : plain_frame(seq, f, rotate);  // frame 0's displacements are zero
    for (std::size_t i = 0; i < d.position.size(); ++i) {
      d.position[i] -= base.position[i];
      d.normal[i] -= base.normal[i];
    }
    std::map<std::string, int> target;
    target["POSITION"] = add_vec3(m, d.position, true);
    target["NORMAL"] = add_vec3(m, d.normal, false);
    prim.targets.push_back(target);
    target_names.emplace_back("frame_" + std::to_string(f));
  }
  return target_names;
}

// Frame 0 quantised on the grid, 4 uint16 per vertex (each element aligned to 4 bytes).
std::vector<std::uint16_t> quantised_base(const MeshSequence& seq, const Grid& g, bool rotate) {
  const std::size_t nv = seq.positions[0].size();
  std::vector<std::uint16_t> base(nv * 4, 0);
  for (std::size_t v = 0; v < nv; ++v) {
    const Vec3 p = to_gltf(seq.positions[0][v], rotate);
    for (int c = 0; c < 3; ++c)
      base[4 * v + c] = static_cast<std::uint16_t>(std::clamp(std::lround((p[c] - g.lo[c]) / g.step), 0L, 65535L));
  }
  return base;
}

// Adds the base positions and the indices (views and accessors) to the primitive.
void add_geometry(tinygltf::Model& m, const MeshSequence& seq, const std::vector<std::uint16_t>& base,
                  tinygltf::Primitive& prim) {
  const std::size_t nv = seq.positions[0].size();
  std::vector<double> bmn(3, 65535), bmx(3, 0);
  for (std::size_t v = 0; v < nv; ++v)
    for (int c = 0; c < 3; ++c) {
      bmn[c] = std::min<double>(bmn[c], base[4 * v + c]);
      bmx[c] = std::max<double>(bmx[c], base[4 * v + c]);
    }
  std::vector<std::uint32_t> idx;
  idx.reserve(seq.triangles.size() * 3);
  for (const Triangle& t : seq.triangles) idx.insert(idx.end(), t.begin(), t.end());
  int view = add_view(m, base, TINYGLTF_TARGET_ARRAY_BUFFER);
  m.bufferViews.back().byteStride = 8;
  prim.attributes["POSITION"] =
      add_accessor(m, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC3, nv, bmn, bmx);
  view = add_view(m, idx, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  prim.indices = add_accessor(m, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, idx.size(), {0},
                              {static_cast<double>(nv - 1)});
  prim.mode = TINYGLTF_MODE_TRIANGLES;
}

// Adds one morph target per frame (int16 displacements from the base) to the primitive; returns their names.
tinygltf::Value::Array add_morph_targets(tinygltf::Model& m, const MeshSequence& seq, const Grid& g, bool rotate,
                                         const std::vector<std::uint16_t>& base, tinygltf::Primitive& prim) {
  const std::size_t nv = seq.positions[0].size(), nf = seq.positions.size();
  tinygltf::Value::Array target_names;
  for (std::size_t f = 0; f < nf; ++f) {
    std::vector<std::int16_t> d(nv * 4, 0);
    std::vector<double> mn(3, 0), mx(3, 0);
    for (std::size_t v = 0; v < nv; ++v) {
      const Vec3 p = to_gltf(seq.positions[f][v], rotate);
      for (int c = 0; c < 3; ++c) {
        const long q =
            std::clamp(std::lround((p[c] - g.lo[c]) / g.step), 0L, 65535L) - static_cast<long>(base[4 * v + c]);
        d[4 * v + c] = static_cast<std::int16_t>(std::clamp(q, -32767L, 32767L));
        mn[c] = std::min<double>(mn[c], d[4 * v + c]);
        mx[c] = std::max<double>(mx[c], d[4 * v + c]);
      }
    }
    const int view = add_view(m, d, TINYGLTF_TARGET_ARRAY_BUFFER);
    m.bufferViews.back().byteStride = 8;
    std::map<std::string, int> target;
    target["POSITION"] = add_accessor(m, view, TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC3, nv, mn, mx);
    prim.targets.push_back(target);
    target_names.emplace_back("frame_" + std::to_string(f));
  }
  return target_names;
}

// Adds the mesh (with its target names, units and axes), its node (grid to metres) and the scene.
void add_mesh_node_scene(tinygltf::Model& m, const tinygltf::Primitive& prim,
                         const tinygltf::Value::Array& target_names, std::size_t nf, const Grid* g,
                         const GltfOptions& opt) {
  tinygltf::Mesh mesh;
  mesh.name = opt.name;
  mesh.primitives.push_back(prim);
  mesh.weights.assign(nf, 0.0);
  tinygltf::Value::Object extras;
  extras["targetNames"] = tinygltf::Value(target_names);
  extras["units"] = tinygltf::Value(std::string("m (from mm x 0.001)"));
  extras["axes"] = tinygltf::Value(std::string(opt.lps_to_y_up ? "glTF (x,y,z) = LPS (x, z, -y)" : "LPS"));
  mesh.extras = tinygltf::Value(extras);
  m.meshes.push_back(mesh);
  tinygltf::Node node;
  node.name = opt.name;
  node.mesh = 0;
  if (g) {  // quantised: grid units to metres
    node.translation = {g->lo.x * 0.001, g->lo.y * 0.001, g->lo.z * 0.001};
    node.scale = {g->step * 0.001, g->step * 0.001, g->step * 0.001};
  }
  m.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  m.scenes.push_back(scene);
  m.defaultScene = 0;
}

// Weights animation: key f has weight 1 on target f (times in s from frame 0, 40 ms apart when
// not given); throws when the times do not increase.
void add_weights_animation(tinygltf::Model& m, const MeshSequence& seq, const GltfOptions& opt) {
  const std::size_t nf = seq.positions.size();
  std::vector<float> times(nf), weights(nf * nf, 0.0f);
  for (std::size_t f = 0; f < nf; ++f) {
    const double t = seq.times_ms.size() == nf ? seq.times_ms[f] - seq.times_ms[0] : static_cast<double>(f) * 40.0;
    times[f] = static_cast<float>(t * 0.001);
    weights[f * nf + f] = 1.0f;
  }
  for (std::size_t f = 1; f < nf; ++f)
    if (!(times[f] > times[f - 1]))
      throw InvalidInput(ErrorCode::BadMesh, {{}, -1, static_cast<int>(f)}, "frame times do not increase",
                         "give each frame a distinct, increasing time_ms");
  int view = add_view(m, times, -1);
  m.bufferViews.back().target = 0;
  const int in_acc =
      add_accessor(m, view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, nf, {times.front()}, {times.back()});
  view = add_view(m, weights, -1);
  m.bufferViews.back().target = 0;
  const int out_acc = add_accessor(m, view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, nf * nf, {}, {});
  tinygltf::AnimationSampler sampler;
  sampler.input = in_acc;
  sampler.output = out_acc;
  sampler.interpolation = opt.step ? "STEP" : "LINEAR";
  tinygltf::AnimationChannel channel;
  channel.sampler = 0;
  channel.target_node = 0;
  channel.target_path = "weights";
  tinygltf::Animation anim;
  anim.name = "cycle";
  anim.samplers.push_back(sampler);
  anim.channels.push_back(channel);
  m.animations.push_back(anim);
}

}  // namespace

std::string gltf_glb_bytes(const MeshSequence& seq, const GltfOptions& opt) {
  check_sequence(seq);
  tinygltf::Model m = empty_model(opt.quantized);
  tinygltf::Primitive prim;
  if (opt.quantized) {
    const Grid g = quantisation_grid(seq, opt.lps_to_y_up);
    const std::vector<std::uint16_t> base = quantised_base(seq, g, opt.lps_to_y_up);
    add_geometry(m, seq, base, prim);
    const tinygltf::Value::Array target_names = add_morph_targets(m, seq, g, opt.lps_to_y_up, base, prim);
    add_mesh_node_scene(m, prim, target_names, seq.positions.size(), &g, opt);
  } else {
    const tinygltf::Value::Array target_names = add_plain_geometry(m, seq, opt.lps_to_y_up, prim);
    add_mesh_node_scene(m, prim, target_names, seq.positions.size(), nullptr, opt);
  }
  add_weights_animation(m, seq, opt);

  std::ostringstream os;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&m, os, false, true))
    throw IoError(ErrorCode::Internal, {}, "tinygltf could not serialise the model", "please report this");
  return os.str();
}

void write_gltf(const std::filesystem::path& path, const MeshSequence& seq, const GltfOptions& options) {
  write_file_atomic(path, gltf_glb_bytes(seq, options));
}

}  // namespace c4d
