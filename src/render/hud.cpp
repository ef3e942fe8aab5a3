// The viewer's on-screen information (hud_internal.h): text quads from stb_easy_font and the volume curve,
// both as 2D vertices in pixels through one flat-colour program.
#include "hud_internal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/core.h>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

#include "contour4d/temporal/interpolate.h"

namespace c4d {
namespace {

const char* kHudVertex = R"(#version 430 core
layout(location = 0) in vec2 px;
uniform vec2 viewport;
void main() { gl_Position = vec4(px.x / viewport.x * 2.0 - 1.0, 1.0 - px.y / viewport.y * 2.0, 0.0, 1.0); }
)";

using Points = std::vector<float>;  // x, y pixel pairs

// The triangles of `text` drawn from (x, y) (top left of the first character), `scale` pixels per font unit.
void add_text(Points& tris, const std::string& text, float x, float y, float scale) {
  std::vector<char> buf(text.size() * 300 + 64);
  std::string copy = text;
  const int quads = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, buf.data(), static_cast<int>(buf.size()));
  for (int q = 0; q < quads; ++q) {
    float corner[4][2];
    for (int k = 0; k < 4; ++k) {  // each vertex: x, y, z floats and four colour bytes
      const char* v = buf.data() + (static_cast<std::size_t>(q) * 4 + static_cast<std::size_t>(k)) * 16;
      std::copy_n(reinterpret_cast<const float*>(v), 2, corner[k]);
    }
    for (int k : {0, 1, 2, 0, 2, 3}) {
      tris.push_back(x + scale * corner[k][0]);
      tris.push_back(y + scale * corner[k][1]);
    }
  }
}

}  // namespace

Hud::Hud(const GlFailure& failure) {
  prog_ = link_program({{GL_VERTEX_SHADER, kHudVertex}, {GL_FRAGMENT_SHADER, kFlatFragment}}, "overlay", failure);
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
}

Hud::~Hud() {
  glDeleteBuffers(1, &vbo_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteProgram(prog_);
}

void Hud::draw(const HudContent& c, int width, int height) {
  const float scale = width >= 1000 ? 2.0f : 1.0f, line = 11.0f * scale;
  Points text, box, curve, marker;
  for (std::size_t i = 0; i < c.lines.size(); ++i)
    add_text(text, c.lines[i], 8.0f, 8.0f + line * static_cast<float>(i), scale);
  if (!c.footer.empty()) add_text(text, c.footer, 8.0f, static_cast<float>(height) - line - 4.0f, scale);
  if (c.volumes_ml.size() >= 2 && c.volumes_ml.size() == c.times_ms.size()) {
    // The cycle's volume curve in a box at the bottom right; the current time as a vertical line.
    const float w = std::min(130.0f * scale, static_cast<float>(width) / 3.0f), h = w * 0.45f;
    const float x0 = static_cast<float>(width) - w - 8.0f, y0 = static_cast<float>(height) - h - 2.0f * line;
    const auto [lo_it, hi_it] = std::minmax_element(c.volumes_ml.begin(), c.volumes_ml.end());
    const double lo = *lo_it, span = std::max(*hi_it - lo, 1e-9), t0 = c.times_ms.front();
    const double period = cycle_period(c.times_ms);
    const auto px = [&](double t) { return x0 + static_cast<float>((t - t0) / period) * w; };
    const auto py = [&](double v) { return y0 + h - static_cast<float>((v - lo) / span) * h; };
    box = {x0, y0, x0 + w, y0, x0 + w, y0 + h, x0, y0 + h};
    for (std::size_t f = 0; f <= c.times_ms.size(); ++f) {  // closed over the cycle: back to frame 0
      const std::size_t i = f % c.times_ms.size();
      curve.push_back(px(f < c.times_ms.size() ? c.times_ms[i] : t0 + period));
      curve.push_back(py(c.volumes_ml[i]));
    }
    const float xm = px(t0 + std::fmod(std::fmod(c.t_ms - t0, period) + period, period));
    marker = {xm, y0, xm, y0 + h};
    add_text(text, fmt::format("volume {:.0f}-{:.0f} ml", lo, lo + span), x0, y0 - line, scale);
  }
  glDisable(GL_DEPTH_TEST);
  glUseProgram(prog_);
  glUniform2f(glGetUniformLocation(prog_, "viewport"), static_cast<float>(width), static_cast<float>(height));
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 8, nullptr);
  glEnableVertexAttribArray(0);
  const auto draw = [&](const Points& p, GLenum mode, float r, float g, float b) {
    if (p.empty()) return;
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(p.size() * 4), p.data(), GL_STREAM_DRAW);
    glUniform3f(glGetUniformLocation(prog_, "color"), r, g, b);
    glDrawArrays(mode, 0, static_cast<GLsizei>(p.size() / 2));
  };
  draw(box, GL_LINE_LOOP, 0.6f, 0.6f, 0.6f);
  draw(curve, GL_LINE_STRIP, 0.0f, 0.35f, 0.9f);
  draw(marker, GL_LINES, 0.85f, 0.1f, 0.1f);
  draw(text, GL_TRIANGLES, 0.05f, 0.05f, 0.08f);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace c4d
