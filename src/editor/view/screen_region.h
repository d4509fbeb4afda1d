#pragma once
// Which faces a brush dab, box or lasso covers on screen. The renderer draws face ids and eye
// depth into a pick image; the faces seen there inside the shape are taken, and so are faces
// too small to own a pixel whose projected centroid lies inside and is not hidden. With x-ray,
// hidden faces are taken too (every face whose centroid projects inside).

#include <glm/glm.hpp>
#include <vector>

namespace primo::editor {

class ScreenShape {
 public:
  static ScreenShape circle(const glm::dvec2& center, double radius);
  static ScreenShape box(const glm::dvec2& corner_a, const glm::dvec2& corner_b);
  static ScreenShape lasso(std::vector<glm::dvec2> points);  // closed polygon, even-odd rule

  bool contains(const glm::dvec2& p) const;
  // Pixel bounds [x0, x1) x [y0, y1) of the shape.
  void bounds(int& x0, int& y0, int& x1, int& y1) const;

 private:
  enum class Kind { Circle, Box, Lasso } kind_ = Kind::Circle;
  glm::dvec2 a_{0.0}, b_{0.0};
  double radius_ = 0.0;
  std::vector<glm::dvec2> points_;
};

// A window of the pick buffer: per pixel the face id (-1 for background) and the eye-space
// depth (distance along the view direction; +inf for background). Row 0 is the top row y0.
struct PickImage {
  int x0 = 0, y0 = 0, width = 0, height = 0;
  std::vector<int> face;
  std::vector<float> depth;

  bool contains(int x, int y) const {
    return x >= x0 && y >= y0 && x < x0 + width && y < y0 + height;
  }
  int face_at(int x, int y) const {
    return contains(x, y) ? face[size_t(y - y0) * width + (x - x0)] : -1;
  }
  float depth_at(int x, int y) const;
};

// A point on screen (a face centroid, a vertex): viewport pixel position and eye depth (<= 0:
// behind the eye).
struct ProjectedPoint {
  double x = 0.0, y = 0.0, depth = 0.0;
};

// The points that project inside `shape` and are visible there: not behind what `image`
// shows by more than `depth_tolerance` (world units), or any with x-ray. Sorted ascending.
std::vector<int> points_in_shape(const ScreenShape& shape, const PickImage& image,
                                 const std::vector<ProjectedPoint>& points, bool xray,
                                 double depth_tolerance);

// Faces under `shape`, sorted ascending. `image` should cover the shape's bounds.
// `depth_tolerance` (world units) decides when a centroid counts as hidden.
std::vector<int> faces_in_shape(const ScreenShape& shape, const PickImage& image,
                                const std::vector<ProjectedPoint>& centroids, bool xray,
                                double depth_tolerance);

}  // namespace primo::editor
