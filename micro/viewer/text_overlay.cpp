#include "viewer/text_overlay.hpp"

#include <cstring>

#include "gl/gl.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace oitbench::viewer {

namespace {
constexpr glm::u8vec4 kBackdrop{0, 0, 0, 170};
constexpr int kPad = 3;  // font pixels of backdrop around each line
// stb_easy_font_print's vertex: x, y, z floats and RGBA8.
struct EasyFontVertex {
  float x, y, z;
  unsigned char rgba[4];
};
static_assert(sizeof(EasyFontVertex) == 16);
}  // namespace

TextOverlay::TextOverlay(const ShaderLibrary& shaders)
    : program_(shaders.build({{GL_VERTEX_SHADER, "viewer/text.vert"}, {GL_FRAGMENT_SHADER, "viewer/text.frag"}}, {})),
      vao_(gl::make_vertex_array()) {}

void TextOverlay::add_quad(glm::vec2 lo, glm::vec2 hi, glm::u8vec4 colour) {
  staged_.push_back({{lo.x, lo.y}, colour});
  staged_.push_back({{hi.x, lo.y}, colour});
  staged_.push_back({{hi.x, hi.y}, colour});
  staged_.push_back({{lo.x, hi.y}, colour});
}

namespace {
int text_width(const std::string& s) {
  std::vector<char> text(s.begin(), s.end());
  text.push_back('\0');
  return stb_easy_font_width(text.data());
}

// Lines longer than `width` font pixels break at spaces (a long path breaks anywhere), the
// continuation indented.
std::vector<TextLine> wrap(const std::vector<TextLine>& lines, int width) {
  std::vector<TextLine> out;
  for (TextLine line : lines) {
    while (text_width(line.text) > width && line.text.size() > 8) {
      size_t cut = line.text.size() - 1;
      while (cut > 8 && text_width(line.text.substr(0, cut)) > width) --cut;
      size_t space = line.text.rfind(' ', cut);
      if (space != std::string::npos && space > cut / 2) cut = space;
      out.push_back({line.text.substr(0, cut), line.colour});
      line.text = "    " + line.text.substr(line.text[cut] == ' ' ? cut + 1 : cut);
    }
    out.push_back(line);
  }
  return out;
}
}  // namespace

void TextOverlay::draw(const std::vector<TextLine>& unwrapped, int fb_width, int fb_height, int scale) {
  staged_.clear();
  const float s = static_cast<float>(scale);
  float y = kPad;
  std::vector<char> text;
  for (const auto& line : wrap(unwrapped, fb_width / scale - 2 * kPad)) {
    text.assign(line.text.begin(), line.text.end());
    text.push_back('\0');
    if (!line.text.empty()) {
      float width = static_cast<float>(stb_easy_font_width(text.data()));
      add_quad(glm::vec2(0, y - kPad) * s, glm::vec2(width + 2 * kPad, y + 12 - kPad) * s, kBackdrop);
      scratch_.resize(text.size() * 300 + 64);  // ~270 bytes per character (the header's estimate)
      unsigned char rgba[4] = {line.colour.r, line.colour.g, line.colour.b, line.colour.a};
      int quads = stb_easy_font_print(kPad, y, text.data(), rgba, scratch_.data(), static_cast<int>(scratch_.size()));
      for (int q = 0; q < quads * 4; ++q) {
        EasyFontVertex v;
        std::memcpy(&v, scratch_.data() + q * sizeof v, sizeof v);
        staged_.push_back({glm::vec2(v.x, v.y) * s, glm::u8vec4(v.rgba[0], v.rgba[1], v.rgba[2], v.rgba[3])});
      }
    }
    y += 12;
  }
  if (staged_.empty()) return;

  size_t quads = staged_.size() / 4;
  if (staged_.size() > vertex_capacity_) {
    vertex_capacity_ = staged_.size() * 2;
    vertices_ = gl::make_buffer();
    glNamedBufferStorage(vertices_.get(), static_cast<GLsizeiptr>(vertex_capacity_ * sizeof(Vertex)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    glVertexArrayVertexBuffer(vao_.get(), 0, vertices_.get(), 0, sizeof(Vertex));
    glEnableVertexArrayAttrib(vao_.get(), 0);
    glVertexArrayAttribFormat(vao_.get(), 0, 2, GL_FLOAT, GL_FALSE, offsetof(Vertex, position));
    glVertexArrayAttribBinding(vao_.get(), 0, 0);
    glEnableVertexArrayAttrib(vao_.get(), 1);
    glVertexArrayAttribFormat(vao_.get(), 1, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(Vertex, colour));
    glVertexArrayAttribBinding(vao_.get(), 1, 0);
  }
  if (quads * 6 > index_capacity_) {  // two triangles per quad, the same pattern for every quad
    index_capacity_ = quads * 6 * 2;
    std::vector<unsigned> idx(index_capacity_);
    for (size_t q = 0; q < index_capacity_ / 6; ++q) {
      unsigned b = static_cast<unsigned>(q * 4);
      unsigned tri[6] = {b, b + 1, b + 2, b, b + 2, b + 3};
      std::copy(tri, tri + 6, idx.begin() + static_cast<std::ptrdiff_t>(q * 6));
    }
    indices_ = gl::make_buffer();
    glNamedBufferStorage(indices_.get(), static_cast<GLsizeiptr>(idx.size() * sizeof(unsigned)), idx.data(), 0);
    glVertexArrayElementBuffer(vao_.get(), indices_.get());
  }
  glNamedBufferSubData(vertices_.get(), 0, static_cast<GLsizeiptr>(staged_.size() * sizeof(Vertex)), staged_.data());

  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glUseProgram(program_.get());
  glUniform2f(glGetUniformLocation(program_.get(), "viewportSize"), static_cast<float>(fb_width),
              static_cast<float>(fb_height));
  glBindVertexArray(vao_.get());
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(quads * 6), GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
  glDisable(GL_BLEND);
}

}  // namespace oitbench::viewer
