#pragma once
// Transitional. Atomic file output moved from src/app to the core (primo/output_files.h), and
// editor.cpp, which another change is editing at the same time, still calls it by its old
// names app::check_mesh_output_path and app::write_text_atomically. This alias keeps those two
// calls compiling without touching more than editor.cpp's include line. Once they lose their
// "app::", include primo/output_files.h in editor.cpp and delete this header.

#include "primo/output_files.h"

namespace primo::editor {
namespace app = ::primo;
}  // namespace primo::editor
