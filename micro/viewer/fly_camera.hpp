#pragma once
// The viewer's fly camera: starts at a scene view and moves freely (WASD, Q/E down/up, mouse look).
// It hands back a scene View each frame, so the projection is the benchmark's own view_projection,
// near and far planes enclosing the scene's bounds.
#include <glm/glm.hpp>

#include "oit/scene/scene.hpp"

namespace oitbench::viewer {

class FlyCamera {
 public:
  // `mesh` only gives the scene's bounds (the speed scale and the near/far planes).
  FlyCamera(const oit::View& start, const oit::Mesh& mesh);

  struct Motion {
    float forward = 0, right = 0, up = 0;  // each -1, 0 or 1
    bool fast = false;                     // shift: 4x
  };
  void move(const Motion& motion, float seconds);
  // Mouse look: radians per pixel of drag.
  void look(float dx_pixels, float dy_pixels);
  // Scroll: each step scales the speed by 1.25.
  void scale_speed(float steps);

  oit::View view() const;  // named like the start view; target at the start's focus distance
  glm::mat4 view_projection(float aspect) const;
  float speed() const { return speed_; }  // scene units per second

 private:
  oit::View start_;
  glm::vec3 eye_, forward_, up_;
  float focus_;  // distance from the eye to the target, kept from the start view
  float speed_;
  oit::Mesh bounds_;  // the 8 corners of the scene's bounding box: cheap near/far planes per frame
};

}  // namespace oitbench::viewer
