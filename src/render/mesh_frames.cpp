// The decoded frames of a 4D mesh on the GPU (mesh_frames_internal.h).
#include "mesh_frames_internal.h"

#include <string>
#include <vector>

namespace c4d {

MeshFramesBuffers upload_mesh_frames(const MeshSequence& seq, const Vec3& center, const GlFailure& failure) {
  MeshFramesBuffers b;
  const std::size_t nv = seq.positions.at(0).size(), nf = seq.positions.size();
  GLint max_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  if (nf * nv > static_cast<std::size_t>(max_texels))
    gl_fail(failure, std::to_string(nf) + " frames of " + std::to_string(nv) + " vertices exceed the driver's " +
                         std::to_string(max_texels) +
                         " texels of motion (fewer frames: contour4d pack --resample N; or render --classical)");
  std::vector<float> base(nv * 3), motion(nf * nv * 3);
  for (std::size_t v = 0; v < nv; ++v)
    for (int c = 0; c < 3; ++c) base[3 * v + c] = static_cast<float>(seq.positions[0][v][c] - center[c]);
  for (std::size_t f = 0; f < nf; ++f)
    for (std::size_t v = 0; v < nv; ++v)
      for (int c = 0; c < 3; ++c)
        motion[(f * nv + v) * 3 + c] = static_cast<float>(seq.positions[f][v][c] - seq.positions[0][v][c]);
  b.vertex_count = nv;
  b.index_count = seq.triangles.size() * 3;
  glGenBuffers(1, &b.vbo);
  glBindBuffer(GL_ARRAY_BUFFER, b.vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(base.size() * 4), base.data(), GL_STATIC_DRAW);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 12, nullptr);
  glEnableVertexAttribArray(0);
  glGenBuffers(1, &b.ebo);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, b.ebo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(b.index_count * 4), seq.triangles.data(),
               GL_STATIC_DRAW);
  glGenBuffers(1, &b.tbo);
  glBindBuffer(GL_TEXTURE_BUFFER, b.tbo);
  glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(motion.size() * 4), motion.data(), GL_STATIC_DRAW);
  glGenTextures(1, &b.tex);
  glBindTexture(GL_TEXTURE_BUFFER, b.tex);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGB32F, b.tbo);
  b.bytes = (base.size() + motion.size() + b.index_count) * 4;
  return b;
}

void release_mesh_frames(MeshFramesBuffers& b) {
  const GLuint bufs[] = {b.vbo, b.ebo, b.tbo};
  for (GLuint id : bufs)
    if (id) glDeleteBuffers(1, &id);
  if (b.tex) glDeleteTextures(1, &b.tex);
  b = {};
}

void set_mesh_frames_uniforms(GLuint program, const MeshFramesBuffers& b, const FrameBlend& blend, int unit,
                              const GLfloat clip_plane[4]) {
  glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
  glBindTexture(GL_TEXTURE_BUFFER, b.tex);
  glUniform1i(glGetUniformLocation(program, "motion"), unit);
  glUniform1i(glGetUniformLocation(program, "nv"), static_cast<GLint>(b.vertex_count));
  glUniform4iv(glGetUniformLocation(program, "frames"), 1, blend.id);
  glUniform4fv(glGetUniformLocation(program, "fw"), 1, blend.w);
  glUniform4fv(glGetUniformLocation(program, "clip_plane"), 1, clip_plane);
}

}  // namespace c4d
