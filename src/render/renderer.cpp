// Headless playback of a 4D mesh, classical against compact (Miara et al. §IV, Table II: the
// classical method sends each frame's high-resolution mesh to the GPU; the new one sends the base
// mesh and displacement data once and only selects the time per frame).
//
// The context comes from EGL without a window: EGL_EXT_platform_device first (a GPU, or Mesa's
// software device), then EGL_MESA_platform_surfaceless, then the default display; all GL entry points
// come from glvnd's libOpenGL. Normals come from screen-space derivatives, so both paths shade alike.
#include "contour4d/render/renderer.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>

#include "contour4d/core/errors.h"
#include "gl_util_internal.h"
#include "mesh_frames_internal.h"

namespace c4d {
namespace {

const GlFailure kFailure{"headless OpenGL: ",
                         "needs EGL with OpenGL 4.3 core: install Mesa (libegl-mesa0, libgl1-mesa-dri) and try "
                         "LIBGL_ALWAYS_SOFTWARE=1 EGL_PLATFORM=surfaceless; on a GPU check its EGL driver"};

[[noreturn]] void fail(const std::string& what) { gl_fail(kFailure, what); }

}  // namespace

struct OffscreenRenderer::Impl {
  RenderOptions opt;
  EGLDisplay dpy = EGL_NO_DISPLAY;
  EGLContext ctx = EGL_NO_CONTEXT;
  GLuint fbo = 0, color = 0, depth = 0;
  GLuint classical_prog = 0, compact_prog = 0;
  GLuint vao = 0, vbo = 0, ebo = 0;  // classical
  MeshFramesBuffers compact;
  std::size_t index_count = 0;
  MeshSequence frames;  // classical: all frames on the CPU
  std::vector<float> staging;
  std::vector<double> times;  // compact
  Mat4 mv{}, proj{};
  Vec3 center{};
  std::unique_ptr<PatchRenderer> patches;  // created on first use, destroyed before the context

  void fit_camera(const std::vector<std::vector<Vec3>>& all) {
    const auto [lo, hi] = frame_bounds(all);
    center = 0.5 * (lo + hi);
    const double r = std::max(0.5 * norm(hi - lo), 1e-6);
    const Vec3 d = normalized(opt.view_direction);
    Vec3 up{0, 0, 1};  // superior up
    if (std::abs(dot(up, d)) > 0.99) up = {0, -1, 0};
    const Vec3 s = normalized(cross(d, up));
    const Vec3 u = cross(s, d);
    const Vec3 eye = -2.5 * r * d;  // positions are uploaded relative to the centre
    mv = view_matrix(s, u, d, eye);
    const float aspect = float(opt.width) / float(opt.height);
    const float n = float(1.5 * r * 0.5), fa = float(3.5 * r + r);
    const float hr = float(r * 1.05);
    if (opt.perspective) {
      const float t = hr / float(2.5 * r) * n * 1.1f;
      proj = {n / (t * aspect),       0, 0, 0, 0, n / t, 0, 0, 0, 0, -(fa + n) / (fa - n), -1, 0, 0,
              -2 * fa * n / (fa - n), 0};
    } else {
      proj = {1.0f / (hr * aspect), 0, 0, 0, 0, 1.0f / hr, 0, 0, 0, 0, -2.0f / (fa - n), 0, 0, 0,
              -(fa + n) / (fa - n), 1};
    }
  }

  void set_common(GLuint prog) {
    use_program(prog, mv, proj);
    glUniform3fv(glGetUniformLocation(prog, "color"), 1, opt.color);
  }

  void reset_buffers() {
    const GLuint bufs[] = {vbo, ebo};
    for (GLuint b : bufs)
      if (b) glDeleteBuffers(1, &b);
    vbo = ebo = 0;
    release_mesh_frames(compact);
    if (vao) glDeleteVertexArrays(1, &vao);
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
  }

  void begin_frame() {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, opt.width, opt.height);
    glClearColor(1, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  }
};

OffscreenRenderer::OffscreenRenderer(const RenderOptions& options) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.opt = options;
  if (options.width <= 0 || options.height <= 0 || options.width > 16384 || options.height > 16384)
    throw InvalidInput(ErrorCode::Usage, {}, "image size out of range", "use e.g. --size 640x480");
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  std::vector<EGLDisplay> candidates;
  if (get_platform_display && query_devices) {
    EGLDeviceEXT devices[8];
    EGLint n = 0;
    if (query_devices(8, devices, &n))
      for (EGLint i = 0; i < n; ++i)
        candidates.push_back(get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr));
  }
  if (get_platform_display)
    candidates.push_back(get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
  candidates.push_back(eglGetDisplay(EGL_DEFAULT_DISPLAY));
  std::string tried;
  for (EGLDisplay d : candidates) {
    if (d == EGL_NO_DISPLAY) continue;
    EGLint major = 0, minor = 0;
    if (!eglInitialize(d, &major, &minor)) continue;
    if (!eglBindAPI(EGL_OPENGL_API)) {
      eglTerminate(d);
      continue;
    }
    const EGLint cfg_attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig cfg = nullptr;
    EGLint ncfg = 0;
    eglChooseConfig(d, cfg_attr, &cfg, 1, &ncfg);
    const EGLint ctx_attr[] = {
        EGL_CONTEXT_MAJOR_VERSION,           4,       EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext c = eglCreateContext(d, ncfg > 0 ? cfg : nullptr, EGL_NO_CONTEXT, ctx_attr);
    if (c != EGL_NO_CONTEXT && eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) {
      s.dpy = d;
      s.ctx = c;
      break;
    }
    tried += " (EGL error 0x" + std::to_string(eglGetError()) + ")";
    if (c != EGL_NO_CONTEXT) eglDestroyContext(d, c);
    eglTerminate(d);
  }
  if (s.ctx == EGL_NO_CONTEXT) fail("no EGL display could create an OpenGL 4.3 core context" + tried);

  glGenFramebuffers(1, &s.fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, s.fbo);
  glGenRenderbuffers(1, &s.color);
  glBindRenderbuffer(GL_RENDERBUFFER, s.color);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, options.width, options.height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, s.color);
  glGenRenderbuffers(1, &s.depth);
  glBindRenderbuffer(GL_RENDERBUFFER, s.depth);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, options.width, options.height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, s.depth);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) fail("framebuffer incomplete");
  glEnable(GL_DEPTH_TEST);
  s.classical_prog =
      link_program({{GL_VERTEX_SHADER, kPlainVertex}, {GL_FRAGMENT_SHADER, kShadedFragment}}, nullptr, kFailure);
  s.compact_prog =
      link_program({{GL_VERTEX_SHADER, kMeshFramesVertex}, {GL_FRAGMENT_SHADER, kShadedFragment}}, nullptr, kFailure);
}

OffscreenRenderer::~OffscreenRenderer() {
  Impl& s = *impl_;
  if (s.ctx != EGL_NO_CONTEXT) {
    s.patches.reset();
    s.reset_buffers();
    glDeleteVertexArrays(1, &s.vao);
    glDeleteProgram(s.classical_prog);
    glDeleteProgram(s.compact_prog);
    glDeleteRenderbuffers(1, &s.color);
    glDeleteRenderbuffers(1, &s.depth);
    glDeleteFramebuffers(1, &s.fbo);
    eglMakeCurrent(s.dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(s.dpy, s.ctx);
    eglTerminate(s.dpy);
    eglReleaseThread();
  }
}

std::string OffscreenRenderer::description() const {
  const auto* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(r ? r : "?") + ", OpenGL " + (v ? v : "?");
}

void OffscreenRenderer::load_classical(const MeshSequence& seq) { load_classical(seq, seq); }

void OffscreenRenderer::load_classical(const MeshSequence& seq, const MeshSequence& camera) {
  Impl& s = *impl_;
  if (seq.positions.empty() || seq.triangles.empty() || camera.positions.empty())
    throw InvalidInput(ErrorCode::BadMesh, {}, "empty mesh sequence", "nothing to draw");
  s.fit_camera(camera.positions);
  s.frames = seq;
  s.reset_buffers();
  const std::size_t nv = seq.positions[0].size();
  glGenBuffers(1, &s.vbo);
  glBindBuffer(GL_ARRAY_BUFFER, s.vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(nv * 12), nullptr, GL_STREAM_DRAW);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 12, nullptr);
  glEnableVertexAttribArray(0);
  glGenBuffers(1, &s.ebo);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, s.ebo);
  s.index_count = seq.triangles.size() * 3;
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(s.index_count * 4), nullptr, GL_STREAM_DRAW);
  s.staging.resize(nv * 3);
}

std::size_t OffscreenRenderer::draw_classical(std::size_t f) {
  Impl& s = *impl_;
  const auto& P = s.frames.positions.at(f);
  for (std::size_t v = 0; v < P.size(); ++v)
    for (int c = 0; c < 3; ++c) s.staging[3 * v + c] = static_cast<float>(P[v][c] - s.center[c]);
  glBindVertexArray(s.vao);
  glBindBuffer(GL_ARRAY_BUFFER, s.vbo);
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(s.staging.size() * 4), s.staging.data());
  // The full mesh of the frame: its triangles too, as a per-frame marching-cubes mesh would need.
  glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(s.index_count * 4), s.frames.triangles.data());
  s.begin_frame();
  s.set_common(s.classical_prog);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(s.index_count), GL_UNSIGNED_INT, nullptr);
  return s.staging.size() * 4 + s.index_count * 4;
}

void OffscreenRenderer::load_compact(const CompactModel& model) {
  Impl& s = *impl_;
  const MeshSequence seq = compact_decode(model);  // what unpack writes, on the model's grid
  s.fit_camera(seq.positions);
  s.reset_buffers();
  s.times = seq.times_ms;
  s.compact = upload_mesh_frames(seq, s.center, kFailure);
  s.index_count = s.compact.index_count;
}

std::size_t OffscreenRenderer::draw_compact(double t_ms) {
  Impl& s = *impl_;
  const FrameBlend fr = blend_frames(s.times, t_ms, s.opt.interpolation);
  glBindVertexArray(s.vao);
  s.begin_frame();
  s.set_common(s.compact_prog);
  const GLfloat keep_all[4] = {0, 0, 0, 1};
  set_mesh_frames_uniforms(s.compact_prog, s.compact, fr, 0, keep_all);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(s.index_count), GL_UNSIGNED_INT, nullptr);
  return sizeof fr.id + sizeof fr.w;
}

PatchRenderer& OffscreenRenderer::patches() {
  Impl& s = *impl_;
  if (!s.patches) s.patches = std::make_unique<PatchRenderer>();
  return *s.patches;
}

std::size_t OffscreenRenderer::draw_patches(PatchDrawState state) {
  Impl& s = *impl_;
  state.width = s.opt.width;
  state.height = s.opt.height;
  glBindFramebuffer(GL_FRAMEBUFFER, s.fbo);
  return patches().draw(state);
}

void OffscreenRenderer::finish() { glFinish(); }

Image OffscreenRenderer::read_image() {
  Impl& s = *impl_;
  Image img;
  img.width = s.opt.width;
  img.height = s.opt.height;
  img.rgba.resize(static_cast<std::size_t>(img.width) * img.height * 4);
  glBindFramebuffer(GL_FRAMEBUFFER, s.fbo);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
  const std::size_t row = static_cast<std::size_t>(img.width) * 4;
  std::vector<std::uint8_t> tmp(row);
  for (int y = 0; y < img.height / 2; ++y) {  // GL rows are bottom-up
    std::uint8_t* a = img.rgba.data() + static_cast<std::size_t>(y) * row;
    std::uint8_t* b = img.rgba.data() + static_cast<std::size_t>(img.height - 1 - y) * row;
    std::memcpy(tmp.data(), a, row);
    std::memcpy(a, b, row);
    std::memcpy(b, tmp.data(), row);
  }
  return img;
}

}  // namespace c4d
