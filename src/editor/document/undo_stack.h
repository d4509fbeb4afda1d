#pragma once
// Linear undo history of whole EditStates. A gesture (one drag, one stroke, one slider change)
// edits the live state and pushes one step when it ends; undo and redo return the state to
// show. Pushing after an undo drops the redo branch. The oldest steps fall off beyond `limit`.

#include <cstddef>
#include <string>
#include <vector>

#include "edit_state.h"

namespace primo::editor {

class UndoStack {
 public:
  explicit UndoStack(EditState initial = {}, std::size_t limit = 200);

  // Clears the history and starts from `initial`.
  void reset(EditState initial);
  // Records `state` as a new step named `label`. Returns false (and records nothing) when it
  // equals the current state.
  bool push(const std::string& label, const EditState& state);

  bool can_undo() const { return index_ > 0; }
  bool can_redo() const { return index_ + 1 < steps_.size(); }
  // Label of the step an undo / redo would revert / reapply ("" when none).
  std::string undo_label() const;
  std::string redo_label() const;
  const EditState& undo();
  const EditState& redo();
  const EditState& current() const { return steps_[index_].state; }
  std::size_t size() const { return steps_.size(); }
  // The visible history (Edit > History): step i's label (step 0 is the opened document) and
  // which step is current. go_to moves there as that many undos or redos would.
  const std::string& label(std::size_t i) const { return steps_[i].label; }
  std::size_t position() const { return index_; }
  const EditState& go_to(std::size_t i);

  // Maya-style grouping of the visible history: a run of consecutive steps with the same
  // label (five drags of one handle, a series of paint strokes) is one group, shown folded,
  // and undone at once by Edit > Undo group. Step 0 is a group of its own.
  struct Group {
    std::size_t first, last;  // step indices, inclusive
    std::size_t size() const { return last - first + 1; }
  };
  std::vector<Group> groups() const;
  // The group that holds step i.
  Group group_of(std::size_t i) const;

 private:
  struct Step {
    std::string label;
    EditState state;
  };
  std::vector<Step> steps_;
  std::size_t index_ = 0;
  std::size_t limit_;
};

}  // namespace primo::editor
