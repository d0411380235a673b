#pragma once
// On-screen text for the viewer: stb_easy_font's quads (no font texture), each line over a dark
// backdrop so it reads on white and on black scenes alike, drawn in one call.
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "gl/gl_objects.hpp"
#include "gl/shader.hpp"

namespace oitbench::viewer {

struct TextLine {
  std::string text;
  glm::u8vec4 colour{235, 235, 235, 255};
};

class TextOverlay {
 public:
  explicit TextOverlay(const ShaderLibrary& shaders);
  // Draws the lines from the top-left corner of the bound framebuffer (fb_width x fb_height
  // pixels), `scale` framebuffer pixels per font pixel; lines wider than the framebuffer wrap.
  void draw(const std::vector<TextLine>& lines, int fb_width, int fb_height, int scale);
  static int line_height(int scale) { return 12 * scale; }

 private:
  struct Vertex {
    glm::vec2 position;
    glm::u8vec4 colour;
  };
  void add_quad(glm::vec2 lo, glm::vec2 hi, glm::u8vec4 colour);
  gl::Program program_;
  gl::VertexArray vao_;
  gl::Buffer vertices_, indices_;
  size_t vertex_capacity_ = 0, index_capacity_ = 0;
  std::vector<Vertex> staged_;
  std::vector<char> scratch_;  // stb_easy_font's output
};

}  // namespace oitbench::viewer
