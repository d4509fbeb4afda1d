// Editor painting: brush values into factor arrays, erasing, grouping into regions.

#include <gtest/gtest.h>

#include "paint.h"

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
