#include "undo_stack.h"

#include <algorithm>

namespace primo::editor {

UndoStack::UndoStack(EditState initial, std::size_t limit) : limit_(std::max<std::size_t>(limit, 2)) {
  reset(std::move(initial));
}

void UndoStack::reset(EditState initial) {
  steps_.clear();
  steps_.push_back({"", std::move(initial)});
  index_ = 0;
}

bool UndoStack::push(const std::string& label, const EditState& state) {
  if (state == current()) return false;
  steps_.erase(steps_.begin() + index_ + 1, steps_.end());
  steps_.push_back({label, state});
  if (steps_.size() > limit_) steps_.erase(steps_.begin());
  index_ = steps_.size() - 1;
  return true;
}

std::string UndoStack::undo_label() const { return can_undo() ? steps_[index_].label : ""; }

std::string UndoStack::redo_label() const { return can_redo() ? steps_[index_ + 1].label : ""; }

const EditState& UndoStack::go_to(std::size_t i) {
  if (i < steps_.size()) index_ = i;
  return current();
}

std::vector<UndoStack::Group> UndoStack::groups() const {
  std::vector<Group> out;
  for (std::size_t i = 0; i < steps_.size(); ++i) {
    if (i > 1 && steps_[i].label == steps_[i - 1].label)
      out.back().last = i;
    else
      out.push_back({i, i});
  }
  return out;
}

UndoStack::Group UndoStack::group_of(std::size_t i) const {
  Group g{i, i};
  if (i == 0 || i >= steps_.size()) return g;
  while (g.first > 1 && steps_[g.first - 1].label == steps_[i].label) --g.first;
  while (g.last + 1 < steps_.size() && steps_[g.last + 1].label == steps_[i].label) ++g.last;
  return g;
}

const EditState& UndoStack::undo() {
  if (can_undo()) --index_;
  return current();
}

const EditState& UndoStack::redo() {
  if (can_redo()) ++index_;
  return current();
}

}  // namespace primo::editor
