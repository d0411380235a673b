#pragma once
// A scene mesh on the GPU: one interleaved vertex buffer (oit::Vertex), an index buffer in
// submission order, and the vertex array that describes them for shaders/oit/capture.vert.
#include "gl/gl_objects.hpp"
#include "oit/scene.hpp"

namespace oitbench::oit {

class GpuMesh {
 public:
  explicit GpuMesh(const Mesh& mesh);                               // the transparent primitives (mesh.indices)
  GpuMesh(const Mesh& mesh, const std::vector<unsigned>& indices);  // these triangles of the mesh
  void draw() const;                                                // all triangles, in submission order
  size_t polygons() const { return index_count_ / 3; }

 private:
  gl::Buffer vertices_, indices_;
  gl::VertexArray vao_;
  size_t index_count_;
};

}  // namespace oitbench::oit
