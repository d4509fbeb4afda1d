// Editor undo stack: steps, labels, redo branch, limit.

#include <gtest/gtest.h>

#include "document/undo_stack.h"

using namespace primo::editor;

namespace {

EditState with_height(double h) {
  EditState s = initial_edit_state(3);
  s.prisms.height = h;
  return s;
}

}  // namespace

TEST(EditorUndo, UndoRedoWithLabels) {
  UndoStack u(with_height(1.0));
  EXPECT_FALSE(u.can_undo());
  EXPECT_TRUE(u.push("height 2", with_height(2.0)));
  EXPECT_TRUE(u.push("height 3", with_height(3.0)));
  EXPECT_FALSE(u.push("same", with_height(3.0))) << "no step without a change";
  EXPECT_EQ(u.undo_label(), "height 3");
  EXPECT_EQ(u.undo().prisms.height, 2.0);
  EXPECT_EQ(u.redo_label(), "height 3");
  EXPECT_EQ(u.undo().prisms.height, 1.0);
  EXPECT_FALSE(u.can_undo());
  EXPECT_EQ(u.undo().prisms.height, 1.0);
  EXPECT_EQ(u.redo().prisms.height, 2.0);
  // A new step drops the redo branch.
  EXPECT_TRUE(u.push("height 5", with_height(5.0)));
  EXPECT_FALSE(u.can_redo());
  EXPECT_EQ(u.undo().prisms.height, 2.0);
}

TEST(EditorUndo, ActivatingAHandleIsNoStep) {
  EditState a = initial_edit_state(3), b = a;
  b.active = 2;
  EXPECT_TRUE(a == b);
}

TEST(EditorUndo, OldestStepsFallOff) {
  UndoStack u(with_height(0.0), 3);
  for (int i = 1; i <= 5; ++i) u.push("h", with_height(i));
  EXPECT_EQ(u.size(), 3u);
  EXPECT_EQ(u.undo().prisms.height, 4.0);
  EXPECT_EQ(u.undo().prisms.height, 3.0);
  EXPECT_FALSE(u.can_undo());
}

TEST(UndoStack, GoesToAnyStepOfTheVisibleHistory) {
  UndoStack u(with_height(1.0));
  u.push("a", with_height(2.0));
  u.push("b", with_height(3.0));
  u.push("c", with_height(4.0));
  ASSERT_EQ(u.size(), 4u);
  EXPECT_EQ(u.label(2), "b");
  EXPECT_EQ(u.position(), 3u);
  EXPECT_EQ(u.go_to(1).prisms.height, 2.0);
  EXPECT_EQ(u.position(), 1u);
  EXPECT_EQ(u.redo_label(), "b");  // the later steps stay, as after undos
  EXPECT_EQ(u.go_to(3).prisms.height, 4.0);
  EXPECT_EQ(u.go_to(0).prisms.height, 1.0);
  EXPECT_FALSE(u.can_undo());
  EXPECT_EQ(u.go_to(99).prisms.height, 1.0) << "out of range: stays";
}

TEST(UndoStack, RunsOfLikeStepsAreGroups) {
  UndoStack u(with_height(1.0));
  const char* labels[] = {"Drag 'Hand'", "Drag 'Hand'", "Drag 'Hand'", "Paint stiffness",
                          "Drag 'Hand'", "Drag 'Hand'"};
  double h = 1.0;
  for (const char* label : labels) ASSERT_TRUE(u.push(label, with_height(h += 1.0)));
  const std::vector<UndoStack::Group> g = u.groups();
  ASSERT_EQ(g.size(), 4u);  // as opened | 3 drags | paint | 2 drags
  EXPECT_EQ(g[0].first, 0u);
  EXPECT_EQ(g[0].size(), 1u);
  EXPECT_EQ(g[1].first, 1u);
  EXPECT_EQ(g[1].last, 3u);
  EXPECT_EQ(g[2].size(), 1u);
  EXPECT_EQ(g[3].first, 5u);
  EXPECT_EQ(g[3].last, 6u);
  EXPECT_EQ(u.group_of(2).first, 1u);
  EXPECT_EQ(u.group_of(2).last, 3u);
  EXPECT_EQ(u.group_of(6).first, 5u);
  EXPECT_EQ(u.group_of(0).last, 0u);
}
