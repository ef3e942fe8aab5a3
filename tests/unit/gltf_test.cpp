// glTF export: load back with tinygltf and check morph targets, accessor bounds, animation, units.
#include "contour4d/io/gltf.h"

#include <gtest/gtest.h>

#include <tiny_gltf.h>

#include <cstring>

#include "contour4d/temporal/sequence.h"

namespace c4d {
namespace {

tinygltf::Model load(const std::string& glb) {
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromMemory(&m, &err, &warn, reinterpret_cast<const unsigned char*>(glb.data()),
                                          static_cast<unsigned>(glb.size()), ""))
      << err;
  return m;
}

// A float VEC3 of accessor `acc`, vertex v.
Vec3 vec3(const tinygltf::Model& m, int acc, std::size_t v) {
  const tinygltf::Accessor& a = m.accessors[acc];
  EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  const tinygltf::BufferView& bv = m.bufferViews[a.bufferView];
  const std::size_t stride = bv.byteStride ? bv.byteStride : 12;
  float f[3];
  std::memcpy(f, m.buffers[bv.buffer].data.data() + bv.byteOffset + a.byteOffset + v * stride, sizeof f);
  return {f[0], f[1], f[2]};
}

// The default file: plain floats every reader loads (no extension), normals on the base and every target;
// frame f is the base plus target f (mm after LPS -> Y-up), its normals unit length.
TEST(Gltf, PlainFileHasFloatPositionsNormalsAndNoExtension) {
  const MeshSequence seq = synthetic_beating_mesh(3, 10);
  const tinygltf::Model m = load(gltf_glb_bytes(seq));
  EXPECT_TRUE(m.extensionsRequired.empty());
  EXPECT_TRUE(m.extensionsUsed.empty());
  const tinygltf::Primitive& prim = m.meshes.at(0).primitives.at(0);
  ASSERT_EQ(prim.targets.size(), seq.positions.size());
  const int pa = prim.attributes.at("POSITION"), na = prim.attributes.at("NORMAL");
  EXPECT_EQ(m.accessors[pa].minValues.size(), 3u);
  EXPECT_TRUE(m.nodes.at(0).scale.empty() && m.nodes.at(0).translation.empty());
  double worst = 0.0, worst_normal = 0.0;
  for (std::size_t f = 0; f < seq.positions.size(); f += 2) {
    const auto& target = prim.targets[f];
    EXPECT_EQ(m.accessors[target.at("POSITION")].minValues.size(), 3u);
    for (std::size_t v = 0; v < seq.positions[f].size(); v += 13) {
      const Vec3 g = 1000.0 * (vec3(m, pa, v) + vec3(m, target.at("POSITION"), v));
      const Vec3 p = seq.positions[f][v];
      worst = std::max(worst, distance(g, Vec3{p.x, p.z, -p.y}));
      worst_normal = std::max(worst_normal, std::abs(norm(vec3(m, na, v) + vec3(m, target.at("NORMAL"), v)) - 1.0));
    }
  }
  EXPECT_LT(worst, 1e-3);
  EXPECT_LT(worst_normal, 1e-5);
}

TEST(Gltf, QuantizedLoadsBackWithMorphTargetsAndAnimation) {
  const MeshSequence seq = synthetic_beating_mesh(3, 10);
  GltfOptions quantized;
  quantized.quantized = true;
  const std::string glb = gltf_glb_bytes(seq, quantized);
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromMemory(&m, &err, &warn, reinterpret_cast<const unsigned char*>(glb.data()),
                                          static_cast<unsigned>(glb.size()), ""))
      << err;
  ASSERT_EQ(m.meshes.size(), 1u);
  const tinygltf::Primitive& prim = m.meshes[0].primitives.at(0);
  EXPECT_EQ(prim.targets.size(), seq.positions.size());
  EXPECT_EQ(m.accessors[prim.indices].count, seq.triangles.size() * 3);
  EXPECT_NE(std::find(m.extensionsRequired.begin(), m.extensionsRequired.end(), "KHR_mesh_quantization"),
            m.extensionsRequired.end());
  // Decode frame f vertex v from the file and compare with the input (mm, after LPS -> Y-up).
  const tinygltf::Accessor& pa = m.accessors[prim.attributes.at("POSITION")];
  ASSERT_EQ(pa.count, seq.positions[0].size());
  ASSERT_EQ(pa.minValues.size(), 3u);
  const tinygltf::Node& node = m.nodes.at(0);
  auto read = [&](int acc, std::size_t v, int c, bool is_signed) {
    const tinygltf::Accessor& a = m.accessors[acc];
    const tinygltf::BufferView& bv = m.bufferViews[a.bufferView];
    const unsigned char* p = m.buffers[bv.buffer].data.data() + bv.byteOffset + a.byteOffset + v * 8 + 2 * c;
    std::uint16_t u;
    std::memcpy(&u, p, 2);
    return is_signed ? static_cast<double>(static_cast<std::int16_t>(u)) : static_cast<double>(u);
  };
  double worst = 0.0;
  for (std::size_t f = 0; f < seq.positions.size(); f += 3) {
    const int ta = prim.targets[f].at("POSITION");
    const tinygltf::Accessor& t = m.accessors[ta];
    for (std::size_t v = 0; v < seq.positions[f].size(); v += 17) {
      double g[3];
      for (int c = 0; c < 3; ++c) {
        const double b = read(pa.bufferView >= 0 ? prim.attributes.at("POSITION") : 0, v, c, false);
        const double d = read(ta, v, c, true);
        EXPECT_GE(b, pa.minValues[c]);
        EXPECT_LE(b, pa.maxValues[c]);
        EXPECT_GE(d, t.minValues[c]);
        EXPECT_LE(d, t.maxValues[c]);
        g[c] = ((b + d) * node.scale[c] + node.translation[c]) * 1000.0;  // back to mm
      }
      const Vec3 p = seq.positions[f][v];
      worst = std::max(worst, distance(Vec3{g[0], g[1], g[2]}, Vec3{p.x, p.z, -p.y}));
    }
  }
  EXPECT_LT(worst, 0.01);
  ASSERT_EQ(m.animations.size(), 1u);
  const tinygltf::AnimationSampler& s = m.animations[0].samplers.at(0);
  EXPECT_EQ(s.interpolation, "LINEAR");
  EXPECT_EQ(m.animations[0].channels.at(0).target_path, "weights");
  EXPECT_EQ(m.accessors[s.input].count, seq.positions.size());
  EXPECT_NEAR(m.accessors[s.input].maxValues.at(0), seq.times_ms.back() * 0.001, 1e-6);
  EXPECT_EQ(m.accessors[s.output].count, seq.positions.size() * seq.positions.size());
}

TEST(Gltf, StepOptionAndDeterminism) {
  const MeshSequence seq = synthetic_beating_mesh(1, 3);
  GltfOptions o;
  o.step = true;
  EXPECT_EQ(gltf_glb_bytes(seq, o), gltf_glb_bytes(seq, o));
  EXPECT_NE(gltf_glb_bytes(seq, o).find("STEP"), std::string::npos);
}

}  // namespace
}  // namespace c4d
