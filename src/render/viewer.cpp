// The interactive window of `contour4d view`: GLFW for the window and input, the shared pipeline
// (patch_renderer.cpp) for the drawing, so what the window shows is what `contour4d view --snapshot`
// writes headless: the decoded frames as `contour4d render` draws them, or the tessellated patches
// (Miara et al. §III.E: interpolated display of the 4D mesh between time steps, on the GPU), with the
// overlay. Built only when CMake finds glfw3 (libglfw3-dev).
#include "contour4d/render/viewer.h"

#include <string>

#include "contour4d/core/errors.h"

#ifdef C4D_HAVE_GLFW
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include <fmt/core.h>
#endif

namespace c4d {

#ifndef C4D_HAVE_GLFW

bool viewer_available() { return false; }

void run_viewer(const MeshSequence&, const Sequence*, const ViewerOptions&) {
  throw Error(ErrorCode::NotImplemented, {}, "this contour4d was built without GLFW, so `view` has no window",
              "install libglfw3-dev (scripts/setup.sh) and rebuild; headless: contour4d view INPUT --snapshot v.png");
}

#else

namespace {

// Window state touched by the GLFW callbacks (through the user pointer).
struct ViewerState {
  PatchDrawState draw;
  double speed = 1.0;
  bool playing = true;
  double t = 0.0;  // ms since the first frame
  double period = 1.0;
  std::vector<double> times;
  std::size_t slices = 0;
  bool dragging = false;
  double last_x = 0, last_y = 0;
  OrbitCamera home;
};

void step_frame(ViewerState& s, int dir) {
  // Jump to the previous/next frame time, wrapping over the cycle.
  const std::size_t n = s.times.size();
  const double rel = std::fmod(s.t, s.period);
  std::size_t i = 0;
  while (i + 1 < n && s.times[i + 1] - s.times[0] <= rel + 1e-9) ++i;
  const std::size_t next = dir > 0 ? (i + 1) % n : (i + n - 1) % n;
  s.t = s.times[next] - s.times[0];
  s.playing = false;
}

void on_key(GLFWwindow* w, int key, int, int action, int) {
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  auto& s = *static_cast<ViewerState*>(glfwGetWindowUserPointer(w));
  switch (key) {
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q:
      glfwSetWindowShouldClose(w, GLFW_TRUE);
      break;
    case GLFW_KEY_SPACE:
      s.playing = !s.playing;
      break;
    case GLFW_KEY_RIGHT:
      step_frame(s, +1);
      break;
    case GLFW_KEY_LEFT:
      step_frame(s, -1);
      break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
      s.speed = std::min(s.speed * 1.5, 50.0);
      break;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
      s.speed = std::max(s.speed / 1.5, 0.02);
      break;
    case GLFW_KEY_RIGHT_BRACKET:
      s.draw.level = std::min(s.draw.level + 1, 64);
      break;
    case GLFW_KEY_LEFT_BRACKET:
      s.draw.level = std::max(s.draw.level - 1, 1);
      break;
    case GLFW_KEY_W:
      s.draw.wireframe = !s.draw.wireframe;
      break;
    case GLFW_KEY_D:
      s.draw.displaced = !s.draw.displaced;
      break;
    case GLFW_KEY_T:
      s.draw.mesh = !s.draw.mesh;
      break;
    case GLFW_KEY_H:
      s.draw.hud = !s.draw.hud;
      break;
    case GLFW_KEY_S:
      s.draw.section = !s.draw.section;
      break;
    case GLFW_KEY_I:
      s.draw.interpolation = s.draw.interpolation == TimeInterpolation::Linear ? TimeInterpolation::CatmullRomPeriodic
                                                                               : TimeInterpolation::Linear;
      break;
    case GLFW_KEY_COMMA:
    case GLFW_KEY_PERIOD:
      if (s.slices > 0) {
        const int cur = s.draw.section_slice < 0 ? static_cast<int>(s.slices / 2) : s.draw.section_slice;
        s.draw.section_slice = std::clamp(cur + (key == GLFW_KEY_PERIOD ? 1 : -1), 0, static_cast<int>(s.slices) - 1);
      }
      break;
    case GLFW_KEY_R:
      s.draw.camera = s.home;
      break;
    default:
      break;
  }
}

void on_button(GLFWwindow* w, int button, int action, int) {
  auto& s = *static_cast<ViewerState*>(glfwGetWindowUserPointer(w));
  if (button != GLFW_MOUSE_BUTTON_LEFT) return;
  s.dragging = action == GLFW_PRESS;
  glfwGetCursorPos(w, &s.last_x, &s.last_y);
}

void on_cursor(GLFWwindow* w, double x, double y) {
  auto& s = *static_cast<ViewerState*>(glfwGetWindowUserPointer(w));
  if (!s.dragging) return;
  s.draw.camera.yaw_deg -= 0.4 * (x - s.last_x);
  s.draw.camera.pitch_deg = std::clamp(s.draw.camera.pitch_deg + 0.4 * (y - s.last_y), -85.0, 85.0);
  s.last_x = x;
  s.last_y = y;
}

void on_scroll(GLFWwindow* w, double, double dy) {
  auto& s = *static_cast<ViewerState*>(glfwGetWindowUserPointer(w));
  s.draw.camera.zoom = std::clamp(s.draw.camera.zoom * std::pow(0.9, dy), 0.1, 10.0);
}

struct GlfwSession {
  GlfwSession() {
    if (!glfwInit())
      throw Error(ErrorCode::NotImplemented, {}, "cannot open a window: GLFW could not initialise (no display?)",
                  "run it on a desktop (DISPLAY or WAYLAND_DISPLAY set); headless, use "
                  "`contour4d render INPUT -o DIR --tessellated` or `contour4d view INPUT --snapshot out.png`");
  }
  ~GlfwSession() { glfwTerminate(); }
  GlfwSession(const GlfwSession&) = delete;
  GlfwSession& operator=(const GlfwSession&) = delete;
};

}  // namespace

bool viewer_available() { return true; }

// Shows `message` in the overlay alone (while something slow is prepared).
void show_message(GLFWwindow* win, PatchRenderer& renderer, PatchDrawState st, const std::string& message) {
  glfwGetFramebufferSize(win, &st.width, &st.height);
  st.hud = true;
  st.hud_lines = {message};
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  renderer.draw(st);
  glfwSwapBuffers(win);
  glfwPollEvents();
}

void run_viewer(const MeshSequence& frames, const Sequence* contours, const ViewerOptions& opt) {
  GlfwSession session;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, 4);
  GLFWwindow* win = glfwCreateWindow(opt.width, opt.height, opt.title.c_str(), nullptr, nullptr);
  if (!win)
    throw Error(ErrorCode::NotImplemented, {}, "cannot open an OpenGL 4.3 core window",
                "update the graphics driver (Mesa 22+ gives 4.5 even in software: LIBGL_ALWAYS_SOFTWARE=1); "
                "headless, use `contour4d view INPUT --snapshot v.png`");
  glfwMakeContextCurrent(win);
  glfwSwapInterval(0);  // report the pipeline's rate, not the display's
  ViewerState st;
  st.draw = opt.initial;
  st.draw.hud_footer = kViewerKeys;
  st.home = st.draw.camera;
  st.speed = opt.speed;
  st.times = frames.times_ms;
  st.period = cycle_period(frames.times_ms);
  {
    auto renderer = std::make_unique<PatchRenderer>();  // destroyed while the context is current
    renderer->load_mesh(frames);
    if (contours) renderer->set_contours(*contours);
    st.slices = renderer->slice_count();
    bool patches_loaded = false;
    glfwSetWindowUserPointer(win, &st);
    glfwSetKeyCallback(win, on_key);
    glfwSetMouseButtonCallback(win, on_button);
    glfwSetCursorPosCallback(win, on_cursor);
    glfwSetScrollCallback(win, on_scroll);
    using clock = std::chrono::steady_clock;
    auto last = clock::now(), title_time = last;
    const auto start = last;
    int frames_drawn = 0;
    double fps = 0.0;
    while (!glfwWindowShouldClose(win)) {
      if (!st.draw.mesh && !patches_loaded) {  // first T: build the base mesh and its displacement maps
        PatchDrawState busy = st.draw;
        busy.mesh = true;  // the decoded frames stay on screen behind the message
        show_message(win, *renderer, busy, "building the tessellated patches (base mesh + displacement maps)...");
        renderer->load(build_patch_mesh(frames, opt.patches));
        patches_loaded = true;
        last = clock::now();
      }
      const auto now = clock::now();
      const double dt = std::chrono::duration<double, std::milli>(now - last).count();
      last = now;
      if (st.playing) st.t = std::fmod(st.t + dt * st.speed, st.period);
      glfwGetFramebufferSize(win, &st.draw.width, &st.draw.height);
      st.draw.t_ms = frames.times_ms.front() + st.t;
      st.draw.hud_lines = {fmt::format("{} x{:.2f}   {}   {:.0f} frames/s", st.playing ? "playing" : "paused", st.speed,
                                       st.draw.mesh ? "decoded frames (as render draws them)"
                                                    : fmt::format("tessellated patches, level {}{}", st.draw.level,
                                                                  st.draw.displaced ? "" : ", no maps"),
                                       fps)};
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      renderer->draw(st.draw);
      glfwSwapBuffers(win);
      glfwPollEvents();
      ++frames_drawn;
      const double since = std::chrono::duration<double>(now - title_time).count();
      if (since >= 0.5) {
        fps = frames_drawn / since;
        glfwSetWindowTitle(win, fmt::format("{} | {:.1f} fps", opt.title, fps).c_str());
        frames_drawn = 0;
        title_time = now;
      }
      if (opt.max_seconds > 0 && std::chrono::duration<double>(now - start).count() > opt.max_seconds) break;
    }
  }
  glfwDestroyWindow(win);
}

#endif

}  // namespace c4d
