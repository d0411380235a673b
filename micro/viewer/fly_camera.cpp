#include "viewer/fly_camera.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace oitbench::viewer {

namespace {
constexpr float kLookRadiansPerPixel = 0.005f;
constexpr float kFastFactor = 4.0f;
constexpr float kMaxPitch = 1.52f;  // radians: stop short of looking straight along `up` (lookAt degenerates)
}  // namespace

FlyCamera::FlyCamera(const oit::View& start, const oit::Mesh& mesh) : start_(start), eye_(start.eye) {
  up_ = glm::length(start.up) > 0 ? glm::normalize(start.up) : glm::vec3(0, 1, 0);
  glm::vec3 to_target = start.target - start.eye;
  focus_ = glm::length(to_target);
  forward_ = focus_ > 0 ? to_target / focus_ : glm::vec3(0, 0, -1);
  if (focus_ <= 0) focus_ = 1;
  if (std::abs(glm::dot(forward_, up_)) > std::sin(kMaxPitch)) {  // looking along up: pick another up
    up_ = std::abs(forward_.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
  }
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const auto& v : mesh.vertices) {
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
  }
  if (mesh.vertices.empty()) lo = hi = glm::vec3(0);
  for (int i = 0; i < 8; ++i) {
    oit::Vertex v{};
    v.position = glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    bounds_.vertices.push_back(v);
  }
  // A quarter of the scene's diagonal per second: slow enough to aim, fast enough to cross it in seconds.
  speed_ = std::max(1e-3f, 0.25f * glm::length(hi - lo));
}

void FlyCamera::move(const Motion& m, float seconds) {
  glm::vec3 right = glm::normalize(glm::cross(forward_, up_));
  glm::vec3 d = forward_ * m.forward + right * m.right + up_ * m.up;
  if (glm::length(d) == 0) return;
  eye_ += glm::normalize(d) * speed_ * (m.fast ? kFastFactor : 1.0f) * seconds;
}

void FlyCamera::look(float dx, float dy) {
  glm::vec3 f = glm::vec3(glm::rotate(glm::mat4(1), -dx * kLookRadiansPerPixel, up_) * glm::vec4(forward_, 0));
  float along_up = glm::dot(f, up_);
  glm::vec3 level = glm::normalize(f - up_ * along_up);
  float pitch =
      std::clamp(std::asin(std::clamp(along_up, -1.0f, 1.0f)) - dy * kLookRadiansPerPixel, -kMaxPitch, kMaxPitch);
  forward_ = glm::normalize(level * std::cos(pitch) + up_ * std::sin(pitch));
}

void FlyCamera::scale_speed(float steps) { speed_ = std::clamp(speed_ * std::pow(1.25f, steps), 1e-4f, 1e6f); }

oit::View FlyCamera::view() const {
  oit::View v = start_;
  v.eye = eye_;
  v.target = eye_ + forward_ * focus_;
  v.up = up_;
  return v;
}

glm::mat4 FlyCamera::view_projection(float aspect) const { return oit::view_projection(view(), bounds_, aspect); }

}  // namespace oitbench::viewer
