// OpenGL helpers shared by the headless renderer and the tessellation pipeline (see
// gl_util_internal.h): no paper method here, only GL plumbing.
#include "gl_util_internal.h"

#include <algorithm>

#include "contour4d/core/errors.h"

namespace c4d {
namespace {

std::string named(const char* name, const char* what) {
  return (name ? std::string(name) + " " : std::string()) + what;
}

// Throws through gl_fail with the driver's log when the `status` of shader or program `object` is
// not set, deleting the object first.
void require(GLuint object, GLenum status, decltype(&glGetShaderiv) get_iv, decltype(&glGetShaderInfoLog) get_log,
             decltype(&glDeleteShader) destroy, const std::string& what, const GlFailure& failure) {
  GLint ok = 0;
  get_iv(object, status, &ok);
  if (ok) return;
  char log[4096] = {};
  get_log(object, sizeof log, nullptr, log);
  destroy(object);
  gl_fail(failure, what + log);
}

GLuint compile(GLenum type, const char* src, const char* name, const GlFailure& failure) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  require(s, GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog, glDeleteShader,
          named(name, "shader compilation failed: "), failure);
  return s;
}

}  // namespace

void gl_fail(const GlFailure& failure, const std::string& what) {
  throw Error(ErrorCode::Internal, {}, failure.prefix + what, failure.hint);
}

GLuint link_program(std::initializer_list<std::pair<GLenum, const char*>> stages, const char* name,
                    const GlFailure& failure) {
  const GLuint p = glCreateProgram();
  std::vector<GLuint> shaders;
  for (const auto& [type, src] : stages) {
    shaders.push_back(compile(type, src, name, failure));
    glAttachShader(p, shaders.back());
  }
  glLinkProgram(p);
  for (GLuint s : shaders) glDeleteShader(s);
  require(p, GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog, glDeleteProgram, named(name, "program link failed: "),
          failure);
  return p;
}

Mat4 view_matrix(const Vec3& side, const Vec3& up, const Vec3& d, const Vec3& eye) {
  return {
      float(side.x), float(up.x), float(-d.x), 0, float(side.y),          float(up.y),          float(-d.y),        0,
      float(side.z), float(up.z), float(-d.z), 0, float(-dot(side, eye)), float(-dot(up, eye)), float(dot(d, eye)), 1};
}

std::pair<Vec3, Vec3> frame_bounds(const std::vector<std::vector<Vec3>>& frames) {
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const auto& f : frames)
    for (const Vec3& p : f)
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], p[c]);
        hi[c] = std::max(hi[c], p[c]);
      }
  return {lo, hi};
}

void use_program(GLuint p, const Mat4& mv, const Mat4& proj) {
  glUseProgram(p);
  glUniformMatrix4fv(glGetUniformLocation(p, "mv"), 1, GL_FALSE, mv.data());
  glUniformMatrix4fv(glGetUniformLocation(p, "proj"), 1, GL_FALSE, proj.data());
}

FrameBlend blend_frames(const std::vector<double>& times_ms, double t_ms, TimeInterpolation mode) {
  FrameBlend fr;
  const std::size_t n = times_ms.size();
  const bool periodic = mode == TimeInterpolation::CatmullRomPeriodic;
  const TimeSample ts = locate_time(times_ms, t_ms, periodic);
  fr.nearest = ts.u < 0.5 ? ts.i0 : ts.i1;
  if (mode == TimeInterpolation::Step || ts.u == 0.0) {
    fr.id[0] = static_cast<GLint>(ts.i0);
    fr.w[0] = 1;
    fr.nearest = ts.i0;
  } else if (!periodic) {
    fr.id[0] = static_cast<GLint>(ts.i0);
    fr.id[1] = static_cast<GLint>(ts.i1);
    fr.w[0] = static_cast<float>(1 - ts.u);
    fr.w[1] = static_cast<float>(ts.u);
  } else {
    double w[4];
    catmull_rom_weights(ts.u, w);
    const std::size_t ids[4] = {(ts.i0 + n - 1) % n, ts.i0, ts.i1, (ts.i1 + 1) % n};
    for (int i = 0; i < 4; ++i) {
      fr.id[i] = static_cast<GLint>(ids[i]);
      fr.w[i] = static_cast<float>(w[i]);
    }
  }
  return fr;
}

}  // namespace c4d
