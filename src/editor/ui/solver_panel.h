#pragma once
// The Solver section of the properties panel: the solver's phase with Stop / Continue, its
// progress, and its figures as labels and values whose values wrap, so that every line reads
// whole at any panel width.

#include "editor.h"
#include "solver_worker.h"

namespace primo::editor {

void solver_section(Editor& editor);

// The figures alone: energy, iterations, timings, the frame, the last gesture and the
// picture a drag shows.
void solver_figures(const SolverStatus& status, double frame_ms,
                    const Editor::GestureStats& last_gesture);

}  // namespace primo::editor
