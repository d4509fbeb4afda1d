#pragma once
// The editor without its window: the open document, camera, tools, display settings, the
// solver thread and file tasks, and everything input does in the viewport (navigation, tool
// gestures, shortcuts). The GLFW/ImGui application owns one Editor, feeds it input events,
// calls its commands from menus and panels, and draws what it exposes. Tests drive it the
// same way with a stand-in Picker instead of the GPU pick buffer.

#include <array>
#include <cstdint>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "view/camera.h"
#include "view/frame_times.h"
#include "document/document.h"
#include "view/gizmo.h"
#include "view/gizmo_orientation.h"
#include "input/input.h"
#include "document/mirror.h"
#include "document/paint.h"
#include "user_files/preferences.h"
#include "user_files/recent_files.h"
#include "view/screen_region.h"
#include "recording/session_control.h"
#include "solver_worker.h"

namespace primo::editor {

enum class Tool { Select, Drag, Move, Rotate, Paint };
enum class SelectShape { Brush, Box, Lasso };
const char* tool_label(Tool tool);

struct ToolSettings {
  Tool tool = Tool::Select;
  SelectShape shape = SelectShape::Brush;
  double brush_radius = 32.0;  // viewport pixels (selection and paint brushes)
  PaintLayer paint_layer = PaintLayer::Height;
  double paint_height = 0.3;   // the height factor the brush paints (below 1: softer)
  double paint_width = 0.85;   // the width factor the brush paints (below 1: shrink)
  double paint_strength = 1.0; // how far one dab moves a face towards the value (0..1]
  Falloff paint_falloff = Falloff::Constant;  // from the brush's centre to its rim
  bool xray = false;           // selections reach hidden faces too
  // The frame of the gizmo's axes (gizmo_orientation.h); Comma cycles through them.
  GizmoOrientation gizmo_orientation = GizmoOrientation::Global;
  double linked_angle_deg = 30.0;  // select linked by angle stops at sharper edges
  double falloff_radius = 0.0;     // the last falloff radius set (world units; 0: none yet)
  // Symmetry across the planes perpendicular to X, Y, Z through the mesh's centre: selecting
  // and painting act on the twin faces too, and handles are made in mirrored pairs.
  std::array<bool, 3> mirror{false, false, false};
};

struct DisplaySettings {
  bool smooth = true;          // smooth (vertex normals) or flat (face normals) shading
  bool wireframe = false;      // polygon edges over the surface
  bool prisms = false;         // the prism layer as wire cages
  bool heat_map = false;       // joint energy density per face
  bool paint_overlay = true;   // painted factors in false colour
  bool grid = true;            // the ground grid under the model (ground_grid.h)
};

// The viewport inside the window: origin and size in window coordinates, and framebuffer
// pixels per window unit (HiDPI).
struct ViewportRect {
  double x = 0.0, y = 0.0, width = 1.0, height = 1.0, scale = 1.0;
};

// Reads face ids and eye depths of the current view (viewport pixels).
class Picker {
 public:
  virtual ~Picker() = default;
  virtual PickImage read(int x0, int y0, int width, int height) = 0;
  // False when a read would first have to render a big mesh again: hover feedback skips it.
  virtual bool cheap_to_read() const { return true; }
};

class Editor {
 public:
  struct Message {
    std::string text;
    bool error = false;
    double time = 0.0;  // editor clock when it was said
    long serial = 0;    // counts messages, for what came after a tool or mode change
  };
  enum class Gesture {
    None, Orbit, Pan, Zoom, SelectBrush, SelectBox, SelectLasso, DragHandle, Gizmo, Paint
  };

  explicit Editor(std::function<void()> wake_ui = {});
  ~Editor();

  // --- Files --------------------------------------------------------------------------
  // In the background; errors become messages. Asked while a file task runs, it opens when
  // that is done (the newest request wins; an open under way that it replaces is dropped).
  void open(const std::string& path);
  void adopt(std::unique_ptr<Document> document);
  void save_mesh(const std::string& path);      // in the background, the latest result
  // At once; false (with an error message) when it could not be written. A saved document
  // has no unsaved changes, and its autosave is removed.
  bool save_scenario(const std::string& path);
  bool file_task_running() const { return task_.valid(); }
  const std::string& file_task_label() const { return task_label_; }
  double file_task_seconds() const;
  // An open (or a recovery) is under way: cancel_open() can stop it.
  bool opening() const { return task_.valid() && task_is_open_; }
  // Stops the open under way and forgets one asked for after it: the document open before
  // stays as it was. The reader cannot be interrupted, so it reads on in the background and
  // its document is dropped unseen; a new open starts at once. False when no open runs.
  bool cancel_open();

  // --- Unsaved work (editor_unsaved_work.cpp) ------------------------------------------
  // Changes since the document was opened or last saved as a scenario: handles, poses,
  // material, painting (the selection and which handle is active do not count).
  bool has_unsaved_changes() const;
  // What the UI asks before work would be discarded: save, discard or cancel.
  enum class DiscardAnswer { Save, Discard, Cancel };
  struct DiscardQuestion {
    enum class Then { Open, Quit } then = Then::Open;
    std::string path;  // Then::Open: the file to open
  };
  // Opens `path`, or first asks (discard_question()) when the open document has unsaved
  // changes. File > Open, drag and drop and Open Recent come here; scripts open directly.
  void request_open(const std::string& path);
  // True when the window may close now; otherwise the question is asked.
  bool ask_to_quit();
  const std::optional<DiscardQuestion>& discard_question() const { return discard_question_; }
  // Save writes the scenario to `save_path` (the document's own scenario when empty) and then
  // goes on; a failed save keeps the question. Discard goes on; Cancel forgets the question.
  void answer_discard(DiscardAnswer answer, const std::string& save_path = {});
  // Autosave (autosave.h): every `seconds` while there are unsaved changes (0: never).
  void set_autosave_interval(double seconds) { autosave_every_ = seconds; }
  bool autosave_now();  // writes the autosave of the open document; false when it could not
  // The autosave written when the editor is told to end (SIGTERM, a timeout): a solve under
  // way is stopped first (waiting at most `max_seconds`), so the file keeps the pose shown.
  bool autosave_before_exit(double max_seconds = 2.0);
  // Opens an autosaved scenario as unsaved work with no file of its own (Save asks where).
  void recover(const std::string& autosave_file);
  RecentFiles& recent_files() { return recent_; }
  // The user's defaults (preferences.h), read when the editor starts. apply_preferences puts
  // them into the display, brush and autosave settings now.
  Preferences& preferences() { return preferences_; }
  void apply_preferences();

  // --- Per frame ------------------------------------------------------------------------
  // Finishes file tasks, sends edits to the solver, picks up its newest result, animates the
  // camera. `seconds` is the time since the last frame.
  void update(double seconds);
  // Nothing pending: no file task, the solver idle for the latest edit, its result shown.
  bool settled() const;
  // The solver result the view should show changed since the last call.
  bool take_geometry_changed();
  bool take_overlay_changed();

  // --- Input ----------------------------------------------------------------------------
  void set_viewport(const ViewportRect& rect);
  const ViewportRect& viewport() const { return viewport_; }
  void set_picker(Picker* picker) { picker_ = picker; }
  // Meshes opened from now on get a stand-in for motion above this many triangles (the window
  // says how it draws: document.h).
  void set_stand_in_above(int triangles) { stand_in_above_ = triangles; }
  // `ui_mouse` / `ui_keyboard`: the UI wants this event (ImGui's capture flags).
  void handle_event(const InputEvent& event, bool ui_mouse, bool ui_keyboard);
  void cancel_gesture();

  // --- Commands -------------------------------------------------------------------------
  // Undoes the current step's whole group of like steps (UndoStack::groups).
  void undo_group();
  void undo();
  void redo();
  // Jumps to step `index` of the undo history (UndoStack::label), as undos or redos would.
  void go_to_history(std::size_t index);
  void select_all();
  void clear_selection();
  void invert_selection();
  void grow_selection();
  // The connected piece around the selection (Ctrl+L), or up to edges sharper than
  // tools.linked_angle_deg (Ctrl+Shift+L).
  void select_linked(bool by_angle);
  void shrink_selection();
  // Hide and reveal (editor_visibility.cpp, face_visibility.h): H hides the selection, Shift+H
  // every face but the selection, Alt+H shows all and selects what was hidden. Undo steps,
  // with a message saying how many faces are hidden.
  // Edge loops (face_ring.h): the ring of quads across the edge nearest the cursor on the face
  // under it; Alt+click with the Select tool, Shift+Alt+click adds. False when nothing was
  // selected (not on the surface, or no quad at that edge: the status bar says so).
  bool select_loop_at_cursor(bool add);
  void hide_selected();
  void hide_unselected();
  void reveal_all();
  void make_handle(HandleMode mode);  // from the selection
  // Vertex mode (1) or face mode (3): converts the selection (vertex_selection.h) as an undo
  // step and says what the mode does.
  void set_selection_mode(SelectionMode mode);
  // Soft selection (soft_selection.h): the handle's falloff radius in world units (0: off), an
  // undo step; says how many faces it reaches. O turns the active handle's on (the last
  // radius, at first a tenth of the diagonal) and off; Alt + wheel scales it.
  void set_falloff_radius(int index, double radius);
  void toggle_falloff();
  // Vertex mode while the edit state holds a vertex selection (so undo brings the mode back).
  SelectionMode selection_mode() const;
  // The faces the selection stands for: in face mode the selected faces, in vertex mode every
  // face touching a selected vertex (what a handle takes).
  FaceMask selection_as_faces() const;
  void delete_handle(int index);
  void reset_handle(int index);
  void reset_all_handles();
  // The editor's solver settles until converged; Stop ends a solve early, where it is, and
  // Continue solves on from there (to convergence). False when it had not stopped.
  void stop_solving();
  bool continue_solving();
  void set_active_handle(int index);
  void set_handle_mode(int index, HandleMode mode);

  // --- Pivots (editor_pivot.cpp, pivot.h) -------------------------------------------------
  // Each is an undo step that leaves the handle's faces where they are; a mirror twin's pivot
  // follows as its mirror image. False (with a message where the user asked for something
  // impossible) when nothing changed.
  // The pivot as a point of the handle's rest pose (the scenario's transform `center`).
  bool set_pivot(int index, const Vec3& rest_point);
  // The same without an undo step, for a panel field while it is dragged (commit() at its end).
  bool place_pivot(int index, const Vec3& rest_point);
  // The pivot where `world` is in the view now (the point moves with the handle).
  bool set_pivot_at(int index, const Vec3& world);
  bool pivot_to_selection(int index);      // the selected faces' centre as shown now
  bool pivot_to_rest_centroid(int index);  // where a new handle's pivot is
  // The active handle's pivot to the surface under the cursor (Shift+S, Ctrl+Shift+right-click).
  bool pivot_to_cursor();

  // --- Symmetry (editor_mirror.cpp) ------------------------------------------------------
  // Turns mirroring across the plane perpendicular to `axis` on or off; turning it on
  // matches the twin faces (once per mesh and axis) and says how many were matched and how.
  void set_mirror(int axis, bool on);
  // The twin faces across `axis` (matched on first use), or null without a document.
  const MirrorMap* mirror_map(int axis);
  // The status of mirroring across `axis` ("" when off): faces matched, by what.
  std::string mirror_summary(int axis) const;
  // Per face: 1 where a mirror that is on has no twin for it (the view shades those: edits
  // reach them on one side only). Empty while no mirror is on.
  std::vector<char> faces_without_twin();

  void frame_all();
  void frame_selection();  // the selection, else the active handle, else everything
  // The view direction becomes the model's front and the camera's up its up, each snapped to
  // the nearest signed world axis (editor_orientation.cpp); an undo step, saved with the
  // scenario. The front, right and top views, and the turntable, follow the orientation.
  void set_front_from_view();
  void set_tool(Tool tool);
  // Panels edit document()->state directly, call live_edit() while a widget is active and
  // commit() when it is released (one undo step per widget interaction). live_edit() sends
  // the change to the solver; commit() also redraws the overlay colours.
  void live_edit();
  void commit(const std::string& label);
  void request_quit() { quit_requested_ = true; }

  // --- Keys (editor_keys.cpp) -------------------------------------------------------------
  // The user's key map (Edit > Preferences > Keys; changes there take effect at once).
  const KeyMap& key_map() const { return preferences_.keys; }
  // Runs a keyboard command as its key would. False for the window's own commands (open,
  // save, export, screenshot, panels, controls), which the window runs, and without effect.
  bool run_action(Action action);
  bool quit_requested() const { return quit_requested_; }
  void info(const std::string& text);
  void error(const std::string& text);
  // An error said in the status bar only, without a popup to dismiss: for a command that
  // cannot run now (nothing selected, nothing open, nothing recorded), which the user fixes
  // with the next click. Counted as an error all the same (a script stops on it).
  void error_in_status(const std::string& text);

  // --- State ----------------------------------------------------------------------------
  Document* document() { return doc_.get(); }
  const Document* document() const { return doc_.get(); }
  Camera& camera() { return camera_; }
  const Camera& camera() const { return camera_; }
  ToolSettings tools;
  DisplaySettings display;
  // Session recording and playback (docs/sessions.md), driven from update().
  SessionControl sessions;
  const SolverStatus& solver_status() const { return status_; }
  std::shared_ptr<const SolverGeometry> geometry() const { return geometry_; }
  // Deformed vertex positions shown now (rest positions before the first result).
  const std::vector<Vec3>& positions() const;
  const std::vector<Message>& messages() const { return messages_; }
  // What the status bar says on its left: the newest message while it is fresh (10 s, an
  // error 30 s) and no tool or handle mode changed since; else "" (the bar shows its hint).
  const Message* current_message() const;
  // Errors reported so far (a script or screenshot run fails when it grows).
  size_t error_count() const { return error_count_; }
  // The newest error not yet shown in a popup ("" when none).
  std::string take_error_popup();

  // --- For drawing overlays -------------------------------------------------------------
  Gesture gesture() const { return gesture_; }
  glm::dvec2 cursor_pixels() const { return cursor_; }  // viewport pixels
  bool cursor_in_viewport() const;
  const std::vector<glm::dvec2>& lasso() const { return lasso_; }
  glm::dvec2 gesture_start() const { return press_; }
  int hovered_handle() const { return hovered_handle_; }
  // The gizmo on the active handle, if the tool shows one.
  bool gizmo_visible(GizmoKind& kind, glm::dvec3& center) const;
  // The gizmo's axes (columns) in tools.gizmo_orientation for the active handle as posed now.
  glm::dmat3 gizmo_axes() const;
  GizmoPart gizmo_hover() const { return gizmo_hover_; }
  GizmoPart gizmo_active() const { return gizmo_ ? gizmo_->part() : GizmoPart::None; }
  bool brush_visible() const;
  // World position of a handle's pivot as drawn now (where the gizmo is).
  glm::dvec3 handle_pivot(int index) const;
  // Window coordinates of a handle's pivot (for scripts); false when there is no such handle.
  bool handle_window_position(const std::string& name, double& x, double& y) const;

  // Frame statistics: time between frames (smoothed), and frame times during the last mouse
  // gesture (a handle drag, an orbit, a stroke...), also printed on stdout when it ends.
  // The time between frames, smoothed, as shown: refreshed twice a second, so that the panels
  // showing it do not change (and need not be drawn again) at every frame.
  double frame_ms() const { return shown_frame_ms_; }
  // The window drew a new picture this frame (counted in the gesture's figures).
  void count_drawn_frame();
  // The next update() follows a wait for events (nothing moved): its time is not a frame
  // time, for the frame-time display nor for a gesture's statistics.
  void mark_idle_wait() { idle_wait_ = true; }
  bool idle() const { return idle_; }  // the last update followed such a wait
  struct GestureStats {
    std::string what;  // "drag 'top'", "orbit", ...
    int frames = 0;
    double total_ms = 0.0, max_ms = 0.0;
    // How often the mesh shown changed during the gesture: what the artist sees move (on a
    // big mesh, fewer times than frames are drawn).
    int mesh_updates = 0;
    int preview_updates = 0;  // of them, drags' previews (SolverGeometry::preview)
    FrameTimes times;         // each frame's time, for its median and 90th percentile
    int drawn_frames = 0;     // of the frames, those that drew a new picture
    double updates_per_second() const { return total_ms > 0 ? 1000.0 * mesh_updates / total_ms : 0.0; }
  };
  const GestureStats& last_gesture_stats() const { return gesture_stats_; }

 private:
  void on_mouse_button(const InputEvent& e, bool ui_mouse);
  void on_cursor(const InputEvent& e);
  void on_scroll(const InputEvent& e, bool ui_mouse);
  void on_key(const InputEvent& e);
  void begin_tool_gesture(int mods);
  void update_gesture();
  void end_gesture();
  // Commands that add, remove, renumber or re-mode handles end a gesture under way first, as
  // releasing the button would: a drag holds its handle by index, and must not go on with
  // whichever handle takes that index (a fixed region, after a Delete during the drag).
  void end_gesture_before_edit();
  // The handle a drag or gizmo gesture started on is still at drag_group_ and may be posed.
  bool dragged_handle_intact() const;
  // Stops a gesture without an undo step and without restoring the state: for a drag whose
  // handle is gone.
  void drop_gesture();
  void brush_dab();
  std::vector<int> faces_under(const ScreenShape& shape);
  // The pick buffer under a shape's bounds (empty without a picker).
  PickImage pick_image_under(const ScreenShape& shape);
  std::vector<ProjectedPoint> project_points(const std::vector<Vec3>& points) const;
  int face_at_cursor();
  // The surface point under the cursor as shown now: the pick buffer's depth along the mouse
  // ray, else the centroid of the face there.
  std::optional<Vec3> surface_point_at_cursor();
  void update_hover();
  void sync_solver();
  void apply_document(std::unique_ptr<Document> doc);
  // A face mask made by a command; in vertex mode its faces' corners become the selection.
  void set_selection(const FaceMask& mask, const std::string& label);
  void hide_faces(bool selected);  // the selection's faces, or every other face
  // Vertex mode: the selected vertices and the faces within them, without an undo step.
  void store_vertex_selection(VertexMask vertices);
  void set_vertex_selection(VertexMask vertices, const std::string& label);
  // A brush, box, lasso or click gesture's items (faces, or vertices in vertex mode).
  void select_picked(const std::vector<int>& items);
  std::vector<int> vertices_under(const ScreenShape& shape);
  int vertex_at_cursor();
  // Every selection change ends here: mirrored to the twin faces, hidden faces deselected.
  void finish_selection(const FaceMask& before, FaceMask& after);
  // Symmetry hooks: copy a selection or paint change to the twin faces of every mirror axis
  // that is on, and pose the leading handle's twin as its mirror image.
  void mirror_selection(const FaceMask& before, FaceMask& after);
  FactorArray mirror_paint(const FactorArray& before, FactorArray after);
  void follow_mirror();
  // Turns the camera's frame to the document's orientation (Camera::set_model_axes).
  void follow_orientation(bool keep_view);
  // make_handle with a mirror on: the selection split into mirrored pairs when it lies on
  // both sides (or one) away from the plane. False when it is not such a selection.
  bool make_mirrored_handles(const std::vector<int>& faces, HandleMode mode);
  // After a handle is made with the Select tool, the Drag tool, so that it can be posed at
  // once. Returns what the message about the new handle adds ("" when the tool stays).
  std::string drag_tool_after_making(HandleMode mode);

  std::function<void()> wake_ui_;
  std::unique_ptr<Document> doc_;
  Camera camera_;
  ViewportRect viewport_;
  Picker* picker_ = nullptr;
  std::unique_ptr<SolverWorker> worker_;

  std::array<std::shared_ptr<const MirrorMap>, 3> mirror_maps_;  // per axis, per document

  // Unsaved work.
  void open_file(const std::string& path, bool recovered);
  // The document as saved at `path`, its mesh named `mesh` (the document's, or a link to it).
  std::string scenario_text(const std::string& path, const std::string& mesh) const;
  void forget_autosave();
  std::optional<DiscardQuestion> discard_question_;
  double autosave_every_ = 120.0, last_autosave_ = 0.0;
  RecentFiles recent_;
  Preferences preferences_;
  int stand_in_above_ = kStandInAboveInSoftware;
  double settle_limit_ = 0.0;        // seconds; 0: settle until converged
  double last_submit_clock_ = 0.0;   // clock_ when the solver was last given something to do
  double settle_stopped_at_ = -1.0;  // the submission the settle limit stopped


  // Solver bookkeeping.
  EditState sent_;
  bool sent_any_ = false;
  // Serial of the first solver problem of the current document: older geometry is dropped.
  std::uint64_t document_serial_ = 0;
  SolverStatus status_;
  std::shared_ptr<const SolverGeometry> geometry_;
  std::uint64_t shown_serial_ = 0;
  bool geometry_changed_ = true, overlay_changed_ = true;
  DisplaySettings last_display_;
  ToolSettings last_tools_;

  // File task.
  std::future<std::function<void()>> task_;  // returns the work to finish on the UI thread
  bool task_is_open_ = false;                 // the task opens a file (another may replace it)
  struct QueuedOpen {
    std::string path;
    bool recovered = false;
  };
  std::optional<QueuedOpen> queued_open_;     // asked for while a task ran: the newest only
  // Cancelled opens still reading, kept until they end (a future of std::async blocks in its
  // destructor), their documents dropped.
  std::vector<std::future<std::function<void()>>> cancelled_opens_;
  std::string task_label_;
  double task_started_ = 0.0;
  double clock_ = 0.0;

  // Gesture.
  Gesture gesture_ = Gesture::None;
  int gesture_button_ = -1;
  glm::dvec2 cursor_{-1.0}, press_{0.0}, last_{0.0};
  std::vector<glm::dvec2> lasso_;
  EditState gesture_start_state_;
  int drag_group_ = -1;
  std::shared_ptr<const std::vector<int>> drag_faces_;  // the dragged handle's, to know it again
  glm::dvec3 drag_anchor_{0.0};
  Pose drag_start_pose_;
  SelectOp select_op_ = SelectOp::Add;
  // An Alt+click orbits when it moves; one that does not selects a loop (Shift adds).
  bool loop_click_ = false, loop_click_adds_ = false;
  bool paint_erase_ = false;
  std::unique_ptr<GizmoDrag> gizmo_;
  GizmoPart gizmo_hover_ = GizmoPart::None;
  int hovered_handle_ = -1;
  double last_hover_pick_ = -1.0;
  double last_paint_sync_ = 0.0;
  int held_mods_ = 0;
  bool quit_requested_ = false;
  long message_serial_ = 0;
  long stale_up_to_ = 0;  // messages up to this serial predate the last tool or mode change

  std::vector<Message> messages_;
  std::string error_popup_;
  size_t error_count_ = 0;
  double frame_ms_ = 0.0;
  double shown_frame_ms_ = 0.0, frame_ms_shown_at_ = 0.0;
  bool idle_wait_ = false, idle_ = false;
  GestureStats gesture_stats_, current_gesture_;
};

}  // namespace primo::editor
