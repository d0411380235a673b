#pragma once
// A scene mesh on the GPU: one interleaved vertex buffer (oit::Vertex), index buffers in submission
// order (triangles, then line segments), and the vertex array that describes them for
// shaders/scene/scene.vert; and the mesh's Gaussian splats (GpuSplats), drawn after them.
#include <memory>
#include <vector>

#include "gl/gl_objects.hpp"
#include "oit/scene/scene.hpp"
#include "oit/splats/gpu_splats.hpp"

namespace oitbench::oit {

// Describes oit::Vertex records in `vertices` (binding 0) to `vao` at the locations
// shaders/scene/scene.vert reads: the one place that layout is written.
void bind_vertex_layout(GLuint vao, GLuint vertices);

class GpuMesh {
 public:
  // The transparent primitives: mesh.indices (triangles), mesh.line_indices (segments) and mesh.splats.
  explicit GpuMesh(const Mesh& mesh);
  // These triangles of the mesh and no line segments (the opaque effect's mesh.opaque_indices).
  GpuMesh(const Mesh& mesh, const std::vector<unsigned>& triangles);
  // All triangles, then all line segments (GL_LINES), in submission order; a mesh of splats draws its
  // splats instead (a program built with splat_defines(): the splat path of scene.vert).
  void draw() const;
  // `segments` line segments whose vertex index pairs come from `elements` (the lines experiment's
  // sorted order); the mesh's own line indices when `elements` is 0.
  void draw_lines(GLuint elements, size_t segments) const;
  size_t polygons() const { return triangles_ + segments_; }  // triangles plus line segments
  size_t triangles() const { return triangles_; }
  size_t segments() const { return segments_; }
  GLuint vertex_buffer() const { return vertices_.get(); }   // oit::Vertex[], for compute passes
  GLuint line_index_buffer() const { return lines_.get(); }  // two vertex indices per segment
  const GpuSplats* splats() const { return splats_.get(); }  // null for a mesh without splats

 private:
  GpuMesh(const Mesh& mesh, const std::vector<unsigned>& triangles, const std::vector<unsigned>& lines);
  gl::Buffer vertices_, indices_, lines_;
  gl::VertexArray vao_;
  size_t triangles_, segments_;
  std::unique_ptr<GpuSplats> splats_;
};

}  // namespace oitbench::oit
