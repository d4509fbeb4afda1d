// Editor painting: brush values into factor arrays, erasing, grouping into regions.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "view/face_colors.h"
#include "document/selection/mesh_topology.h"
#include "document/paint.h"
#include "primo/mesh/mesh_generators.h"

using namespace primo::editor;

TEST(EditorPaint, PaintEraseAndGroup) {
  FactorArray f = paint_factors(nullptr, 6, {1, 2}, 0.25);
  ASSERT_TRUE(f);
  EXPECT_EQ(*f, (std::vector<double>{1, 0.25, 0.25, 1, 1, 1}));
  const FactorArray before = f;
  f = paint_factors(f, 6, {4}, 2.0);
  EXPECT_EQ((*before)[4], 1.0) << "copy on write: earlier arrays (undo steps) stay as they were";
  const std::vector<FactorGroup> groups = group_factors(f);
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].value, 0.25);
  EXPECT_EQ(groups[0].faces, (std::vector<int>{1, 2}));
  EXPECT_EQ(groups[1].value, 2.0);
  EXPECT_EQ(groups[1].faces, (std::vector<int>{4}));
  f = paint_factors(f, 6, {1, 2, 4}, 1.0);
  EXPECT_FALSE(f) << "erased everywhere: back to no array";
  EXPECT_TRUE(group_factors(f).empty());
}

TEST(EditorPaint, LayersAreSeparate) {
  EditState s = initial_edit_state(4);
  layer_factors(s, PaintLayer::Width) = paint_factors(nullptr, 4, {0}, 1.5);
  EXPECT_FALSE(s.height_factor);
  EXPECT_EQ(factor_at(s.width_factor, 0), 1.5);
  EXPECT_EQ(factor_at(s.height_factor, 0), 1.0);
}

TEST(EditorPaint, FalloffFadesFromTheCentreToTheRim) {
  EXPECT_EQ(falloff_weight(Falloff::Constant, 0.7), 1.0);
  EXPECT_EQ(falloff_weight(Falloff::Linear, 0.25), 0.75);
  EXPECT_EQ(falloff_weight(Falloff::Smooth, 0.0), 1.0);
  EXPECT_NEAR(falloff_weight(Falloff::Smooth, 0.5), 0.5625, 1e-15);
  for (Falloff f : {Falloff::Constant, Falloff::Linear, Falloff::Smooth})
    EXPECT_EQ(falloff_weight(f, 1.0), 0.0) << "nothing at or beyond the rim";
}

TEST(EditorPaint, SoftDabsBlendTowardsTheValueInHundredths) {
  FactorArray f = blend_factors(nullptr, 4, {0, 1, 2}, {1.0, 0.5, 0.0}, 0.3);
  ASSERT_TRUE(f);
  EXPECT_EQ((*f)[0], 0.3);   // full weight: the value exactly
  EXPECT_EQ((*f)[1], 0.65);  // half way from 1
  EXPECT_EQ((*f)[2], 1.0);   // no weight: untouched
  // Dabs build up; values stay on a 0.01 grid, so a soft stroke saves as few regions.
  for (int k = 0; k < 3; ++k) f = blend_factors(f, 4, {1}, {0.37}, 0.3);
  EXPECT_NEAR((*f)[1], 0.3 + 0.35 * std::pow(0.63, 3), 0.01);
  EXPECT_EQ(std::round((*f)[1] * 100) / 100, (*f)[1]);
  // Blending everything back to 1 gives the empty layer again.
  EXPECT_EQ(blend_factors(f, 4, {0, 1}, {1.0, 1.0}, 1.0), nullptr);
}

TEST(EditorPaint, SmoothingSoftensThePaintedEdge) {
  const primo::Mesh grid = primo::make_grid(1.0, 1.0, 5, 5, primo::FaceShape::Quads);
  const MeshTopology t = build_topology(grid);
  const int centre = 12;  // the middle quad of 5 x 5
  const FactorArray painted = paint_factors(nullptr, t.n_faces, {centre}, 0.1);
  const FactorArray smoothed = smooth_factors(painted, t);
  ASSERT_TRUE(smoothed);
  EXPECT_NEAR((*smoothed)[centre], (0.1 + 8.0) / 9.0, 0.005);  // itself and 8 neighbours
  EXPECT_NEAR((*smoothed)[centre + 1], (0.1 + 8.0) / 9.0, 0.005);  // one painted neighbour of 9
  EXPECT_EQ((*smoothed)[0], 1.0);  // far from the paint
  EXPECT_EQ(smooth_factors(nullptr, t), nullptr);
}

TEST(EditorPaint, NoPaintColourIsAHandleColour) {
  // Painted faces show under handles (55% over them): no paint colour may pass for any
  // handle's. Every paint colour of both layers, softer and stiffer, shrink and grow, and the
  // colour of a broken factor, against every handle colour. Distance in 0..255 RGB.
  auto distance = [](const Rgb& a, const Rgb& b) {
    return 255.0 * std::sqrt(std::pow(a[0] - b[0], 2) + std::pow(a[1] - b[1], 2) + std::pow(a[2] - b[2], 2));
  };
  std::vector<std::pair<std::string, Rgb>> handles;
  HandleGroup g;
  for (int slot = 0; slot < 8; ++slot) {
    g.color = slot;
    handles.emplace_back("palette slot " + std::to_string(slot), handle_color(g));
  }
  g.mode = HandleMode::Fixed;
  handles.emplace_back("fixed regions", handle_color(g));
  for (PaintLayer layer : {PaintLayer::Height, PaintLayer::Width})
    for (double factor : {0.3, 0.9, 1.1, 3.0, -1.0}) {
      float opacity = 0.0f;
      const Rgb paint = factor_color(layer, factor, opacity);
      EXPECT_GT(opacity, 0.0f);
      for (const auto& [name, handle] : handles)
        EXPECT_GT(distance(paint, handle), 100.0)
            << (layer == PaintLayer::Height ? "stiffness" : "width") << " x" << factor << " and "
            << name;
      EXPECT_GT(distance(paint, selection_color()), 100.0);
    }
}
