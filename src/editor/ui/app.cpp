#include "app.h"

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <imgui_internal.h>

#include <atomic>
#include <cctype>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <thread>

#include "user_files/autosave.h"
#include "editor.h"
#include "document/selection/shown_edges.h"
#include "view/face_colors.h"
#include "view/frame_pacer.h"
#include "view/shown_picture.h"
#include "draw_data_fingerprint.h"
#include "render/gl.h"
#include "view/ground_grid.h"
#include "panels.h"
#include "paths.h"
#include "preferences_window.h"
#include "primo/util/error.h"
#include "primo/io/input_files.h"
#include "render/renderer.h"
#include "input/run_deadline.h"
#include "render/screenshot.h"
#include "input/script.h"
#include "ui_input.h"

namespace primo::editor {
namespace {

// SIGINT, SIGTERM and SIGHUP (Ctrl+C in the terminal, a logout, a kill) only set this flag:
// writing files is not safe inside a signal handler, so the main loop autosaves the unsaved
// work and quits at its next frame.
std::atomic<bool> g_termination_requested{false};
extern "C" void on_termination_signal(int) { g_termination_requested = true; }

std::string g_glfw_error;

void glfw_error(int code, const char* description) {
  char text[64];
  std::snprintf(text, sizeof text, " (GLFW error 0x%x)", code);
  g_glfw_error = std::string(description) + text;
}

void apply_style(float scale) {
  ImGuiStyle& s = ImGui::GetStyle();
  ImGui::StyleColorsDark();
  s.WindowRounding = 0.0f;
  s.FrameRounding = 4.0f;
  s.GrabRounding = 4.0f;
  s.PopupRounding = 6.0f;
  s.ScrollbarRounding = 6.0f;
  s.TabRounding = 4.0f;
  s.WindowBorderSize = 0.0f;
  s.FrameBorderSize = 0.0f;
  s.ItemSpacing = ImVec2(8, 6);
  s.FramePadding = ImVec2(7, 4);
  s.WindowPadding = ImVec2(10, 10);
  ImVec4* c = s.Colors;
  c[ImGuiCol_WindowBg] = ImVec4(0.135f, 0.14f, 0.155f, 0.97f);
  c[ImGuiCol_PopupBg] = ImVec4(0.15f, 0.155f, 0.17f, 0.98f);
  c[ImGuiCol_MenuBarBg] = ImVec4(0.11f, 0.115f, 0.13f, 1.0f);
  c[ImGuiCol_FrameBg] = ImVec4(0.21f, 0.22f, 0.245f, 1.0f);
  c[ImGuiCol_FrameBgHovered] = ImVec4(0.27f, 0.29f, 0.32f, 1.0f);
  c[ImGuiCol_FrameBgActive] = ImVec4(0.30f, 0.33f, 0.37f, 1.0f);
  c[ImGuiCol_Header] = ImVec4(0.22f, 0.24f, 0.28f, 1.0f);
  c[ImGuiCol_HeaderHovered] = ImVec4(0.26f, 0.36f, 0.52f, 1.0f);
  c[ImGuiCol_HeaderActive] = ImVec4(0.26f, 0.45f, 0.75f, 1.0f);
  c[ImGuiCol_Button] = ImVec4(0.23f, 0.25f, 0.29f, 1.0f);
  c[ImGuiCol_ButtonHovered] = ImVec4(0.28f, 0.40f, 0.60f, 1.0f);
  c[ImGuiCol_ButtonActive] = ImVec4(0.26f, 0.45f, 0.75f, 1.0f);
  c[ImGuiCol_SliderGrab] = ImVec4(0.36f, 0.56f, 0.88f, 1.0f);
  c[ImGuiCol_SliderGrabActive] = ImVec4(0.45f, 0.65f, 0.95f, 1.0f);
  c[ImGuiCol_CheckMark] = ImVec4(0.45f, 0.68f, 1.0f, 1.0f);
  c[ImGuiCol_PlotHistogram] = ImVec4(0.36f, 0.6f, 0.95f, 1.0f);
  c[ImGuiCol_TitleBgActive] = ImVec4(0.16f, 0.2f, 0.28f, 1.0f);
  s.ScaleAllSizes(scale);
}

void load_font(float scale) {
  ImGuiIO& io = ImGui::GetIO();
  for (const char* path :
       {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/TTF/DejaVuSans.ttf"}) {
    if (std::filesystem::exists(path) && io.Fonts->AddFontFromFileTTF(path, 15.0f * scale)) return;
  }
  ImFontConfig config;
  config.SizePixels = 13.0f * scale;
  io.Fonts->AddFontDefault(&config);
}

// Whether the current context draws in software (Mesa's llvmpipe: machines without a GPU,
// remote desktops, Xvfb).
bool software_renderer() {
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string name = renderer ? renderer : "";
  return name.find("llvmpipe") != std::string::npos || name.find("softpipe") != std::string::npos ||
         name.find("swrast") != std::string::npos;
}

// Multisampling of the scene: 4 samples on a GPU, none on a software renderer (llvmpipe under
// Xvfb pays 3-4x per frame for it). PRIMO_MSAA=N forces N.
int scene_samples(bool software) {
  if (const char* msaa = std::getenv("PRIMO_MSAA"); msaa && *msaa) return std::atoi(msaa);
  return software ? 0 : 4;
}

class App : public ScriptHost {
 public:
  App(const EditorOptions& options, GLFWwindow* window)
      : options_(options), window_(window), editor_([] { glfwPostEmptyEvent(); }) {}

  int run();

  // ScriptHost
  void push_input(const InputEvent& e) override { queue_.push_back(e); }
  void locate(const ScriptCommand& c, double& x, double& y) override;
  void cursor(double& x, double& y) override { x = ui_input_.cursor().x, y = ui_input_.cursor().y; }
  bool settled() override { return editor_.settled() && renderer_->has_mesh(); }
  bool nothing_open() override { return !editor_.document() && !editor_.file_task_running(); }
  void run(const ScriptCommand& c) override;

  // GLFW callbacks
  static App& of(GLFWwindow* w) { return *static_cast<App*>(glfwGetWindowUserPointer(w)); }
  void install_callbacks();

 private:
  // Returns whether the frame drew a new picture (one that equals the shown one is not drawn).
  bool frame(double now, double dt);
  void begin_ui_frame(const InputQueue& batch);
  void sync_renderer();
  void draw_picture(const PictureFingerprint& picture, const DisplaySettings& shown,
                    const ViewportRect& vp, int fb_w, int fb_h);
  void take_screenshot(const ViewportRect& vp, int fb_width, int fb_height, bool with_ui_drawn);
  void fail(const std::string& message);
  void stop_at_timeout();
  std::string busy_or_unsettled() const;
  std::string autosave_unsaved_work();
  bool out_of_time() const { return deadline_ && deadline_->expired(); }
  void finish_file_task();

  EditorOptions options_;
  GLFWwindow* window_;
  // Scripted and --screenshot runs only. Before the editor, so that its watchdog still runs
  // while the editor shuts down (which waits for an open or save under way).
  std::unique_ptr<RunDeadline> deadline_;
  Editor editor_;
  UiState ui_;
  std::unique_ptr<MeshRenderer> renderer_;
  std::unique_ptr<ScriptPlayer> script_;
  InputQueue queue_;  // GLFW's and the script's events, in order, until a panel frame takes them
  UiInput ui_input_;
  const MeshTopology* shown_topology_ = nullptr;
  HiddenFaces drawn_hidden_;  // the hidden faces the wireframe leaves out
  const ProxyTriangles* shown_proxy_ = nullptr;       // null until the document's proxy is built
  bool software_renderer_ = false;
  std::optional<ModelOrientation> grid_orientation_;  // of the ground grid drawn (none yet)
  int settled_frames_ = 0;
  FramePacer pacer_;
  ShownPicture shown_picture_;
  bool screenshot_run_ = false;
  size_t errors_seen_ = 0;
  std::string shown_title_;
  bool quit_ = false;
  int exit_code_ = 0;
};

void App::install_callbacks() {
  glfwSetWindowUserPointer(window_, this);
  glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
    of(w).queue_.push_back(InputEvent::cursor(x, y));
  });
  glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int mods) {
    of(w).queue_.push_back(InputEvent::mouse(button, action, mods));
  });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double dx, double dy) {
    of(w).queue_.push_back(InputEvent::scroll(dx, dy));
  });
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int scancode, int action, int mods) {
    InputEvent e = InputEvent::key_event(key, action, mods);
    e.scancode = scancode;
    of(w).queue_.push_back(e);
  });
  glfwSetCharCallback(
      window_, [](GLFWwindow* w, unsigned c) { of(w).queue_.push_back(InputEvent::character(c)); });
  glfwSetDropCallback(window_, [](GLFWwindow* w, int count, const char** paths) {
    of(w).queue_.push_back(InputEvent::drop(std::vector<std::string>(paths, paths + count)));
  });
  glfwSetWindowRefreshCallback(window_, [](GLFWwindow* w) { of(w).shown_picture_.forget(); });
  glfwSetWindowFocusCallback(window_, ImGui_ImplGlfw_WindowFocusCallback);
  glfwSetCursorEnterCallback(window_, ImGui_ImplGlfw_CursorEnterCallback);
}

void App::locate(const ScriptCommand& c, double& x, double& y) {
  if (c.anchor == ScriptCommand::Anchor::Handle) {
    if (!editor_.handle_window_position(c.handle, x, y))
      throw Error("no handle named '" + c.handle + "'");
  } else if (c.anchor == ScriptCommand::Anchor::Center) {
    const ViewportRect& vp = editor_.viewport();
    x = vp.x + vp.width * 0.5;
    y = vp.y + vp.height * 0.5;
  } else {
    x = y = 0.0;
  }
  x += c.x;
  y += c.y;
}

void App::run(const ScriptCommand& c) {
  using K = ScriptCommand::Kind;
  const size_t errors_before = editor_.error_count();
  switch (c.kind) {
    case K::Open:
      // As a person would, a script opens the next file once the last open or save is done
      // (the editor refuses a second file task); the solver may still be busy.
      finish_file_task();
      editor_.open(c.text);
      break;
    case K::SaveMesh:
      editor_.save_mesh(c.text);
      finish_file_task();  // a script goes on once the file is there
      break;
    case K::SaveScenario:
      editor_.save_scenario(c.text);
      break;
    case K::Screenshot:
      ui_.screenshot_path = c.text;
      ui_.screenshot_with_ui = c.with_ui;
      break;
    case K::Echo:
      std::printf("%s\n", c.text.c_str());
      break;
    case K::RecordStart:
      editor_.sessions.start_recording(editor_);
      break;
    case K::RecordStop:
      editor_.sessions.stop_recording(editor_);
      break;
    case K::SaveSession:
      editor_.sessions.save(editor_, c.text);
      break;
    case K::PlaySession:
      editor_.sessions.open_playback(editor_, c.text);
      editor_.sessions.play(editor_);
      break;
    case K::Quit:
      quit_ = true;
      break;
    default:
      break;
  }
  if (editor_.error_count() != errors_before) throw Error(editor_.messages().back().text);
}

void App::fail(const std::string& message) {
  std::fprintf(stderr, "primo edit: error: %s\n", message.c_str());
  exit_code_ = 1;
  quit_ = true;
}

// Waits for the open or save under way; throws when the --timeout runs out first (frame()
// then reports the timeout, not this).
void App::finish_file_task() {
  while (editor_.file_task_running()) {
    if (out_of_time()) throw Error("still busy with " + editor_.file_task_label());
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    editor_.update(0.0);
  }
}

// What SIGTERM does too: the work is kept for recovery at the next start (autosave.h).
// Returns how the message goes on: where the work went, or that it could not be kept.
std::string App::autosave_unsaved_work() {
  if (!editor_.has_unsaved_changes()) return "";
  if (!editor_.autosave_before_exit()) return "; the unsaved work could not be autosaved";
  return "; the unsaved work is autosaved to " + autosave_path(editor_.document()->mesh_path);
}

// Why a --screenshot run is not done: the input is still loading (a huge file, or a pipe that
// never ends), or its solve has not settled.
std::string App::busy_or_unsettled() const {
  if (!editor_.file_task_running()) return "the solve did not settle";
  std::string label = editor_.file_task_label();  // "Opening bar.obj"
  if (!label.empty()) label[0] = char(std::tolower(static_cast<unsigned char>(label[0])));
  return "still " + label;
}

// One line naming what ran out of time (the script and its line, or the input whose solve did
// not settle), exit status 1, and the unsaved work autosaved.
void App::stop_at_timeout() {
  const std::string what =
      script_ ? options_.script + ":" + std::to_string(script_->line()) +
                    ": the script did not finish within the --timeout of " + deadline_->shown()
              : options_.input + ": " + busy_or_unsettled() + " within the --timeout of " +
                    deadline_->shown() + " (nothing was written)";
  fail(what + autosave_unsaved_work());
}

void App::sync_renderer() {
  const Document* doc = editor_.document();
  if (!doc) return;
  if (shown_topology_ != doc->topology.get()) {
    renderer_->set_topology(*doc->topology);
    shown_topology_ = doc->topology.get();
    drawn_hidden_.reset();  // the topology's edges are all drawn
    shown_proxy_ = nullptr;
    grid_orientation_.reset();
  }
  if (!grid_orientation_ || !(*grid_orientation_ == doc->state.orientation)) {
    renderer_->set_ground_grid(
        make_ground_grid(doc->topology->rest_points, doc->state.orientation));
    grid_orientation_ = doc->state.orientation;
  }
  if (!shown_proxy_) {
    if (const ProxyTriangles* proxy = doc->proxy->ready()) {
      renderer_->set_proxy(*proxy);
      shown_proxy_ = proxy;
    }
  }
  if (editor_.take_geometry_changed()) {
    if (const auto g = editor_.geometry()) {
      renderer_->set_geometry(g->render_positions, g->render_normals);
      renderer_->set_prism_corners(g->prism_corners);
    } else {
      const MeshTopology& t = *doc->topology;
      std::vector<float> p(3 * t.rest_points.size()), n;
      for (size_t v = 0; v < t.rest_points.size(); ++v)
        for (int i = 0; i < 3; ++i) p[3 * v + i] = float(t.rest_points[v][i]);
      compute_vertex_normals(t, t.rest_points, n);
      renderer_->set_geometry(p, n);
      renderer_->set_prism_corners({});
    }
  }
  if (editor_.take_overlay_changed()) {
    OverlayInputs in;
    in.state = &doc->state;
    in.n_faces = doc->n_faces();
    in.paint_overlay = editor_.display.paint_overlay;
    in.paint_layer = editor_.tools.tool == Tool::Paint ? editor_.tools.paint_layer
                     : doc->state.height_factor        ? PaintLayer::Height
                                                       : PaintLayer::Width;
    const auto g = editor_.geometry();
    if (editor_.display.heat_map && g && !g->face_energy.empty()) {
      in.face_energy = &g->face_energy;
      in.energy_scale = g->energy_scale;
    }
    in.hovered_handle = editor_.hovered_handle();
    const std::vector<char> without_twin = editor_.faces_without_twin();
    in.without_twin = &without_twin;
    renderer_->set_face_colors(face_overlay_colors(in));
    // The wireframe loses the edges of hidden faces (uploaded again when the hidden set changes).
    if (!same_hidden(drawn_hidden_, doc->state.hidden)) {
      renderer_->set_edges(shown_edges(*doc->topology, doc->state.hidden));
      drawn_hidden_ = doc->state.hidden;
    }
    if (const auto& vertices = doc->state.vertex_selection)
      renderer_->set_vertex_points(shown_vertices(*doc->topology, doc->state.hidden),
                                   selected_vertices(*vertices, doc->state.hidden, *doc->topology));
    else
      renderer_->set_vertex_points({}, {});
  }
}

void App::take_screenshot(const ViewportRect& vp, int fb_width, int fb_height, bool whole_window) {
  try {
    if (whole_window) {
      save_screenshot(ui_.screenshot_path, 0, 0, fb_width, fb_height);
    } else {
      const int x = int(vp.x * vp.scale), w = int(vp.width * vp.scale),
                h = int(vp.height * vp.scale);
      const int y = fb_height - int(vp.y * vp.scale) - h;
      save_screenshot(ui_.screenshot_path, x, y, w, h);
    }
    editor_.info("Saved a screenshot to " + ui_.screenshot_path);
  } catch (const std::exception& e) {
    editor_.error(e.what());
    if (script_ || !options_.screenshot.empty()) fail(e.what());
  }
  ui_.screenshot_path.clear();
}

// A Dear ImGui frame for one batch of the queued events (ui_input.h): fed, begun, and each
// event routed to whoever takes it as of this frame.
void App::begin_ui_frame(const InputQueue& batch) {
  ui_input_.feed(batch);
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ui_input_.apply_pointer();
  ImGuiIO& io = ImGui::GetIO();
  // Frames for a batch follow each other within microseconds; Dear ImGui needs time to pass.
  io.DeltaTime = std::max(io.DeltaTime, 1e-4f);
  ImGui::NewFrame();

  int win_w, win_h, fb_w, fb_h;
  glfwGetWindowSize(window_, &win_w, &win_h);
  glfwGetFramebufferSize(window_, &fb_w, &fb_h);
  const float scale = win_w > 0 ? float(fb_w) / float(win_w) : 1.0f;
  if (ui_.show_panels && ui_.menu_height == 0.0f) ui_.menu_height = ImGui::GetFrameHeight();
  editor_.set_viewport(viewport_rect(ui_, float(win_w), float(win_h), scale));
  route_input(batch, editor_, ui_);
}

bool App::frame(double now, double dt) {
  if (script_ && !script_->finished()) {
    script_->update(now, *this);
    if (script_->failed()) out_of_time() ? stop_at_timeout() : fail(script_->error());
  }
  // As many panel frames as the queued events need, each laid out; the last one is drawn. A
  // frame drawn slowly (a big mesh in software) still sees every key tap as a press.
  constexpr int kMostPanelFramesPerFrame = 64;  // the rest waits for the next frame
  for (int panel_frames = 1;; ++panel_frames) {
    const auto taken = queue_.begin() + std::ptrdiff_t(one_ui_frame_of_input(queue_));
    const InputQueue batch(queue_.begin(), taken);
    queue_.erase(queue_.begin(), taken);
    begin_ui_frame(batch);
    if (queue_.empty() || panel_frames == kMostPanelFramesPerFrame) break;
    draw_ui(editor_, ui_);
    ImGui::EndFrame();
  }

  int win_w, win_h, fb_w, fb_h;
  glfwGetWindowSize(window_, &win_w, &win_h);
  glfwGetFramebufferSize(window_, &fb_w, &fb_h);
  const float scale = win_w > 0 ? float(fb_w) / float(win_w) : 1.0f;
  const ViewportRect vp = editor_.viewport();
  editor_.update(dt);
  sync_renderer();
  draw_ui(editor_, ui_);
  if (ui_.quit_requested || editor_.quit_requested()) quit_ = true;
  if (const Document* doc = editor_.document()) {
    const std::string& name = doc->scenario_path.empty() ? doc->mesh_path : doc->scenario_path;
    const std::string title = "PriMo - " + std::filesystem::path(name).filename().string();
    if (title != shown_title_) glfwSetWindowTitle(window_, (shown_title_ = title).c_str());
  }
  ImGui::Render();

  const int vx = int(vp.x * scale), vw = int(vp.width * scale), vh = int(vp.height * scale);
  const int vy = fb_h - int(vp.y * scale) - vh;
  renderer_->set_interactive(editor_.gesture() != Editor::Gesture::None);
  // A screenshot of the 3D view alone is a picture of the model, as a render is in Blender:
  // the ground grid, an aid for looking around, stays out of it (docs/editor.md).
  DisplaySettings shown = editor_.display;
  if ((!ui_.screenshot_path.empty() && !ui_.screenshot_with_ui) ||
      (screenshot_run_ && !script_ && !options_.screenshot_ui))
    shown.grid = false;
  const PictureFingerprint picture{renderer_->scene_fingerprint(shown, vw, vh),
                                   draw_data_fingerprint(*ImGui::GetDrawData()),
                                   vx, vy, vw, vh, fb_w, fb_h};
  // The stand-in is drawn only in motion; `settled` counts a request the solver has not
  // taken up yet as unsettled.
  if (const Document* doc = editor_.document())
    doc->proxy->set_paused(
        stand_in_waits(software_renderer_, editor_.settled(), renderer_->in_motion()));

  // A --screenshot run: once the view shows a settled solve (two frames in a row).
  if (screenshot_run_ && !script_) {
    if (editor_.error_count() > errors_seen_) {
      fail("could not prepare the screenshot: " + editor_.messages().back().text);
    } else if (settled() && ++settled_frames_ >= 2) {
      ui_.screenshot_path = options_.screenshot;
      ui_.screenshot_with_ui = options_.screenshot_ui;
      quit_ = true;
    }
  }
  errors_seen_ = editor_.error_count();
  const bool drawn = !ui_.screenshot_path.empty() || shown_picture_.needs_drawing(picture);
  if (drawn) draw_picture(picture, shown, vp, fb_w, fb_h);
  if (script_ && script_->finished() && screenshot_run_ && !quit_) {
    ui_.show_panels = options_.screenshot_ui;  // then the --screenshot after the script
    script_.reset();
  }
  return drawn;
}

// Draws the frame's picture (the 3D view, then the panels over it) and shows it.
void App::draw_picture(const PictureFingerprint& picture, const DisplaySettings& shown,
                       const ViewportRect& vp, int fb_w, int fb_h) {
  glViewport(0, 0, fb_w, fb_h);
  glClearColor(0.11f, 0.115f, 0.13f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  renderer_->draw(shown, picture.view_x, picture.view_y, picture.view_width, picture.view_height);
  if (!ui_.screenshot_path.empty() && !ui_.screenshot_with_ui)
    take_screenshot(vp, fb_w, fb_h, false);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (!ui_.screenshot_path.empty()) take_screenshot(vp, fb_w, fb_h, true);
  glfwSwapBuffers(window_);
  shown_picture_.drawn(picture);
  editor_.count_drawn_frame();
}

int App::run() {
  install_callbacks();
  float xscale = 1.0f, yscale = 1.0f;
  glfwGetWindowContentScale(window_, &xscale, &yscale);
  load_font(xscale);
  apply_style(xscale);
  ImGui_ImplGlfw_InitForOpenGL(window_, false);
  ImGui_ImplOpenGL3_Init("#version 330 core");

  try {
    software_renderer_ = software_renderer();
    renderer_ = std::make_unique<MeshRenderer>(shader_dir(), scene_samples(software_renderer_));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "primo edit: error: %s\n", e.what());
    return 1;
  }
  renderer_->set_camera(&editor_.camera());
  editor_.set_picker(renderer_.get());
  editor_.set_stand_in_above(software_renderer_ ? kStandInAboveInSoftware : kStandInAboveOnGpu);
  if (!options_.script.empty()) {
    try {
      script_ = std::make_unique<ScriptPlayer>(
          parse_script(read_input_file(options_.script), options_.script));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "primo edit: error: %s\n", e.what());
      return 2;
    }
  }
  screenshot_run_ = !options_.screenshot.empty();
  if (screenshot_run_ && !options_.screenshot_ui) ui_.show_panels = false;
  // Scripted and screenshot runs are automation: no recovery prompt in their way.
  if (script_ || screenshot_run_) ui_.recovery_checked = true;
  // Automation must end: a script may wait, a solve may never settle (docs/editor.md).
  if (script_ || screenshot_run_)
    deadline_ =
        std::make_unique<RunDeadline>(options_.timeout, script_ ? options_.script : options_.input);
  if (!options_.input.empty()) editor_.open(options_.input);

  double last = glfwGetTime();
  for (;;) {
    if (g_termination_requested) {
      autosave_unsaved_work();
      break;
    }
    // The window's close button asks first when there is unsaved work.
    if (glfwWindowShouldClose(window_)) {
      if (editor_.ask_to_quit()) break;
      glfwSetWindowShouldClose(window_, GLFW_FALSE);
    }
    if (quit_) break;
    if (out_of_time()) {
      stop_at_timeout();
      break;
    }
    const bool animate = !queue_.empty() || editor_.solver_status().busy() ||
                         editor_.file_task_running() || script_ ||
                         screenshot_run_ || editor_.gesture() != Editor::Gesture::None ||
                         editor_.camera().update(0.0) || renderer_->drew_proxy();
    if (animate) {
      glfwPollEvents();
    } else {
      glfwWaitEventsTimeout(0.25);
      editor_.mark_idle_wait();
    }
    double now = glfwGetTime();
    // At most about 60 frames a second while animating, fewer while the solver works and
    // drawing is slow (FramePacer): the rest of the CPU goes to the solver.
    const double interval = pacer_.interval(editor_.solver_status().busy());
    if (animate && now - last < interval) {
      std::this_thread::sleep_for(std::chrono::duration<double>(interval - (now - last)));
      now = glfwGetTime();
    }
    const double dt = now - last;
    last = now;

    try {
      // The pace follows the cost of drawing: a frame that drew nothing costs little.
      if (frame(now, dt)) pacer_.frame_drawn(glfwGetTime() - now);
    } catch (const std::exception& e) {
      // A bug must not take the user's work down: report it and go on with the next frame.
      if (ImGui::GetCurrentContext()->WithinFrameScope) {
        ImGui::ErrorCheckEndFrameRecover(nullptr);
        ImGui::EndFrame();
      }
      queue_.clear();
      editor_.error(std::string("internal error: ") + e.what());
      if (script_ || screenshot_run_) fail(std::string("internal error: ") + e.what());
    }
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  return exit_code_;
}

}  // namespace

int run_editor(const EditorOptions& options) {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, on_termination_signal);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  glfwSetErrorCallback(glfw_error);
  if (!glfwInit()) {
    std::fprintf(stderr,
                 "primo edit: error: cannot open a window: %s. The editor needs a display; "
                 "headless, run it under xvfb-run.\n",
                 g_glfw_error.c_str());
    return 1;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(options.width, options.height, "PriMo", nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "primo edit: error: cannot create an OpenGL 3.3 core window: %s\n",
                 g_glfw_error.c_str());
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  int code = 1;
  {
    App app(options, window);
    code = app.run();
  }
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return code;
}

}  // namespace primo::editor
