// Cancelling an open under way (the status bar's Cancel, or Esc): the document open before
// stays as it was, an open asked for after it is forgotten, and the next open works.

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "support/editor_harness.h"
#include "primo/io/mesh_io.h"
#include "primo/mesh/mesh_generators.h"
#include "support/test_support.h"

using namespace primo;
using namespace primo::editor;
using primo::editor::harness::Harness;

namespace {

// Updates the editor for `seconds` as frames would.
void run_for(Editor& e, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    e.update(0.016);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace

TEST(EditorCancelOpen, ACancelledOpenLeavesTheDocumentAsItWas) {
  const std::string dir = test::temp_dir();
  const std::string big = dir + "/big.obj", other = dir + "/other.obj";
  save_mesh(make_bar(0.2, 1.0, 20, 400), big);
  save_mesh(make_bar(0.2, 1.0, 2, 30), other);
  Harness h;
  Editor& e = h.editor;
  h.two_handles();
  const Document* before = e.document();
  const EditState state = before->state;
  const int faces = before->n_faces();
  const size_t errors = e.error_count();

  EXPECT_FALSE(e.cancel_open()) << "nothing to cancel";
  e.open(big);
  EXPECT_TRUE(e.opening());
  EXPECT_TRUE(e.cancel_open());
  EXPECT_FALSE(e.file_task_running()) << "the status bar and scripts see no task";
  EXPECT_NE(e.messages().back().text.find("Stopped opening big.obj"), std::string::npos)
      << e.messages().back().text;
  run_for(e, 1.5);  // the read ends in the background, unseen
  EXPECT_EQ(e.document(), before);
  EXPECT_EQ(e.document()->state.handles.size(), state.handles.size());
  EXPECT_EQ(e.document()->n_faces(), faces);
  EXPECT_EQ(e.error_count(), errors);

  // An open asked for while another ran is forgotten with it.
  e.open(big);
  e.open(other);
  EXPECT_TRUE(e.cancel_open());
  run_for(e, 1.5);
  EXPECT_EQ(e.document(), before);

  // Esc cancels as the button does.
  e.open(big);
  h.key(GLFW_KEY_ESCAPE);
  EXPECT_FALSE(e.file_task_running());
  run_for(e, 1.5);
  EXPECT_EQ(e.document(), before);

  // The next open opens.
  e.open(other);
  for (int i = 0; i < 3000 && e.file_task_running(); ++i) run_for(e, 0.005);
  ASSERT_NE(e.document(), nullptr);
  EXPECT_EQ(e.document()->mesh_path, other);
  EXPECT_EQ(e.error_count(), errors);
}
