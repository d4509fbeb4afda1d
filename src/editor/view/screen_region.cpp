#include "screen_region.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace primo::editor {

ScreenShape ScreenShape::circle(const glm::dvec2& center, double radius) {
  ScreenShape s;
  s.kind_ = Kind::Circle;
  s.a_ = center;
  s.radius_ = radius;
  return s;
}

ScreenShape ScreenShape::box(const glm::dvec2& corner_a, const glm::dvec2& corner_b) {
  ScreenShape s;
  s.kind_ = Kind::Box;
  s.a_ = glm::min(corner_a, corner_b);
  s.b_ = glm::max(corner_a, corner_b);
  return s;
}

ScreenShape ScreenShape::lasso(std::vector<glm::dvec2> points) {
  ScreenShape s;
  s.kind_ = Kind::Lasso;
  s.points_ = std::move(points);
  if (!s.points_.empty()) {
    s.a_ = s.b_ = s.points_.front();
    for (const auto& p : s.points_) {
      s.a_ = glm::min(s.a_, p);
      s.b_ = glm::max(s.b_, p);
    }
  }
  return s;
}

bool ScreenShape::contains(const glm::dvec2& p) const {
  switch (kind_) {
    case Kind::Circle: {
      const glm::dvec2 d = p - a_;
      return glm::dot(d, d) <= radius_ * radius_;
    }
    case Kind::Box:
      return p.x >= a_.x && p.x <= b_.x && p.y >= a_.y && p.y <= b_.y;
    case Kind::Lasso: {
      if (points_.size() < 3) return false;
      bool inside = false;
      for (size_t i = 0, j = points_.size() - 1; i < points_.size(); j = i++) {
        const glm::dvec2 &pi = points_[i], &pj = points_[j];
        if ((pi.y > p.y) != (pj.y > p.y) &&
            p.x < (pj.x - pi.x) * (p.y - pi.y) / (pj.y - pi.y) + pi.x)
          inside = !inside;
      }
      return inside;
    }
  }
  return false;
}

void ScreenShape::bounds(int& x0, int& y0, int& x1, int& y1) const {
  glm::dvec2 lo = a_, hi = b_;
  if (kind_ == Kind::Circle) {
    lo = a_ - glm::dvec2(radius_);
    hi = a_ + glm::dvec2(radius_);
  }
  x0 = int(std::floor(lo.x));
  y0 = int(std::floor(lo.y));
  x1 = int(std::floor(hi.x)) + 1;
  y1 = int(std::floor(hi.y)) + 1;
}

float PickImage::depth_at(int x, int y) const {
  return contains(x, y) ? depth[size_t(y - y0) * width + (x - x0)]
                        : std::numeric_limits<float>::infinity();
}

std::vector<int> points_in_shape(const ScreenShape& shape, const PickImage& image,
                                 const std::vector<ProjectedPoint>& points, bool xray,
                                 double depth_tolerance) {
  std::vector<int> inside;
  for (size_t i = 0; i < points.size(); ++i) {
    const ProjectedPoint& c = points[i];
    if (c.depth <= 0.0 || !shape.contains({c.x, c.y})) continue;
    if (!xray) {
      const float seen = image.depth_at(int(std::floor(c.x)), int(std::floor(c.y)));
      if (double(seen) < c.depth - depth_tolerance) continue;
    }
    inside.push_back(int(i));
  }
  return inside;
}

std::vector<int> faces_in_shape(const ScreenShape& shape, const PickImage& image,
                                const std::vector<ProjectedPoint>& centroids, bool xray,
                                double depth_tolerance) {
  // 1. Faces whose centroid projects inside and is visible there (or any, with x-ray).
  std::vector<int> faces = points_in_shape(shape, image, centroids, xray, depth_tolerance);
  // 2. Faces that own a pixel inside the shape (pixel centres are tested).
  for (int y = image.y0; y < image.y0 + image.height; ++y)
    for (int x = image.x0; x < image.x0 + image.width; ++x) {
      const int f = image.face_at(x, y);
      if (f >= 0 && shape.contains({x + 0.5, y + 0.5})) faces.push_back(f);
    }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

}  // namespace primo::editor
