#pragma once
// Which way a model's up and front point (ModelOrientation, primo/scenario/scenario.h), and
// where the editor gets it from. "Front" means the model's front, as artists expect: Numpad 1
// shows a character's face, whatever axis the file happens to use. In order:
//  1. the scenario's `editor.orientation`;
//  2. the mesh's orientation file beside it, `<name>.orientation.json` for `<name>.obj`
//     (mesh formats such as OBJ have no place for it, and the bundled Spot faces -z);
//  3. the convention of the mesh's format: up +y and front +z (OBJ, glTF, PLY scans, OFF),
//     but up +z and front -y for STL, which CAD and 3D-printing tools write z-up (Blender's
//     importers make the same choice).

#include <glm/glm.hpp>
#include <string>

#include "primo/scenario/scenario.h"

namespace primo::editor {

// The unit world vector of a signed axis.
glm::dvec3 axis_vector(const SignedAxis& axis);

// The convention of the mesh file's format (step 3 above).
ModelOrientation format_orientation(const std::string& mesh_path);
// `<folder>/<stem>.orientation.json` for `<folder>/<stem>.<ext>`.
std::string orientation_file_path(const std::string& mesh_path);
// Steps 2 and 3: the orientation file when there is one, else the format's convention.
// Throws primo::Error (the file and the key) when the orientation file is malformed.
ModelOrientation mesh_orientation(const std::string& mesh_path);

// The orientation a view gives: the front is the signed world axis nearest the direction from
// the model towards the eye, the up the one nearest the camera's up among the two axes
// perpendicular to that front ("View > Set front from view").
ModelOrientation orientation_from_view(const glm::dvec3& towards_eye, const glm::dvec3& camera_up);

// "up +Y, front -Z", for menus and messages.
std::string orientation_label(const ModelOrientation& orientation);

}  // namespace primo::editor
