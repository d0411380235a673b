#include "oit/scene/gpu_mesh.hpp"

#include <algorithm>
#include <cstddef>

namespace oitbench::oit {

namespace {

// An immutable buffer of `data`; an empty list still gets storage (glNamedBufferStorage refuses 0 bytes).
void upload(const gl::Buffer& b, const std::vector<unsigned>& data) {
  glNamedBufferStorage(b.get(), static_cast<GLsizeiptr>(std::max<size_t>(data.size(), 1) * sizeof(unsigned)),
                       data.empty() ? nullptr : data.data(), 0);
}

}  // namespace

void bind_vertex_layout(GLuint vao, GLuint vertices) {
  glVertexArrayVertexBuffer(vao, 0, vertices, 0, sizeof(Vertex));
  glEnableVertexArrayAttrib(vao, 0);
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(Vertex, position));
  glEnableVertexArrayAttrib(vao, 1);
  glVertexArrayAttribFormat(vao, 1, 4, GL_FLOAT, GL_FALSE, offsetof(Vertex, colour));
  glEnableVertexArrayAttrib(vao, 2);
  glVertexArrayAttribFormat(vao, 2, 2, GL_FLOAT, GL_FALSE, offsetof(Vertex, uv));
  glEnableVertexArrayAttrib(vao, 3);
  glVertexArrayAttribFormat(vao, 3, 1, GL_FLOAT, GL_FALSE, offsetof(Vertex, soft));
  for (GLuint a = 0; a < 4; ++a) glVertexArrayAttribBinding(vao, a, 0);
}

GpuMesh::GpuMesh(const Mesh& mesh) : GpuMesh(mesh, mesh.indices, mesh.line_indices) {
  if (!mesh.splats.empty()) splats_ = std::make_unique<GpuSplats>(mesh.splats);
}

GpuMesh::GpuMesh(const Mesh& mesh, const std::vector<unsigned>& triangles) : GpuMesh(mesh, triangles, {}) {}

GpuMesh::GpuMesh(const Mesh& mesh, const std::vector<unsigned>& triangles, const std::vector<unsigned>& lines)
    : vertices_(gl::make_buffer()),
      indices_(gl::make_buffer()),
      lines_(gl::make_buffer()),
      vao_(gl::make_vertex_array()),
      triangles_(triangles.size() / 3),
      segments_(lines.size() / 2) {
  glNamedBufferStorage(vertices_.get(),
                       static_cast<GLsizeiptr>(std::max<size_t>(mesh.vertices.size(), 1) * sizeof(Vertex)),
                       mesh.vertices.empty() ? nullptr : mesh.vertices.data(), 0);
  upload(indices_, triangles);
  upload(lines_, lines);
  bind_vertex_layout(vao_.get(), vertices_.get());
  glVertexArrayElementBuffer(vao_.get(), indices_.get());
}

void GpuMesh::draw() const {
  if (splats_) {
    splats_->draw();
    return;
  }
  glBindVertexArray(vao_.get());
  if (triangles_ > 0) glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(3 * triangles_), GL_UNSIGNED_INT, nullptr);
  if (segments_ > 0) draw_lines(0, segments_);
}

void GpuMesh::draw_lines(GLuint elements, size_t segments) const {
  if (segments == 0) return;
  glVertexArrayElementBuffer(vao_.get(), elements ? elements : lines_.get());
  glBindVertexArray(vao_.get());
  glDrawElements(GL_LINES, static_cast<GLsizei>(2 * segments), GL_UNSIGNED_INT, nullptr);
  glVertexArrayElementBuffer(vao_.get(), indices_.get());
}

}  // namespace oitbench::oit
