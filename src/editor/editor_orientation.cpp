// The model's orientation in the editor: the camera's turntable follows the document's up and
// front (model_orientation.h has where they come from), and View > Set front from view makes
// the current view the model's front.

#include "editor.h"
#include "document/model_orientation.h"

namespace primo::editor {

void Editor::set_front_from_view() {
  if (!doc_) return;
  const ModelOrientation o = orientation_from_view(-camera_.forward(), camera_.up());
  if (o == doc_->state.orientation) {
    camera_.view_preset(ViewPreset::Front);
    return info("The model's front is already this view (" + orientation_label(o) + ")");
  }
  doc_->state.orientation = o;
  commit("Set front from view");
  follow_orientation(true);
  camera_.view_preset(ViewPreset::Front);  // shows what "front" now means
  info("The model's front is now this view: " + orientation_label(o) +
       " (saved with the scenario)");
}

void Editor::follow_orientation(bool keep_view) {
  if (!doc_) return;
  const ModelOrientation& o = doc_->state.orientation;
  camera_.set_model_axes(axis_vector(o.up), axis_vector(o.front), keep_view);
}

}  // namespace primo::editor
