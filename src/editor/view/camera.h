#pragma once
// The viewport camera: a turntable orbiting a target point about the model's up, as in Blender
// and Maya. Yaw and pitch are measured in the model's frame (its up and front, world +y and +z
// unless set), so the front, right and top views are the model's. Orbit, pan and dolly take
// pixel deltas, dolly zooms towards the cursor, framing fits a sphere, and view changes
// animate. Pixel coordinates are relative to the viewport's top-left corner, y down, in
// framebuffer pixels.

#include <array>
#include <glm/glm.hpp>

namespace primo::editor {

enum class ViewPreset { Front, Back, Right, Left, Top, Bottom };

struct CameraPose {
  glm::dvec3 target{0.0};
  double distance = 3.0;
  double yaw = 0.6;     // radians about the model's up; 0 looks at its front (front view)
  double pitch = 0.35;  // radians above the model's horizon
};

struct Ray {
  glm::dvec3 origin;
  glm::dvec3 direction;  // unit
};

class Camera {
 public:
  void set_viewport(int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }

  const CameraPose& pose() const { return pose_; }
  void set_pose(const CameraPose& pose);       // immediately
  void animate_to(const CameraPose& pose);     // over a quarter second
  // Advances an animation; returns true while one is running.
  bool update(double seconds);

  bool orthographic() const { return orthographic_; }
  void set_orthographic(bool ortho) { orthographic_ = ortho; }
  double fov_y() const { return fov_y_; }

  // Navigation from mouse motion in pixels.
  void orbit(double dx, double dy);
  void pan(double dx, double dy);
  void dolly(double steps, const glm::dvec2& cursor);  // wheel steps; > 0 zooms in
  void dolly_drag(double dy);                          // drag down zooms in

  // Fits a sphere into the view (animated unless `immediate`), keeping the direction.
  void frame(const glm::dvec3& center, double radius, bool immediate = false);
  void view_preset(ViewPreset preset);
  // The model's up and front (unit, perpendicular world vectors). With `keep_view` the eye
  // stays where it is: its yaw and pitch are measured again in the new frame (the view only
  // rolls so that the new up is up). Without it the yaw and pitch keep their values, so the
  // eye moves with the frame: a new model is seen from the same side of it.
  void set_model_axes(const glm::dvec3& up, const glm::dvec3& front, bool keep_view);
  const glm::dvec3& model_up() const { return up_; }
  const glm::dvec3& model_front() const { return front_; }
  // Near/far planes follow the scene's bounding radius.
  void set_scene_radius(double radius) { scene_radius_ = radius; }

  glm::dvec3 eye() const;
  // Unit, from the target towards the eye of a yaw and pitch in the model's frame.
  glm::dvec3 direction(double yaw, double pitch) const;
  glm::dvec3 forward() const;  // unit, from eye towards target
  glm::dvec3 right() const;
  glm::dvec3 up() const;
  glm::dmat4 view() const;
  glm::dmat4 projection() const;

  // Viewport pixel (x, y down) and window depth in [0, 1].
  glm::dvec3 project(const glm::dvec3& world) const;
  glm::dvec3 unproject(const glm::dvec2& pixel, double depth) const;
  Ray ray(const glm::dvec2& pixel) const;
  // World length of one pixel at a world point (at the point's depth).
  double world_per_pixel(const glm::dvec3& at) const;
  // How the world's x, y and z axes appear, for the view-axis widget in the corner: screen
  // direction (x right, y down) and depth (> 0 pointing away from the viewer) of each.
  std::array<glm::dvec3, 3> axes_on_screen() const;

 private:
  CameraPose pose_;
  CameraPose from_, to_;
  double anim_t_ = 1.0;
  bool orthographic_ = false;
  double fov_y_ = glm::radians(35.0);
  double scene_radius_ = 1.0;
  glm::dvec3 up_{0.0, 1.0, 0.0}, front_{0.0, 0.0, 1.0};
  int width_ = 1, height_ = 1;
};

}  // namespace primo::editor
