#include "camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace primo::editor {
namespace {

constexpr double kOrbitRadiansPerPixel = 0.008;
constexpr double kMaxPitch = 1.5607;  // just short of the pole: the turntable stays upright
constexpr double kDollyPerStep = 0.85;
constexpr double kAnimationSeconds = 0.25;

double wrap_angle(double a) {
  const double two_pi = glm::two_pi<double>();
  a = std::fmod(a, two_pi);
  if (a > glm::pi<double>()) a -= two_pi;
  if (a < -glm::pi<double>()) a += two_pi;
  return a;
}

}  // namespace

void Camera::set_viewport(int width, int height) {
  width_ = std::max(width, 1);
  height_ = std::max(height, 1);
}

void Camera::set_pose(const CameraPose& pose) {
  pose_ = pose;
  anim_t_ = 1.0;
}

void Camera::animate_to(const CameraPose& pose) {
  from_ = pose_;
  to_ = pose;
  // Take the short way round.
  to_.yaw = from_.yaw + wrap_angle(to_.yaw - from_.yaw);
  anim_t_ = 0.0;
}

bool Camera::update(double seconds) {
  if (anim_t_ >= 1.0) return false;
  anim_t_ = std::min(1.0, anim_t_ + seconds / kAnimationSeconds);
  const double s = anim_t_ * anim_t_ * (3.0 - 2.0 * anim_t_);  // smoothstep
  pose_.target = glm::mix(from_.target, to_.target, s);
  // Distances interpolate geometrically so zooming feels uniform.
  pose_.distance = from_.distance * std::pow(to_.distance / from_.distance, s);
  pose_.yaw = glm::mix(from_.yaw, to_.yaw, s);
  pose_.pitch = glm::mix(from_.pitch, to_.pitch, s);
  return anim_t_ < 1.0;
}

void Camera::orbit(double dx, double dy) {
  anim_t_ = 1.0;
  pose_.yaw = wrap_angle(pose_.yaw - dx * kOrbitRadiansPerPixel);
  pose_.pitch = std::clamp(pose_.pitch + dy * kOrbitRadiansPerPixel, -kMaxPitch, kMaxPitch);
}

void Camera::pan(double dx, double dy) {
  anim_t_ = 1.0;
  const double s = world_per_pixel(pose_.target);
  pose_.target += (-dx * s) * right() + (dy * s) * up();
}

void Camera::dolly(double steps, const glm::dvec2& cursor) {
  anim_t_ = 1.0;
  const double factor = std::pow(kDollyPerStep, steps);
  // The point under the cursor on the plane through the target stays under the cursor.
  const glm::dvec3 target_window = project(pose_.target);
  const glm::dvec3 anchor = unproject(cursor, target_window.z);
  pose_.distance = std::clamp(pose_.distance * factor, 1e-4 * scene_radius_, 1e3 * scene_radius_);
  pose_.target = anchor + (pose_.target - anchor) * factor;
}

void Camera::dolly_drag(double dy) {
  dolly(dy * 0.02, glm::dvec2(width_ * 0.5, height_ * 0.5));
}

void Camera::frame(const glm::dvec3& center, double radius, bool immediate) {
  CameraPose p = pose_;
  p.target = center;
  const double half = 0.5 * fov_y_;
  const double aspect = double(width_) / double(height_);
  const double half_min = aspect < 1.0 ? std::atan(std::tan(half) * aspect) : half;
  p.distance = std::max(radius, 1e-9) * 1.1 / std::sin(half_min);
  if (immediate)
    set_pose(p);
  else
    animate_to(p);
}

void Camera::view_preset(ViewPreset preset) {
  CameraPose p = pose_;
  const double half_pi = glm::half_pi<double>();
  switch (preset) {
    case ViewPreset::Front: p.yaw = 0.0, p.pitch = 0.0; break;
    case ViewPreset::Back: p.yaw = glm::pi<double>(), p.pitch = 0.0; break;
    case ViewPreset::Right: p.yaw = half_pi, p.pitch = 0.0; break;
    case ViewPreset::Left: p.yaw = -half_pi, p.pitch = 0.0; break;
    case ViewPreset::Top: p.yaw = 0.0, p.pitch = kMaxPitch; break;
    case ViewPreset::Bottom: p.yaw = 0.0, p.pitch = -kMaxPitch; break;
  }
  animate_to(p);
}

void Camera::set_model_axes(const glm::dvec3& up, const glm::dvec3& front, bool keep_view) {
  if (up == up_ && front == front_) return;
  const glm::dvec3 towards_eye = direction(pose_.yaw, pose_.pitch);
  anim_t_ = 1.0;  // an animation's yaw and pitch belong to the old frame
  up_ = up;
  front_ = front;
  if (!keep_view) return;
  const glm::dvec3 side = glm::cross(up_, front_);
  pose_.pitch = std::clamp(std::asin(std::clamp(glm::dot(towards_eye, up_), -1.0, 1.0)),
                           -kMaxPitch, kMaxPitch);
  pose_.yaw = std::atan2(glm::dot(towards_eye, side), glm::dot(towards_eye, front_));
}

glm::dvec3 Camera::direction(double yaw, double pitch) const {
  // Yaw 0 and pitch 0 look at the front; yaw pi/2 at the side on the viewer's right.
  const glm::dvec3 side = glm::cross(up_, front_);
  return std::cos(pitch) * std::sin(yaw) * side + std::sin(pitch) * up_ +
         std::cos(pitch) * std::cos(yaw) * front_;
}

glm::dvec3 Camera::eye() const {
  return pose_.target + pose_.distance * direction(pose_.yaw, pose_.pitch);
}

glm::dvec3 Camera::forward() const { return -direction(pose_.yaw, pose_.pitch); }

glm::dvec3 Camera::right() const {
  return glm::normalize(glm::cross(forward(), up_));
}

glm::dvec3 Camera::up() const { return glm::cross(right(), forward()); }

glm::dmat4 Camera::view() const { return glm::lookAt(eye(), pose_.target, up()); }

glm::dmat4 Camera::projection() const {
  const double aspect = double(width_) / double(height_);
  const double near_plane = std::max(pose_.distance - 3.0 * scene_radius_, pose_.distance * 0.01);
  const double far_plane = pose_.distance + 3.0 * scene_radius_;
  if (orthographic_) {
    const double h = pose_.distance * std::tan(0.5 * fov_y_);
    // Orthographic depth may start behind the eye: nothing is cut off when zoomed in.
    return glm::ortho(-h * aspect, h * aspect, -h, h, pose_.distance - 3.0 * scene_radius_,
                      far_plane);
  }
  return glm::perspective(fov_y_, aspect, near_plane, far_plane);
}

glm::dvec3 Camera::project(const glm::dvec3& world) const {
  const glm::dvec4 clip = projection() * view() * glm::dvec4(world, 1.0);
  const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  return {(ndc.x * 0.5 + 0.5) * width_, (0.5 - ndc.y * 0.5) * height_, ndc.z * 0.5 + 0.5};
}

glm::dvec3 Camera::unproject(const glm::dvec2& pixel, double depth) const {
  const glm::dvec4 ndc(2.0 * pixel.x / width_ - 1.0, 1.0 - 2.0 * pixel.y / height_,
                       2.0 * depth - 1.0, 1.0);
  const glm::dvec4 world = glm::inverse(projection() * view()) * ndc;
  return glm::dvec3(world) / world.w;
}

Ray Camera::ray(const glm::dvec2& pixel) const {
  const glm::dvec3 a = unproject(pixel, 0.0), b = unproject(pixel, 1.0);
  return {a, glm::normalize(b - a)};
}

double Camera::world_per_pixel(const glm::dvec3& at) const {
  const double h = orthographic_ ? pose_.distance
                                 : std::max(glm::dot(at - eye(), forward()), 1e-9);
  return 2.0 * h * std::tan(0.5 * fov_y_) / height_;
}

std::array<glm::dvec3, 3> Camera::axes_on_screen() const {
  std::array<glm::dvec3, 3> axes;
  const glm::dvec3 r = right(), u = up(), f = forward();
  for (int k = 0; k < 3; ++k) {
    glm::dvec3 a(0.0);
    a[k] = 1.0;
    axes[size_t(k)] = glm::dvec3(glm::dot(a, r), -glm::dot(a, u), glm::dot(a, f));
  }
  return axes;
}

}  // namespace primo::editor
