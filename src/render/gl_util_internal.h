#pragma once
// OpenGL helpers shared by the headless renderer (renderer.cpp) and the tessellation pipeline
// (patch_renderer.cpp): program building, the shaded fragment stage, view matrices, scene bounds,
// and the blend of frames for a time. Private to src/render; GL entry points come from glvnd's
// libOpenGL, which dispatches to whatever context is current.
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

#include <array>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "contour4d/core/vec.h"
#include "contour4d/temporal/interpolate.h"

namespace c4d {

using Mat4 = std::array<float, 16>;  //!< column-major, as glUniformMatrix4fv takes it

//! What a GL failure throws: the c4d::Error (ErrorCode::Internal) message starts with `prefix`
//! and carries `hint`.
struct GlFailure {
  const char* prefix;  //!< e.g. "headless OpenGL: "
  const char* hint;    //!< what to install or try
};

//! Throws the c4d::Error of `failure` for `what`.
[[noreturn]] void gl_fail(const GlFailure& failure, const std::string& what);

//! Compiles the stages (type, source) and links them into a program; on failure throws through
//! gl_fail with the driver's log, the message naming `name` when it is not null.
GLuint link_program(std::initializer_list<std::pair<GLenum, const char*>> stages, const char* name,
                    const GlFailure& failure);

//! Vertex stage of plain meshes: `pos` (attribute 0) through uniforms `mv` and `proj`, with `vpos`
//! (view space) out for kShadedFragment.
inline constexpr const char* kPlainVertex = R"(#version 430 core
layout(location = 0) in vec3 pos;
uniform mat4 mv;
uniform mat4 proj;
out vec3 vpos;
void main() {
  vec4 p = mv * vec4(pos, 1.0);
  vpos = p.xyz;
  gl_Position = proj * p;
}
)";

//! Fragment stage shared by all shaded programs: `vpos` (view space) in, Lambert shading by a
//! headlight from screen-space derivatives, uniform `color`; `wire` != 0 draws dark lines instead
//! (uniforms start at 0, so programs that never set it shade only).
inline constexpr const char* kShadedFragment = R"(#version 430 core
in vec3 vpos;
uniform vec3 color;
uniform int wire;
out vec4 frag;
void main() {
  if (wire != 0) { frag = vec4(0.08, 0.08, 0.1, 1.0); return; }
  vec3 n = normalize(cross(dFdx(vpos), dFdy(vpos)));
  float lambert = abs(n.z);  // headlight along the view axis
  frag = vec4(color * (0.15 + 0.85 * lambert), 1.0);
}
)";

//! Fragment stage of lines and overlays: uniform `color`, unshaded.
inline constexpr const char* kFlatFragment = R"(#version 430 core
uniform vec3 color;
out vec4 frag;
void main() { frag = vec4(color, 1.0); }
)";

//! View matrix of a camera at `eye` looking along unit `d`, with unit `side` and `up` (right-handed).
Mat4 view_matrix(const Vec3& side, const Vec3& up, const Vec3& d, const Vec3& eye);

//! Axis-aligned bounds (lo, hi) of every point of every frame.
std::pair<Vec3, Vec3> frame_bounds(const std::vector<std::vector<Vec3>>& frames);

//! glUseProgram(p) and its `mv` and `proj` uniforms.
void use_program(GLuint p, const Mat4& mv, const Mat4& proj);

//! Up to four frames and their weights for one time, as the vertex stages take them (`frames`, `fw`).
struct FrameBlend {
  GLint id[4] = {0, 0, 0, 0};   //!< frame indices
  GLfloat w[4] = {0, 0, 0, 0};  //!< their weights (Step: one, Linear: two, Catmull-Rom: four)
  std::size_t nearest = 0;      //!< the frame nearest in time
};

//! The frames blended at `t_ms` (times of the frames in ms) for `mode`.
FrameBlend blend_frames(const std::vector<double>& times_ms, double t_ms, TimeInterpolation mode);

}  // namespace c4d
