#pragma once
// A scene mesh on the GPU: one interleaved vertex buffer (oit::Vertex), index buffers in submission
// order (triangles, then line segments), and the vertex array that describes them for
// shaders/oit/capture.vert.
#include "gl/gl_objects.hpp"
#include "oit/scene.hpp"

namespace oitbench::oit {

class GpuMesh {
 public:
  explicit GpuMesh(const Mesh& mesh);
  void draw() const;  // all triangles, then all line segments (GL_LINES), in submission order
  // `segments` line segments whose vertex index pairs come from `elements` (the lines experiment's
  // sorted order); the mesh's own line indices when `elements` is 0.
  void draw_lines(GLuint elements, size_t segments) const;
  size_t polygons() const { return triangles_ + segments_; }  // triangles plus line segments
  size_t triangles() const { return triangles_; }
  size_t segments() const { return segments_; }
  GLuint vertex_buffer() const { return vertices_.get(); }   // oit::Vertex[], for compute passes
  GLuint line_index_buffer() const { return lines_.get(); }  // two vertex indices per segment

 private:
  gl::Buffer vertices_, indices_, lines_;
  gl::VertexArray vao_;
  size_t triangles_, segments_;
};

}  // namespace oitbench::oit
