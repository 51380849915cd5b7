// SPDX-License-Identifier: MIT
// The editor's Dear ImGui interface: scene tree, body parameters, run controls, and the speed↔accuracy
// panel. It draws into its own ImGui context and needs no graphics backend: a host with a window hands
// the draw data (ImGui::GetDrawData()) to a renderer; headless runs and tests drive it with synthetic
// mouse input, pressing widgets by their label.
#pragma once

#include "gizmo.h"
#include "input.h"
#include "parts_library.h"
#include "session.h"
#include "trade.h"

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

struct ImGuiContext;

namespace supermodal::editor
{

/// Where a clickable widget was drawn in the last frame, by its label.
struct WidgetRect {
    std::string label; ///< As passed to ImGui ("Pause", "chair_seat", "Modal##dynamics").
    float min_x = 0, min_y = 0, max_x = 0, max_y = 0; ///< Screen rectangle [pixels].
    bool visible = false;                             ///< Not clipped away (scrolled out, collapsed).
};

/// What the Speed / accuracy window showed in its last frame, value by value and as the text drawn.
struct SpeedAccuracyReadout {
    bool shown = false;              ///< The window was drawn with a scene.
    double dt = 0.0;                 ///< Step [s].
    int substeps = 0;                ///< Substeps per step [-].
    double ms_per_step = 0.0;        ///< EditorSession::ms_per_step() [ms].
    double max_penetration = 0.0;    ///< world_max_penetration [m].
    int contacts = 0;                ///< Touching pairs in the last step [-].
    int contact_points = 0;          ///< Contact points (samples or manifold points) behind them [-].
    std::string modal_body;          ///< The selected modal body, or empty (the modal values stay 0).
    int modes = 0;                   ///< Its modes [-].
    double modal_residual = 0.0;     ///< body_modal_accuracy().residual [-].
    double truncated_fraction = 0.0; ///< body_modal_accuracy().truncated_fraction [-].
    double eigen_residual = 0.0;     ///< Largest mode residual of its eigen solve [-].
    double modal_energy = 0.0;       ///< body_modal_energy [J].
    std::vector<std::string> lines;  ///< The text lines, as drawn.
};

/// The Modes section of the Body window for one body: its modes and how well they hold its loads.
struct ModesReadout {
    bool shown = false;                 ///< Drawn in the last frame (a modal body selected, section open).
    std::string body;                   ///< The body asked about.
    bool modal = false;                 ///< It has modes; false for a rigid body (or none of that name).
    bool rigid = false;                 ///< A rigid body of that name: no modes to list.
    std::vector<double> frequencies_hz; ///< (r) natural frequencies of its basis [Hz], ascending.
    std::vector<double> amplitudes;     ///< (r) modal amplitudes now [√kg·m] (plastic offsets included).
    double residual = 0.0;              ///< body_modal_accuracy().residual [-].
    double truncated_energy = 0.0;      ///< body_modal_accuracy().truncated_energy [J].
    double truncated_fraction = 0.0;    ///< body_modal_accuracy().truncated_fraction [-].
    double plastic_dent = 0.0;          ///< Largest surface displacement of the moulding [m]: the plastic
                                        ///< offsets plus the rest offsets of rebuilt modes.
    int rebuilds = 0;                   ///< Times its modes were rebuilt for the moulded shape [-].
    uint64_t rebuild_pending_step = 0;  ///< Step count at which a rebuild asked for takes over; 0: none.
    int animating = -1;                 ///< The mode being animated (0 = lowest), or −1.
    std::vector<std::string> lines;     ///< The text lines (the panel adds one button per mode).
};
/// What the Modes section shows for `body` now (a script's `modes` action logs the same).
[[nodiscard]] ModesReadout modes_readout(const EditorSession& session, const std::string& body);

/// What the Speed / accuracy plot showed in its last frame.
struct TradeReadout {
    bool shown = false; ///< Its section was open with a scene.
    size_t points = 0;  ///< Configurations plotted [-].
    int marked = -1;    ///< The point of the scene's current dt and substeps, or −1.
    std::string status; ///< The line above the plot ("running", the failure, or what it shows).
};

/// A rectangle of the display [px], top-left origin.
struct ScreenRect {
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    [[nodiscard]] float width() const { return x1 - x0; }
    [[nodiscard]] float height() const { return y1 - y0; }
    [[nodiscard]] float area() const { return width() * height(); }
};

/// What the Parts panel is doing with the mouse.
struct PartsPanelState {
    std::string carrying;        ///< A part file pressed in the panel: released over the view, it is added.
    std::string armed;           ///< A part file clicked: the next left press in the view adds it there.
    bool attach_armed = false;   ///< Attach pressed: the next left press on another part attaches the
                                 ///< selected one there.
    AttachDef attach;            ///< Type, frequency and damping of the constraints Attach makes.
    bool render_in_frame = true; ///< frame() draws pending thumbnails (a window draws them itself).
    std::string last_added;      ///< Root body of the last part added from the panel.
};

/// The texture id the Parts panel draws thumbnail k with is k_thumbnail_texture + k: no GL name (a host
/// maps it to the texture it made of that thumbnail, thumbnail_index() gives k back).
constexpr intptr_t k_thumbnail_texture = 0x7f000000;
[[nodiscard]] int thumbnail_index(void* texture_id, size_t count);

/// Adds a part file where `ray` first meets the scene, set on that point: its lowest point (world box,
/// its origin at the hit) moved up onto it. A ray that hits no body drops it on the plane y = 0.
/// `def`'s name, prefix and orientation are kept. Returns the root body's name.
Result<std::string> drop_part(EditorSession& session, const Ray& ray, PartDef def);
/// The lowest world y [m] of a part file's bodies relative to its origin, turned by `orientation`.
Result<double> part_bottom(const std::string& file, const Quat& orientation);

/// What a left press, held button or release in the 3-D view does for the Parts panel (drops a carried
/// or armed part, attaches); true when it took the event.
bool parts_view_action(EditorSession& session, EditorUi& ui, const Ray& ray, bool left_pressed,
                       bool left_down);

/// Where the panels dock for a display: a left column (Scene over Parts over Run) and a right column (Body
/// over Speed / accuracy), narrow enough that the 3-D view between them keeps over 60% of a 1280x720 display;
/// each panel collapses to its title bar, and Tab hides them all. `scale` (HiDPI) multiplies the columns'
/// pixel limits as it does the fonts.
struct PanelLayout {
    ScreenRect scene, parts, run, body, speed;
};
[[nodiscard]] PanelLayout panel_layout(float display_width, float display_height, float scale = 1.0f);

/// The UI scale a window needs: its content scale (glfwGetWindowContentScale) less what the platform
/// already applies by counting window coordinates in larger units (framebuffer width / window width):
/// 2 on an X11 or Windows screen at 200% (same units), 1 on macOS or Wayland at 200% (the framebuffer
/// is twice the window). Within [0.5, 4]; 1 for sizes ≤ 0.
[[nodiscard]] float hidpi_ui_scale(float content_scale, int window_width, int framebuffer_width);

class EditorUi
{
  public:
    /// Makes an ImGui context for a display of width × height pixels and builds its font atlas (the
    /// pixels stay on the CPU until a renderer uploads them).
    EditorUi(EditorSession& session, int width = 1280, int height = 720);
    ~EditorUi();
    EditorUi(const EditorUi&) = delete;
    EditorUi& operator=(const EditorUi&) = delete;

    /// One UI frame of `real_seconds` [s]: new ImGui frame with the current mouse state, every window
    /// drawn (button presses act on the session at once), ImGui::Render(), then session.frame().
    void frame(double real_seconds = 1.0 / 60.0);
    /// Clicks the widget drawn with this label (exact label first, else the text before "##"): moves the
    /// mouse there, presses and releases over three frames. Fails when no visible widget, or more
    /// than one, has that label; the message lists the labels there are.
    Status press(const std::string& label);

    /// Sets the mouse for the next frame (a windowed host forwards its events here) [pixels].
    void set_mouse(float x, float y, bool left_down);

    /// One frame of the host (input.frame: a window draws and presents one; headless, frame() then
    /// the 3-D view's mouse action).
    void host_frame(double real_seconds);
    /// What the editor does with an event: ImGui's mouse for the next frame and `view_input`. A window's
    /// GLFW callbacks call these; headless, `input` calls them directly.
    void on_cursor(double x, double y);
    void on_button(MouseButton b, bool down, uint8_t mods = k_mod_none);
    void on_scroll(double notches);
    void on_key(EditorKey k, bool down, uint8_t mods = k_mod_none);
    /// The host's events, as a script sends them. Headless (the default) they call on_*() and frame(); a
    /// window replaces them while it is open with its GLFW callback chain and its own frames.
    InputEvents input;
    /// What the 3-D view does with the mouse and keys.
    ViewInput view_input;
    /// The part of the display the 3-D view keeps in the last frame: between the expanded panels of
    /// the left and right columns (the whole display with the panels hidden).
    [[nodiscard]] const ScreenRect& viewport() const { return m_viewport; }

    /// The display the UI is laid out for [px].
    [[nodiscard]] int width() const { return m_width; }
    [[nodiscard]] int height() const { return m_height; }
    /// Lays the UI out for a display of width × height [px] (≥ 1) from the next frame: a resized window.
    void resize(int width, int height);
    /// Scales fonts, widget sizes and the panels' pixel limits by `scale` (clamped to [0.5, 4]) from the
    /// next frame: a HiDPI screen (hidpi_ui_scale()).
    void set_scale(float scale);
    [[nodiscard]] float scale() const { return m_scale; }
    /// False: frames draw no window (a screenshot then shows the plain 3-D view).
    bool show_windows = true;
    /// True: the Shortcuts window lists every mouse and key action over the 3-D view (H, F1).
    bool show_help = false;
    /// The Shortcuts window's lines in the last frame, as drawn (empty while it is hidden).
    std::vector<std::string> help_lines;

    [[nodiscard]] const std::string& selected_body() const { return m_selected; }
    void select_body(const std::string& name) { m_selected = name; }
    /// The widgets of the last frame.
    [[nodiscard]] const std::vector<WidgetRect>& widgets() const { return m_widgets; }
    /// The `supermodal` program the Speed / accuracy plot runs for its sweep (default_bench_cli()).
    std::string bench_cli = default_bench_cli();
    /// Simulated time per run of that sweep [s].
    double trade_seconds = 0.5;
    /// The plot's background sweep, and the dt [s] and substeps it was run for.
    TradeSweep trade;
    double trade_dt = 0.0;
    int trade_substeps = 0;
    bool trade_seen = false; ///< The plot has shown the finished sweep (scrolled into view once).
    TradeReadout trade_readout;
    /// Saves the scene as defined (not its current state) to a file of its own and starts the sweep on
    /// it; fails when the scene cannot be written or the program not started.
    Status start_trade();
    /// The last error of an action started from the UI (a refused value, a failed save), or empty.
    [[nodiscard]] const std::string& last_error() const { return m_last_error; }
    /// A windowed host plugs its platform and renderer backends in here: `before_frame` runs just before
    /// ImGui::NewFrame (ImGui_ImplGlfw_NewFrame, ImGui_ImplOpenGL3_NewFrame), `after_render` just after
    /// ImGui::Render (draw the world, then ImGui_ImplOpenGL3_RenderDrawData). Both are empty headless.
    std::function<void()> before_frame;
    std::function<void()> after_render;
    /// True: frame() feeds ImGui the mouse set by set_mouse()/on_cursor()/on_button() (also in a
    /// window, whose GLFW callbacks call those). False leaves ImGui's mouse to a platform backend.
    bool synthetic_mouse = true;
    /// The camera of the 3-D view and the mouse: the scene's camera with an absent target or distance
    /// framed on a load (editor_camera() in camera.h), then moved only by the user or a re-framing, so
    /// that the view stays put while bodies move and a pixel means the same ray from frame to frame.
    std::optional<CameraDef> view_camera;
    bool view_moved = false;      ///< The user moved view_camera since it was framed.
    uint64_t view_loads = 0;      ///< The session's loads() view_camera was framed for.
    uint64_t view_generation = 0; ///< The session generation view_camera was framed for.
    double view_aspect = 0.0;     ///< The 3-D view's width / height view_camera was framed for.
    /// The transform gizmo over the selected body (mode, snapping) and the handle held, if any.
    GizmoDef gizmo;
    std::optional<GizmoDrag> gizmo_drag;
    /// The Speed / accuracy window's values in the last frame.
    SpeedAccuracyReadout speed_accuracy;
    /// The Body window's Modes section in the last frame.
    ModesReadout modes;
    /// The part files the Parts panel lists, with their thumbnails.
    PartsLibrary parts_library;
    PartsPanelState parts;
    /// Where the Save button writes.
    std::string save_path = "scene_saved.json";
    /// Steps the Step button runs.
    int step_count = 1;

    [[nodiscard]] ImGuiContext* context() { return m_context; }
    [[nodiscard]] EditorSession& session() { return m_session; }

    // ---- Used by the window functions (ui_*.cpp) -----------------------------------------------------
    /// Records the last ImGui item under `label` so press() can find it.
    void track(const char* label);
    /// Sets a scene value from a widget, keeping the message of a refusal for the status line.
    void apply(const std::string& path, const Json& value);
    void report(const Status& status);

  private:
    EditorSession& m_session;
    ImGuiContext* m_context = nullptr;
    std::string m_selected;
    std::vector<WidgetRect> m_widgets;
    std::string m_last_error;
    int m_width = 1, m_height = 1;
    float m_scale = 1.0f;
    float m_mouse_x = -1.0f, m_mouse_y = -1.0f;
    bool m_mouse_down = false, m_mouse_right = false;
    ScreenRect m_viewport;

    void headless_input();
    void update_viewport();
};

/// How the History section shows an edit's value: as written, or for a long array or object its size
/// ("[7 items]") or name ("{leg_fl}").
[[nodiscard]] std::string value_summary(const Json& value);

/// Places the next ImGui window on its docked rectangle (every frame: the panels do not float).
void dock_next_window(const ScreenRect& r);

// The windows, one file each (ui_scene_tree.cpp, ui_body.cpp, ui_controls.cpp).
void draw_scene_tree(EditorUi& ui);
void draw_body_window(EditorUi& ui);
void draw_controls(EditorUi& ui);
void draw_speed_accuracy(EditorUi& ui);
void draw_help(EditorUi& ui);                          // ui_help.cpp
void draw_parts(EditorUi& ui);                         // ui_parts.cpp
void draw_trade_plot(EditorUi& ui, const WorldDef& w); // ui_trade.cpp, inside Speed / accuracy

} // namespace supermodal::editor
