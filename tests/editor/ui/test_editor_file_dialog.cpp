// The file dialog drawn by Dear ImGui without a window or GL: each time it opens for saving,
// its name field has the keyboard with the proposed name selected, so typing replaces it.

#include <gtest/gtest.h>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_internal.h>

#include <filesystem>
#include <string>

#include "file_dialog.h"
#include "support/headless_imgui.h"
#include "support/test_support.h"

using namespace primo::editor;
namespace fs = std::filesystem;

namespace {

struct DialogImGui : primo::test::HeadlessImGui {
  DialogImGui() {
    ImGuiIO& io = ImGui::GetIO();
    io.KeyMap[ImGuiKey_Enter] = GLFW_KEY_ENTER;
    io.KeyMap[ImGuiKey_Escape] = GLFW_KEY_ESCAPE;
    io.KeyMap[ImGuiKey_A] = GLFW_KEY_A;
  }
  // One frame of the dialog; returns the accepted path ("" when none).
  std::string frame(FileDialog& dialog) {
    ImGui::NewFrame();
    std::string path;
    const bool accepted = dialog.draw(path);
    ImGui::Render();
    return accepted ? path : "";
  }
  void settle(FileDialog& dialog, int frames = 3) {
    for (int i = 0; i < frames; ++i) EXPECT_EQ(frame(dialog), "");
  }
  // Keys down for one frame, then up for one.
  std::string tap(FileDialog& dialog, int key) {
    ImGui::GetIO().KeysDown[key] = true;
    std::string path = frame(dialog);
    ImGui::GetIO().KeysDown[key] = false;
    const std::string after = frame(dialog);
    return path.empty() ? after : path;
  }
  // Types `text` and presses Enter; returns the accepted path.
  std::string type_and_accept(FileDialog& dialog, const std::string& text) {
    for (char c : text) ImGui::GetIO().AddInputCharacter(static_cast<unsigned>(c));
    frame(dialog);
    return tap(dialog, GLFW_KEY_ENTER);
  }
};

fs::path scratch_folder() { return fs::path(primo::test::temp_dir()); }

void open_save(FileDialog& dialog, const fs::path& folder) {
  dialog.open(FileDialog::Mode::Save, "Save the scenario", {".json"}, folder.string(),
              "spot-setup.json");
}

}  // namespace

TEST(EditorFileDialog, TypingReplacesTheProposedNameEveryTimeTheDialogOpens) {
  DialogImGui imgui;
  const fs::path folder = scratch_folder();
  FileDialog dialog;
  open_save(dialog, folder);
  imgui.settle(dialog);
  EXPECT_EQ(imgui.type_and_accept(dialog, "first"), (folder / "first.json").string());
  EXPECT_FALSE(dialog.is_open());

  // The second and later times, after an accept and after Esc.
  open_save(dialog, folder);
  imgui.settle(dialog);
  EXPECT_EQ(imgui.type_and_accept(dialog, "second"), (folder / "second.json").string());
  open_save(dialog, folder);
  imgui.settle(dialog);
  EXPECT_EQ(imgui.tap(dialog, GLFW_KEY_ESCAPE), "");
  EXPECT_FALSE(dialog.is_open());
  open_save(dialog, folder);
  imgui.settle(dialog);
  EXPECT_EQ(imgui.type_and_accept(dialog, "third"), (folder / "third.json").string());
}

TEST(EditorFileDialog, TypingReplacesTheProposedNameAfterAKeyboardShortcut) {
  DialogImGui imgui;
  const fs::path folder = scratch_folder();
  FileDialog dialog;
  for (const char* name : {"one", "two"}) {
    // Ctrl+Shift+S: the dialog opens in the frame of the key press, the keys still down.
    ImGuiIO& io = ImGui::GetIO();
    io.KeysDown[GLFW_KEY_LEFT_CONTROL] = io.KeysDown[GLFW_KEY_LEFT_SHIFT] = true;
    io.KeyCtrl = io.KeyShift = true;
    io.KeysDown[GLFW_KEY_S] = true;
    ImGui::NewFrame();
    open_save(dialog, folder);
    std::string path;
    dialog.draw(path);
    ImGui::Render();
    imgui.frame(dialog);
    io.KeysDown[GLFW_KEY_S] = false;
    imgui.frame(dialog);
    io.KeysDown[GLFW_KEY_LEFT_CONTROL] = io.KeysDown[GLFW_KEY_LEFT_SHIFT] = false;
    io.KeyCtrl = io.KeyShift = false;
    imgui.settle(dialog);
    EXPECT_EQ(imgui.type_and_accept(dialog, name),
              (folder / (std::string(name) + ".json")).string());
  }
}
