#include "oit/gpu_mesh.hpp"

#include <algorithm>
#include <cstddef>

namespace oitbench::oit {

GpuMesh::GpuMesh(const Mesh& mesh) : GpuMesh(mesh, mesh.indices) {}

GpuMesh::GpuMesh(const Mesh& mesh, const std::vector<unsigned>& indices)
    : vertices_(gl::make_buffer()),
      indices_(gl::make_buffer()),
      vao_(gl::make_vertex_array()),
      index_count_(indices.size()) {
  glNamedBufferStorage(vertices_.get(), static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(Vertex)),
                       mesh.vertices.data(), 0);
  // An empty buffer store is invalid in GL: a mesh without such triangles keeps one unused index.
  const unsigned none = 0;
  glNamedBufferStorage(indices_.get(), static_cast<GLsizeiptr>(std::max<size_t>(indices.size(), 1) * sizeof(unsigned)),
                       indices.empty() ? &none : indices.data(), 0);
  GLuint vao = vao_.get();
  glVertexArrayVertexBuffer(vao, 0, vertices_.get(), 0, sizeof(Vertex));
  glVertexArrayElementBuffer(vao, indices_.get());
  // Locations match shaders/oit/capture.vert.
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

void GpuMesh::draw() const {
  if (index_count_ == 0) return;
  glBindVertexArray(vao_.get());
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(index_count_), GL_UNSIGNED_INT, nullptr);
}

}  // namespace oitbench::oit
