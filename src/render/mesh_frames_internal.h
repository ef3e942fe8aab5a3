#pragma once
// The decoded frames of a 4D mesh on the GPU, as `contour4d render` (renderer.cpp) and the viewer
// (patch_renderer.cpp) draw the compact model: frame 0 and every frame's displacement from frame 0 are
// uploaded once; per drawn frame only the blend of up to four frames (ids and weights) is set, and the
// vertex stage adds the weighted displacements to frame 0 (docs/compact.md, "On the GPU"). Private to
// src/render.
#include <cstddef>

#include "contour4d/core/mesh.h"
#include "gl_util_internal.h"

namespace c4d {

//! Vertex stage of the decoded frames: attribute 0 is frame 0; `motion` (texture buffer, texel
//! frame * nv + vertex) the displacements; `frames` and `fw` the blend; `clip_plane` the section plane
//! (kept where dot(plane, (p, 1)) >= 0, with GL_CLIP_DISTANCE0 enabled). `vpos` out for kShadedFragment.
inline constexpr const char* kMeshFramesVertex = R"(#version 430 core
layout(location = 0) in vec3 base;
uniform samplerBuffer motion;
uniform int nv;
uniform ivec4 frames;
uniform vec4 fw;
uniform vec4 clip_plane;
uniform mat4 mv;
uniform mat4 proj;
out vec3 vpos;
void main() {
  vec3 p = base;
  for (int k = 0; k < 4; ++k)
    if (fw[k] != 0.0) p += fw[k] * texelFetch(motion, frames[k] * nv + gl_VertexID).xyz;
  gl_ClipDistance[0] = dot(clip_plane, vec4(p, 1.0));
  vec4 q = mv * vec4(p, 1.0);
  vpos = q.xyz;
  gl_Position = proj * q;
}
)";

//! GL objects of the decoded frames. Plain data; release with release_mesh_frames.
struct MeshFramesBuffers {
  GLuint vbo = 0, ebo = 0, tbo = 0, tex = 0;
  std::size_t vertex_count = 0;
  std::size_t index_count = 0;
  std::size_t bytes = 0;  //!< uploaded once
};

//! Uploads `seq` (positions relative to `center`) into the vertex array bound now: frame 0 as attribute
//! 0, the triangles as its element buffer, the displacements as a texture buffer. Throws through gl_fail
//! when the frames exceed the driver's texture buffer size.
MeshFramesBuffers upload_mesh_frames(const MeshSequence& seq, const Vec3& center, const GlFailure& failure);

//! Deletes the GL objects (the context must be current) and zeroes `b`.
void release_mesh_frames(MeshFramesBuffers& b);

//! Binds the motion texture to `unit` and sets the uniforms of kMeshFramesVertex in `program` (in use).
void set_mesh_frames_uniforms(GLuint program, const MeshFramesBuffers& b, const FrameBlend& blend, int unit,
                              const GLfloat clip_plane[4]);

}  // namespace c4d
