#pragma once
// Gaussian splats (Kerbl et al. 2023, "3D Gaussian Splatting for Real-Time Radiance Field Rendering"):
// the primitive every splat scene is made of, whether generated (generator "splats") or loaded from a
// 3DGS PLY file (generator "ply"). What both the GPU rasteriser (shaders/splats/) and the analytic CPU
// reference (splat_reference.hpp) read: one list, in submission order, built for one view.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <vector>

namespace oitbench::oit {

struct Splat {
  glm::vec3 position{0.0f};  // world space
  glm::vec3 scale{1.0f};     // standard deviations along the rotated local axes (linear: exp of the PLY's logs)
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // normalised (w, x, y, z): local axes to world
  float opacity = 1.0f;                        // in [0, 1] (the sigmoid of the PLY's logit)
  glm::vec3 colour{1.0f};  // linear RGB for the view the list was built for (spherical harmonics evaluated)
};

// The splats of one view of a scene, in submission order (a global sort reorders them on the GPU).
using SplatList = std::vector<Splat>;

}  // namespace oitbench::oit
