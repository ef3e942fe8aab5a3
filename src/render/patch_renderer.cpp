// Tessellated playback of a base mesh with per-frame displacement maps (Miara et al. §III.E and
// Table II: the GPU receives the base mesh and the displacement maps once and refines them with
// the tessellation unit). PN patches: Vlachos et al. 2001; the evaluation repeats patch_point in
// src/temporal/displacement_map.cpp so that the CPU and the GPU draw the same surface.
//
// Corner data and maps live in texture buffers indexed by frame, so a new time costs two uniform
// vectors (up to four frames and their weights). GL entry points come from glvnd's libOpenGL, which
// dispatches to whatever context is current (EGL offscreen, or GLX under GLFW).
#include "contour4d/render/patch_renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include <fmt/core.h>

#include "contour4d/core/errors.h"
#include "gl_util_internal.h"
#include "hud_internal.h"
#include "mesh_frames_internal.h"

namespace c4d {
namespace {

const GlFailure kFailure{"OpenGL tessellation pipeline: ",
                         "needs OpenGL 4.3 core with tessellation shaders (Mesa llvmpipe 22+ or a GPU driver)"};

[[noreturn]] void fail(const std::string& what) { gl_fail(kFailure, what); }

const char* kVertex = R"(#version 430 core
uniform samplerBuffer corners;  // texel 2 (frame * nb + v): position, +1: normal
uniform usamplerBuffer tri_corners;  // base vertex of corner gl_VertexID (3 per triangle)
uniform int nb;
uniform ivec4 frames;
uniform vec4 fw;
out vec3 vp;
out vec3 vn;
out int vtri;
void main() {
  // Patches are drawn unindexed: the triangle id travels with its corners (gl_PrimitiveID in the
  // evaluation stage is not reliable on every driver).
  int v = int(texelFetch(tri_corners, gl_VertexID).r);
  vtri = gl_VertexID / 3;
  vec3 p = vec3(0.0), n = vec3(0.0);
  for (int k = 0; k < 4; ++k) {
    if (fw[k] == 0.0) continue;
    int o = 2 * (frames[k] * nb + v);
    p += fw[k] * texelFetch(corners, o).xyz;
    n += fw[k] * texelFetch(corners, o + 1).xyz;
  }
  float l = length(n);
  vp = p;
  vn = l > 0.0 ? n / l : vec3(0.0, 0.0, 1.0);
}
)";

const char* kControl = R"(#version 430 core
layout(vertices = 3) out;
in vec3 vp[];
in vec3 vn[];
in int vtri[];
out vec3 tp[];
out vec3 tn[];
out int ttri[];
patch out vec3 b01, b10, b12, b21, b20, b02, b111;  // PN control points, once per patch
uniform float level;
vec3 b(int i, int j) { return (2.0 * vp[i] + vp[j] - dot(vp[j] - vp[i], vn[i]) * vn[i]) / 3.0; }
void main() {
  tp[gl_InvocationID] = vp[gl_InvocationID];
  tn[gl_InvocationID] = vn[gl_InvocationID];
  ttri[gl_InvocationID] = vtri[gl_InvocationID];
  if (gl_InvocationID == 0) {
    b01 = b(0, 1); b10 = b(1, 0); b12 = b(1, 2); b21 = b(2, 1); b20 = b(2, 0); b02 = b(0, 2);
    vec3 E = (b01 + b10 + b12 + b21 + b20 + b02) / 6.0;
    vec3 V = (vp[0] + vp[1] + vp[2]) / 3.0;
    b111 = E + 0.5 * (E - V);
    gl_TessLevelOuter[0] = level;
    gl_TessLevelOuter[1] = level;
    gl_TessLevelOuter[2] = level;
    gl_TessLevelInner[0] = level;
  }
}
)";

const char* kEvaluation = R"(#version 430 core
layout(triangles, equal_spacing, ccw) in;
in vec3 tp[];
in vec3 tn[];
in int ttri[];
patch in vec3 b01, b10, b12, b21, b20, b02, b111;
uniform samplerBuffer disp;  // texel (frame * nt + triangle) * S + lattice sample
uniform int grid;
uniform int nt;
uniform ivec4 frames;
uniform vec4 fw;
uniform int displaced;
uniform int clip;
uniform vec4 clip_plane;
uniform mat4 mv;
uniform mat4 proj;
out vec3 vpos;
out float gl_ClipDistance[1];
int sidx(int i, int j) { return j * (grid + 1) - j * (j - 1) / 2 + i; }
float d(int o, int i, int j) { return texelFetch(disp, o + sidx(i, j)).r; }
float lattice(int o, float b1, float b2) {
  float x = clamp(b1, 0.0, 1.0) * float(grid), y = clamp(b2, 0.0, 1.0) * float(grid);
  int i = min(int(floor(x)), grid), j = min(int(floor(y)), grid);
  if (i + j >= grid) { i = max(0, grid - j); return d(o, i, j); }
  float fx = x - float(i), fy = y - float(j);
  if (fx + fy <= 1.0) return (1.0 - fx - fy) * d(o, i, j) + fx * d(o, i + 1, j) + fy * d(o, i, j + 1);
  return (fx + fy - 1.0) * d(o, i + 1, j + 1) + (1.0 - fy) * d(o, i + 1, j) + (1.0 - fx) * d(o, i, j + 1);
}
void main() {
  vec3 w = gl_TessCoord;
  vec3 p = w.x * w.x * w.x * tp[0] + w.y * w.y * w.y * tp[1] + w.z * w.z * w.z * tp[2] +
           3.0 * (w.x * w.x * w.y * b01 + w.y * w.y * w.x * b10 + w.y * w.y * w.z * b12 +
                  w.z * w.z * w.y * b21 + w.z * w.z * w.x * b20 + w.x * w.x * w.z * b02) +
           6.0 * w.x * w.y * w.z * b111;
  vec3 n = w.x * tn[0] + w.y * tn[1] + w.z * tn[2];
  float l = length(n);
  n = l > 0.0 ? n / l : vec3(0.0, 0.0, 1.0);
  if (displaced != 0) {
    int S = (grid + 1) * (grid + 2) / 2;
    float s = 0.0;
    for (int k = 0; k < 4; ++k)
      if (fw[k] != 0.0) s += fw[k] * lattice((frames[k] * nt + ttri[0]) * S, w.y, w.z);
    p += s * n;
  }
  gl_ClipDistance[0] = clip != 0 ? dot(clip_plane, vec4(p, 1.0)) : 1.0;
  vec4 q = mv * vec4(p, 1.0);
  vpos = q.xyz;
  gl_Position = proj * q;
}
)";

}  // namespace

struct PatchRenderer::Impl {
  GLuint patch_prog = 0, line_prog = 0, mesh_prog = 0;
  GLuint mesh_vao = 0;
  MeshFramesBuffers mesh;
  std::vector<double> mesh_times, volumes_ml;  // the decoded frames' times and volumes (overlay curve)
  std::unique_ptr<Hud> hud;
  bool has_center = false;  // the first load fixes the centre every upload is relative to
  GLuint vao = 0, ebo = 0, corner_buf = 0, corner_tex = 0, disp_buf = 0, disp_tex = 0, tri_tex = 0;
  GLuint line_vao = 0, line_vbo = 0, query = 0;
  std::size_t nb = 0, nt = 0, index_count = 0, bytes = 0;
  int grid = 1;
  std::vector<double> times;
  Vec3 center{};
  double radius = 1.0;
  // Contours: per frame, per slice index (sorted by offset), the (first, count) of each loop.
  Vec3 slice_normal{0, 0, 1};
  std::vector<double> slice_offsets;
  std::vector<std::vector<std::vector<std::pair<GLint, GLsizei>>>> loops;
  Mat4 mv{}, proj{};

  void camera(const PatchDrawState& s) {
    const double pi = std::numbers::pi;
    const double yaw = s.camera.yaw_deg * pi / 180.0, pitch = std::clamp(s.camera.pitch_deg, -85.0, 85.0) * pi / 180.0;
    const Vec3 e{std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch)};
    const double fov = 30.0 * pi / 180.0;
    const double dist = radius / std::sin(fov / 2) * 1.05 * std::max(s.camera.zoom, 0.05);
    const Vec3 eye = dist * e, d = -1.0 * e;  // positions are uploaded relative to the centre
    const Vec3 side = normalized(cross(d, Vec3{0, 0, 1}));
    const Vec3 up = cross(side, d);
    mv = view_matrix(side, up, d, eye);
    const float aspect = float(std::max(s.width, 1)) / float(std::max(s.height, 1));
    const float n = float(std::max(dist - 1.5 * radius, 0.01 * radius)), fa = float(dist + 1.5 * radius);
    const float f = float(1.0 / std::tan(fov / 2));
    const float fx = aspect >= 1 ? f / aspect : f, fy = aspect >= 1 ? f : f * aspect;
    proj = {fx, 0, 0, 0, 0, fy, 0, 0, 0, 0, -(fa + n) / (fa - n), -1, 0, 0, -2 * fa * n / (fa - n), 0};
  }

  void set_uniforms(GLuint p) { use_program(p, mv, proj); }

  void draw_patches(const PatchDrawState& st, const FrameBlend& fr, bool section, const GLfloat plane[4]);
  void draw_mesh(const PatchDrawState& st, const FrameBlend& fr, const GLfloat* plane);

  void fit(const std::vector<std::vector<Vec3>>& frames) {
    if (has_center) return;
    const auto [lo, hi] = frame_bounds(frames);
    center = 0.5 * (lo + hi);
    radius = std::max(0.5 * norm(hi - lo), 1e-6);
    has_center = true;
  }

  void draw_overlay(const PatchDrawState& st, const FrameBlend& fr) {
    HudContent c;
    const std::vector<double>& t = mesh_times.empty() ? times : mesh_times;
    c.lines.push_back(fmt::format(
        "t = {:.0f} ms   frame {} of {}{}", st.t_ms - (t.empty() ? 0.0 : t.front()), fr.nearest + 1, t.size(),
        volumes_ml.size() > fr.nearest ? fmt::format("   volume {:.1f} ml", volumes_ml[fr.nearest]) : std::string()));
    c.lines.insert(c.lines.end(), st.hud_lines.begin(), st.hud_lines.end());
    c.footer = st.hud_footer;
    c.times_ms = mesh_times;
    c.volumes_ml = volumes_ml;
    c.t_ms = st.t_ms;
    hud->draw(c, st.width, st.height);
  }
};

PatchRenderer::PatchRenderer() : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.patch_prog = link_program({{GL_VERTEX_SHADER, kVertex},
                               {GL_TESS_CONTROL_SHADER, kControl},
                               {GL_TESS_EVALUATION_SHADER, kEvaluation},
                               {GL_FRAGMENT_SHADER, kShadedFragment}},
                              "patch", kFailure);
  s.line_prog =
      link_program({{GL_VERTEX_SHADER, kPlainVertex}, {GL_FRAGMENT_SHADER, kFlatFragment}}, "contour line", kFailure);
  s.mesh_prog = link_program({{GL_VERTEX_SHADER, kMeshFramesVertex}, {GL_FRAGMENT_SHADER, kShadedFragment}},
                             "decoded frames", kFailure);
  s.hud = std::make_unique<Hud>(kFailure);
  glGenVertexArrays(1, &s.vao);
  glGenVertexArrays(1, &s.line_vao);
  glGenVertexArrays(1, &s.mesh_vao);
  glGenQueries(1, &s.query);
}

PatchRenderer::~PatchRenderer() {
  Impl& s = *impl_;
  const GLuint bufs[] = {s.ebo, s.corner_buf, s.disp_buf, s.line_vbo};
  for (GLuint b : bufs)
    if (b) glDeleteBuffers(1, &b);
  const GLuint texs[] = {s.corner_tex, s.disp_tex, s.tri_tex};
  for (GLuint t : texs)
    if (t) glDeleteTextures(1, &t);
  release_mesh_frames(s.mesh);
  s.hud.reset();
  glDeleteVertexArrays(1, &s.vao);
  glDeleteVertexArrays(1, &s.line_vao);
  glDeleteVertexArrays(1, &s.mesh_vao);
  glDeleteQueries(1, &s.query);
  glDeleteProgram(s.patch_prog);
  glDeleteProgram(s.line_prog);
  glDeleteProgram(s.mesh_prog);
}

void PatchRenderer::load(const PatchMesh& pm) {
  Impl& s = *impl_;
  if (pm.triangles.empty() || pm.positions.empty() || pm.normals.size() != pm.positions.size() || pm.grid < 1)
    throw InvalidInput(ErrorCode::BadMesh, {}, "empty patch mesh", "build it with build_patch_mesh from a 4D mesh");
  s.nb = pm.positions[0].size();
  s.nt = pm.triangles.size();
  s.grid = pm.grid;
  s.times = pm.times_ms;
  const std::size_t nf = pm.positions.size();
  s.fit(pm.positions);
  std::vector<float> corners(nf * s.nb * 8);
  for (std::size_t f = 0; f < nf; ++f)
    for (std::size_t v = 0; v < s.nb; ++v) {
      float* c = corners.data() + (f * s.nb + v) * 8;
      for (int i = 0; i < 3; ++i) {
        c[i] = static_cast<float>(pm.positions[f][v][i] - s.center[i]);
        c[4 + i] = static_cast<float>(pm.normals[f][v][i]);
      }
    }
  std::vector<std::uint32_t> idx;
  idx.reserve(s.nt * 3);
  for (const Triangle& t : pm.triangles) idx.insert(idx.end(), t.begin(), t.end());
  s.index_count = idx.size();
  glBindVertexArray(s.vao);
  auto texture_buffer = [](GLuint& buf, GLuint& tex, GLenum format, const void* data, std::size_t bytes) {
    if (!buf) glGenBuffers(1, &buf);
    glBindBuffer(GL_TEXTURE_BUFFER, buf);
    glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(bytes), data, GL_STATIC_DRAW);
    if (!tex) glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_BUFFER, tex);
    glTexBuffer(GL_TEXTURE_BUFFER, format, buf);
  };
  texture_buffer(s.ebo, s.tri_tex, GL_R32UI, idx.data(), idx.size() * 4);
  texture_buffer(s.corner_buf, s.corner_tex, GL_RGBA32F, corners.data(), corners.size() * 4);
  texture_buffer(s.disp_buf, s.disp_tex, GL_R32F, pm.displacement.data(), pm.displacement.size() * 4);
  s.bytes = idx.size() * 4 + corners.size() * 4 + pm.displacement.size() * 4;
  GLint max_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  if (static_cast<std::size_t>(max_texels) < pm.displacement.size())
    fail("displacement maps need " + std::to_string(pm.displacement.size()) + " texels, the driver allows " +
         std::to_string(max_texels) + " (use fewer base triangles or a smaller grid)");
}

void PatchRenderer::load_mesh(const MeshSequence& frames) {
  Impl& s = *impl_;
  if (frames.positions.empty() || frames.triangles.empty() || frames.positions[0].empty())
    throw InvalidInput(ErrorCode::BadMesh, {}, "empty mesh sequence", "nothing to draw");
  s.fit(frames.positions);
  glBindVertexArray(s.mesh_vao);
  release_mesh_frames(s.mesh);
  s.mesh = upload_mesh_frames(frames, s.center, kFailure);
  s.bytes += s.mesh.bytes;
  s.mesh_times = frames.times_ms;
  s.volumes_ml.clear();
  for (std::size_t f = 0; f < frames.positions.size(); ++f)
    s.volumes_ml.push_back(signed_volume(frames.frame(f)) / 1000.0);
}

void PatchRenderer::set_contours(const Sequence& seq) {
  Impl& s = *impl_;
  s.slice_normal = seq.normal;
  std::map<int, double> offsets;  // slice id -> offset
  for (const Frame& fr : seq.frames)
    for (const Slice& sl : fr.slices) offsets.emplace(sl.id, sl.offset);
  s.slice_offsets.clear();
  std::map<int, std::size_t> index;
  std::vector<std::pair<double, int>> sorted;
  for (const auto& [id, off] : offsets) sorted.emplace_back(off, id);
  std::sort(sorted.begin(), sorted.end());
  for (const auto& [off, id] : sorted) {
    index[id] = s.slice_offsets.size();
    s.slice_offsets.push_back(off);
  }
  std::vector<float> pts;
  s.loops.assign(seq.frames.size(), std::vector<std::vector<std::pair<GLint, GLsizei>>>(s.slice_offsets.size()));
  for (std::size_t f = 0; f < seq.frames.size(); ++f)
    for (const Slice& sl : seq.frames[f].slices)
      for (const Contour& c : sl.contours) {
        const GLint first = static_cast<GLint>(pts.size() / 3);
        for (const Vec3& p : c.points)
          for (int i = 0; i < 3; ++i) pts.push_back(static_cast<float>(p[i] - s.center[i]));
        s.loops[f][index[sl.id]].emplace_back(first, static_cast<GLsizei>(c.points.size()));
      }
  glBindVertexArray(s.line_vao);
  if (!s.line_vbo) glGenBuffers(1, &s.line_vbo);
  glBindBuffer(GL_ARRAY_BUFFER, s.line_vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(pts.size() * 4), pts.data(), GL_STATIC_DRAW);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 12, nullptr);
  glEnableVertexAttribArray(0);
  s.bytes += pts.size() * 4;
}

std::size_t PatchRenderer::slice_count() const { return impl_->slice_offsets.size(); }
std::size_t PatchRenderer::static_bytes() const { return impl_->bytes; }

std::size_t PatchRenderer::draw(const PatchDrawState& st) {
  Impl& s = *impl_;
  if (st.mesh ? s.mesh.index_count == 0 : s.index_count == 0)
    fail(st.mesh ? "draw of the decoded frames before load_mesh" : "draw of the patches before load");
  s.camera(st);
  const FrameBlend fr = blend_frames(st.mesh ? s.mesh_times : s.times, st.t_ms, st.interpolation);
  glViewport(0, 0, st.width, st.height);
  glClearColor(1, 1, 1, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  // Section plane: a slice plane of the contours (else through the centre, normal +z).
  const bool section = st.section;
  std::size_t slice = 0;
  GLfloat plane[4] = {0, 0, 1, 0};
  if (section) {
    Vec3 n = s.slice_normal;
    double off = 0.0;  // plane offset relative to the centre
    if (!s.slice_offsets.empty()) {
      slice = st.section_slice < 0
                  ? s.slice_offsets.size() / 2
                  : std::min<std::size_t>(static_cast<std::size_t>(st.section_slice), s.slice_offsets.size() - 1);
      off = s.slice_offsets[slice] - dot(s.center, n);
    }
    // Keep the half below the plane (towards the first slices), so the cut faces the camera's side.
    for (int i = 0; i < 3; ++i) plane[i] = static_cast<float>(-n[i]);
    plane[3] = static_cast<float>(off);
    glEnable(GL_CLIP_DISTANCE0);
  }
  if (st.mesh) {
    s.draw_mesh(st, fr, section ? plane : nullptr);
  } else {
    s.draw_patches(st, fr, section, plane);
  }
  if (section) glDisable(GL_CLIP_DISTANCE0);
  std::size_t uploaded = sizeof fr.id + sizeof fr.w;
  if (section && !s.loops.empty() && fr.nearest < s.loops.size() && slice < s.loops[fr.nearest].size()) {
    glDisable(GL_DEPTH_TEST);  // the contours of the section's slice over the cut
    s.set_uniforms(s.line_prog);
    const GLfloat black[3] = {0.0f, 0.35f, 0.9f};
    glUniform3fv(glGetUniformLocation(s.line_prog, "color"), 1, black);
    glBindVertexArray(s.line_vao);
    glLineWidth(3.0f);  // may be refused (forward-compatible contexts allow only 1): then thin lines
    for (const auto& [first, count] : s.loops[fr.nearest][slice]) glDrawArrays(GL_LINE_LOOP, first, count);
    glLineWidth(1.0f);
    while (glGetError() != GL_NO_ERROR) {}
    glEnable(GL_DEPTH_TEST);
  }
  if (st.hud) s.draw_overlay(st, fr);
  return uploaded;
}

void PatchRenderer::Impl::draw_patches(const PatchDrawState& st, const FrameBlend& fr, bool section,
                                       const GLfloat plane[4]) {
  Impl& s = *this;
  glUseProgram(s.patch_prog);
  s.set_uniforms(s.patch_prog);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_BUFFER, s.corner_tex);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_BUFFER, s.disp_tex);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_BUFFER, s.tri_tex);
  const GLuint p = s.patch_prog;
  glUniform1i(glGetUniformLocation(p, "tri_corners"), 2);
  glUniform1i(glGetUniformLocation(p, "corners"), 0);
  glUniform1i(glGetUniformLocation(p, "disp"), 1);
  glUniform1i(glGetUniformLocation(p, "nb"), static_cast<GLint>(s.nb));
  glUniform1i(glGetUniformLocation(p, "nt"), static_cast<GLint>(s.nt));
  glUniform1i(glGetUniformLocation(p, "grid"), s.grid);
  glUniform4iv(glGetUniformLocation(p, "frames"), 1, fr.id);
  glUniform4fv(glGetUniformLocation(p, "fw"), 1, fr.w);
  glUniform1f(glGetUniformLocation(p, "level"), static_cast<float>(std::clamp(st.level, 1, 64)));
  glUniform1i(glGetUniformLocation(p, "displaced"), st.displaced ? 1 : 0);
  glUniform1i(glGetUniformLocation(p, "clip"), section ? 1 : 0);
  glUniform4fv(glGetUniformLocation(p, "clip_plane"), 1, plane);
  glUniform3fv(glGetUniformLocation(p, "color"), 1, st.color);
  glUniform1i(glGetUniformLocation(p, "wire"), 0);
  glPatchParameteri(GL_PATCH_VERTICES, 3);
  glBindVertexArray(s.vao);
  if (st.wireframe) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
  }
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glDrawArrays(GL_PATCHES, 0, static_cast<GLsizei>(s.index_count));
  if (st.wireframe) {
    glDisable(GL_POLYGON_OFFSET_FILL);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glUniform1i(glGetUniformLocation(p, "wire"), 1);
    glDrawArrays(GL_PATCHES, 0, static_cast<GLsizei>(s.index_count));
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
}

void PatchRenderer::Impl::draw_mesh(const PatchDrawState& st, const FrameBlend& fr, const GLfloat* plane) {
  const GLfloat keep_all[4] = {0, 0, 0, 1};
  glUseProgram(mesh_prog);
  set_uniforms(mesh_prog);
  set_mesh_frames_uniforms(mesh_prog, mesh, fr, 0, plane ? plane : keep_all);
  glUniform3fv(glGetUniformLocation(mesh_prog, "color"), 1, st.color);
  glUniform1i(glGetUniformLocation(mesh_prog, "wire"), 0);
  glBindVertexArray(mesh_vao);
  if (st.wireframe) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
  }
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.index_count), GL_UNSIGNED_INT, nullptr);
  if (st.wireframe) {
    glDisable(GL_POLYGON_OFFSET_FILL);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glUniform1i(glGetUniformLocation(mesh_prog, "wire"), 1);
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.index_count), GL_UNSIGNED_INT, nullptr);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
}

std::uint64_t PatchRenderer::count_triangles(const PatchDrawState& st) {
  Impl& s = *impl_;
  PatchDrawState plain = st;
  plain.wireframe = false;
  plain.hud = false;  // the overlay's text is triangles too
  glBeginQuery(GL_PRIMITIVES_GENERATED, s.query);
  draw(plain);
  glEndQuery(GL_PRIMITIVES_GENERATED);
  GLuint64 n = 0;
  glGetQueryObjectui64v(s.query, GL_QUERY_RESULT, &n);
  return n;
}

}  // namespace c4d
