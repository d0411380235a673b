#include "viewer/viewer.hpp"

#include "gl/gl.hpp"
#ifdef OITBENCH_HAVE_GLFW
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#endif

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

#include "core/memory_budget.hpp"
#include "core/presets.hpp"
#include "core/runner.hpp"
#include "oit/capture/fragment_storage.hpp"
#include "oit/oit_case.hpp"
#include "oit/scene/scene.hpp"
#include "oit/techniques.hpp"
#include "viewer/depth_complexity.hpp"
#include "viewer/fly_camera.hpp"
#include "viewer/image_presenter.hpp"
#include "viewer/key_script.hpp"
#include "viewer/oit_settings.hpp"
#include "viewer/rolling_medians.hpp"
#include "viewer/scene_views.hpp"
#include "viewer/text_overlay.hpp"

namespace oitbench::viewer {

std::string key_help() {
  // B's pairs and M's node counts as the technique table has them.
  std::vector<std::string> sorts;
  for (const auto& t : oit::techniques())
    if (t.scheme == oit::ResolveScheme::Base && oit::bma_twin(t)) sorts.push_back(t.sort);
  const std::string base = oit::scheme_label(oit::ResolveScheme::Base),
                    bma = oit::scheme_label(oit::ResolveScheme::Bma);
  return "  W A S D     move (forward, left, back, right); Q / E down / up; shift: 4x faster\n"
         "  left drag   look around; scroll: slower / faster\n"
         "  T / shift+T next / previous technique (all of the oit experiment's, exact and approximate)\n"
         "  B           " +
         base + "-X <-> " + bma + "-X (" + oit::names_text(sorts) +
         ")\n"
         "  M / shift+M MAX_FRAGS x2 / /2 (below 1: auto); nodes for " +
         oit::names_text(oit::techniques_reading("nodes")) +
         "\n"
         "  C           next capture storage (the oit parameter 'capture': PPLL linked lists, PPPA packed arrays)\n"
         "  Z           depth complexity in false colour (blue 1 -> green -> red at the peak, log scale)\n"
         "  P           screenshot (--screenshot PATH, else oitbench-SCENE-TECHNIQUE-N.png)\n"
         "  V           save the camera as a view in the scene file (--save-view NAME, else view-1, view-2, ...)\n"
         "  H           help on screen; Esc quits";
}

#ifndef OITBENCH_HAVE_GLFW

int run_viewer(Registry&, const ViewerOptions&) {
  throw BackendError("oitbench view needs the GLFW backend, which this build lacks (install libglfw3-dev and rebuild)");
}

#else

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string grouped(unsigned long long v) {  // 1234567 -> 1,234,567
  std::string s = std::to_string(v);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3) s.insert(static_cast<size_t>(i), ",");
  return s;
}

// The window's input, gathered by GLFW's callbacks while glfwPollEvents runs (in swap_buffers) and
// taken once a frame. The callbacks find this object through the window's user pointer.
class WindowInput {
 public:
  explicit WindowInput(GLFWwindow* window) : window_(window) {
    glfwSetWindowUserPointer(window_, this);
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int mods) {
      if (action == GLFW_PRESS) of(w).on_key(key, (mods & GLFW_MOD_SHIFT) != 0);
    });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
      if (button != GLFW_MOUSE_BUTTON_LEFT) return;
      auto& self = of(w);
      self.dragging_ = action == GLFW_PRESS;
      glfwGetCursorPos(w, &self.cursor_.x, &self.cursor_.y);
    });
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
      auto& self = of(w);
      if (self.dragging_) self.drag_ += glm::vec2(x - self.cursor_.x, y - self.cursor_.y);
      self.cursor_ = {x, y};
    });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) { of(w).scroll_ += static_cast<float>(dy); });
  }
  ~WindowInput() {
    glfwSetKeyCallback(window_, nullptr);
    glfwSetMouseButtonCallback(window_, nullptr);
    glfwSetCursorPosCallback(window_, nullptr);
    glfwSetScrollCallback(window_, nullptr);
    glfwSetWindowUserPointer(window_, nullptr);
  }
  WindowInput(const WindowInput&) = delete;
  WindowInput& operator=(const WindowInput&) = delete;

  std::vector<KeyPress> take_presses() { return std::exchange(presses_, {}); }
  glm::vec2 take_drag() { return std::exchange(drag_, glm::vec2(0)); }
  float take_scroll() { return std::exchange(scroll_, 0.0f); }
  // Movement keys are held, not pressed: polled each frame.
  FlyCamera::Motion held_motion() const {
    auto down = [&](int key) { return glfwGetKey(window_, key) == GLFW_PRESS ? 1.0f : 0.0f; };
    FlyCamera::Motion m;
    m.forward = down(GLFW_KEY_W) - down(GLFW_KEY_S);
    m.right = down(GLFW_KEY_D) - down(GLFW_KEY_A);
    m.up = down(GLFW_KEY_E) - down(GLFW_KEY_Q);
    m.fast = down(GLFW_KEY_LEFT_SHIFT) > 0 || down(GLFW_KEY_RIGHT_SHIFT) > 0;
    return m;
  }
  void request_close() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
  void set_title(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }
  glm::ivec2 framebuffer_size() const {
    glm::ivec2 s;
    glfwGetFramebufferSize(window_, &s.x, &s.y);
    return s;
  }

 private:
  static WindowInput& of(GLFWwindow* w) { return *static_cast<WindowInput*>(glfwGetWindowUserPointer(w)); }
  void on_key(int key, bool shift) {
    if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z)
      presses_.push_back({static_cast<char>('A' + key - GLFW_KEY_A), shift});
    else if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9)
      presses_.push_back({static_cast<char>('0' + key - GLFW_KEY_0), shift});
    else if (key == GLFW_KEY_ESCAPE)
      presses_.push_back({kEscape, shift});
  }

  GLFWwindow* window_;
  std::vector<KeyPress> presses_;
  bool dragging_ = false;
  glm::dvec2 cursor_{0};
  glm::vec2 drag_{0};
  float scroll_ = 0;
};

bool is_movement_key(char k) { return k == 'W' || k == 'A' || k == 'S' || k == 'D' || k == 'Q' || k == 'E'; }

// A scripted movement key moves the camera as if held for this long: tests get the same camera on
// every machine, whatever the frame rate.
constexpr float kScriptedMoveSeconds = 0.1f;
// Fragment total and peak depth are counted every this many frames while the depth view is off.
constexpr int kCountEvery = 15;
// A resized window rebuilds the case at the new size once the size has held still this long.
constexpr double kResizeSettleSeconds = 0.3;

class Viewer {
 public:
  Viewer(Registry& registry, const ViewerOptions& o) : options_(o), settings_(make_settings(registry, o)) {
    script_ = parse_key_script(o.keys);
    if (o.frames > 0)
      for (const auto& k : script_)
        if (k.frame >= o.frames)
          throw UsageError("--keys: " + key_name(k.press) + " at frame " + std::to_string(k.frame) +
                           " is never reached (--frames " + std::to_string(o.frames) + " renders frames 0.." +
                           std::to_string(o.frames - 1) + ")");
    Resolution size = parse_resolution(o.size);

    // Everything that can be checked without a window is checked above, so a typo is reported as
    // such on a machine without a display too.
    auto unset = [](const char* name) { return !std::getenv(name) || !*std::getenv(name); };
    if (unset("DISPLAY") && unset("WAYLAND_DISPLAY"))
      throw BackendError(
          "oitbench view opens a window and needs a display, but neither DISPLAY nor WAYLAND_DISPLAY "
          "is set: run it on a desktop, or headless under Xvfb: xvfb-run -a oitbench view ...");
    ContextOptions copt;
    copt.backend = "glfw";
    copt.width = size.width;
    copt.height = size.height;
    copt.visible = true;
    copt.debug = o.gl_debug;
    context_ = create_context(copt);
    gl_ = GlInfo::query();
    shaders_ = std::make_unique<ShaderLibrary>(o.shader_root.empty() ? default_shader_root() : o.shader_root);
    if (gl_.has_extension("GL_ARB_get_program_binary"))
      shaders_->enable_program_cache(default_program_cache_dir(), gl_.vendor + "|" + gl_.renderer + "|" + gl_.version);
    use_gpu_clock_ = !gl_.is_software_renderer() && gl_.has_timer_query();
    timer_ = std::make_unique<PassTimer>(gl_.has_timer_query());
    input_ = std::make_unique<WindowInput>(static_cast<GLFWwindow*>(context_->native_window()));
    presenter_ = std::make_unique<ImagePresenter>(*shaders_);
    overlay_ = std::make_unique<TextOverlay>(*shaders_);
    depth_ = std::make_unique<DepthComplexity>(*shaders_);

    const oit::View& start = scene_.view(settings_.get("view"));
    camera_ = std::make_unique<FlyCamera>(
        start,
        oit::build_mesh(scene_, start, settings_.get("detail") == "small" ? oit::Detail::Small : oit::Detail::Full));
    build_case(/*startup=*/true);
  }

  int run() {
    size_t next_script = 0;
    last_frame_ = Clock::now();
    for (int frame = 0; options_.frames <= 0 || frame < options_.frames; ++frame) {
      if (context_->window_should_close()) break;
      while (next_script < script_.size() && script_[next_script].frame == frame)
        press(script_[next_script++].press, true);
      for (const auto& k : input_->take_presses()) press(k, false);
      if (context_->window_should_close()) break;
      if (rebuild_) build_case(false);
      follow_window_size();

      float dt = static_cast<float>(seconds_since(last_frame_));
      last_frame_ = Clock::now();
      if (frame > 0) frame_ms_.add("frame", dt * 1000.0);
      camera_->move(input_->held_motion(), std::min(dt, 1.0f));  // a held key never jumps across the scene
      glm::vec2 drag = input_->take_drag();
      if (drag != glm::vec2(0)) camera_->look(drag.x, drag.y);
      if (float s = input_->take_scroll(); s != 0) camera_->scale_speed(s);

      render(frame);
      compose();
      if (screenshot_now_) {
        screenshot_now_ = false;
        save_screenshot(screenshot_path());
      }
      context_->swap_buffers();
    }
    if (!options_.screenshot.empty()) {
      compose();  // the back buffer after a swap is undefined: draw the last frame again
      save_screenshot(options_.screenshot);
    }
    std::string summary = settings_.technique() + ": ";
    if (double ms = frame_ms_.median("frame"); ms > 0) summary += fixed(1000.0 / ms, 1) + " fps, ";
    for (const auto& [name, ms] : pass_ms_.medians()) summary += name + " " + fixed(ms, 2) + " ";
    std::fprintf(stderr, "oitbench view: %sms (medians of the last %zu frames)\n", summary.c_str(),
                 pass_ms_.samples("total"));
    return errors_ ? 1 : 0;
  }

 private:
  OitSettings make_settings(Registry& registry, const ViewerOptions& o) {
    try {
      scene_ = oit::load_scene(o.scene);
    } catch (const oit::SceneError& e) {
      throw UsageError(e.what());
    }
    std::string view = o.view;
    if (view.empty()) {
      std::ifstream in(scene_.path);
      std::stringstream text;
      text << in.rdbuf();
      view = view_names_in_file_order(scene_.path, text.str()).front();
    }
    try {
      scene_.view(view);
    } catch (const oit::SceneError& e) {
      throw UsageError(e.what());
    }
    std::map<std::string, std::string> chosen = {
        {"scene", o.scene}, {"view", view}, {"technique", o.technique}, {"detail", o.detail}};
    for (const auto& [k, v] : parse_set_options(o.sets)) {
      if (v.size() != 1) throw UsageError("view: --set " + k + " takes one value");
      if (chosen.count(k) && k != "technique" && k != "detail")
        throw UsageError("view: give " + k + " as --" + k + ", not --set");
      chosen[k] = v.front();
    }
    OitSettings settings(registry, chosen);
    settings.experiment().check_cases({settings.params()});  // an unknown effect: exit 2, as in run
    return settings;
  }

  void say(const std::string& text, bool error = false) {
    message_ = text;
    message_is_error_ = error;
    std::fprintf(stderr, "oitbench view: %s\n", text.c_str());
  }

  // Builds the case for settings_ at the framebuffer's size. At startup a failure ends the viewer;
  // later the old case stays and the failure is shown (and makes the exit code 1).
  void build_case(bool startup) {
    rebuild_ = false;
    glm::ivec2 fb = input_->framebuffer_size();
    if (!startup) {
      message_ = "compiling " + settings_.technique() + " ...";
      message_is_error_ = false;
      compose();
      context_->swap_buffers();
      input_->take_presses();  // keys pressed while the window hung are dropped, not replayed later
    }
    auto start = Clock::now();
    try {
      if (auto why = settings_.experiment().unsupported_reason(gl_, settings_.params()); !why.empty())
        throw Unsupported(why);
      auto cctx = std::make_unique<CaseContext>(*shaders_, gl_, Resolution{fb.x, fb.y}, settings_.get("fault"),
                                                static_cast<unsigned>(settings_.params().get_int("seed")));
      // Held against the memory limit like a run's cases: a technique that cannot be held is not built.
      cctx->set_memory(current_memory_limits(gl_.is_software_renderer(), gl_.has_extension("GL_NVX_gpu_memory_info"),
                                             gl_.has_extension("GL_ATI_meminfo"), options_.memory_limit));
      auto c = oit::make_oit_case(settings_.params(), *cctx);
      case_ = std::move(c);
      case_context_ = std::move(cctx);
    } catch (const std::exception& e) {
      std::string what = "cannot build " + settings_.technique() + ": " + e.what();
      if (startup) throw std::runtime_error(what);
      ++errors_;
      settings_ = built_settings_;
      last_frame_ = Clock::now();
      say(what, true);
      return;
    }
    built_settings_ = settings_;
    last_frame_ = Clock::now();  // the build is neither frame time nor time a held key moves the camera
    case_size_ = fb;
    pending_size_.reset();
    pass_ms_.clear();
    counts_.reset();
    input_->set_title("oitbench view: " + scene_.name + "/" + settings_.get("view") + " " + settings_.technique());
    say(settings_.technique() + " ready in " + fixed(seconds_since(start), 2) + " s (compile + first capture)");
  }

  // A resized window gets a case of its size once the size holds still (each build recompiles).
  void follow_window_size() {
    glm::ivec2 fb = input_->framebuffer_size();
    if (fb == case_size_ || fb.x <= 0 || fb.y <= 0) {
      pending_size_.reset();
      return;
    }
    if (!pending_size_ || pending_size_->first != fb)
      pending_size_ = {fb, Clock::now()};
    else if (seconds_since(pending_size_->second) > kResizeSettleSeconds)
      build_case(false);
  }

  void press(KeyPress k, bool scripted) {
    bool changed = false;
    if (is_movement_key(k.key)) {
      if (!scripted) return;  // from the keyboard: held, polled every frame
      FlyCamera::Motion m;
      m.forward = k.key == 'W' ? 1.0f : k.key == 'S' ? -1.0f : 0.0f;
      m.right = k.key == 'D' ? 1.0f : k.key == 'A' ? -1.0f : 0.0f;
      m.up = k.key == 'E' ? 1.0f : k.key == 'Q' ? -1.0f : 0.0f;
      m.fast = k.shift;
      camera_->move(m, kScriptedMoveSeconds);
      return;
    }
    switch (k.key) {
      case 'T':
        say(settings_.step_technique(k.shift ? -1 : 1, changed));
        break;
      case 'B':
        say(settings_.toggle_bma(changed));
        break;
      case 'M':
        say(settings_.scale_max_frags(!k.shift, case_ ? case_->max_frags() : 0, changed));
        break;
      case 'C':
        say(settings_.step_capture(changed));
        break;
      case 'Z':
        depth_view_ = !depth_view_;
        counts_.reset();
        say(std::string("depth complexity ") + (depth_view_ ? "on" : "off"));
        break;
      case 'P':
        screenshot_now_ = true;
        break;
      case 'V':
        save_view();
        break;
      case 'H':
        help_ = !help_;
        break;
      case kEscape:
        input_->request_close();
        break;
      default:
        if (scripted) say("key " + key_name(k) + " does nothing (H: help)");
    }
    if (changed) rebuild_ = true;
  }

  void render(int frame) {
    if (!case_) return;
    float aspect = static_cast<float>(case_size_.x) / static_cast<float>(case_size_.y);
    case_->set_view_projection(camera_->view_projection(aspect));
    timer_->begin_repetition();
    case_->run(*timer_);
    double total = 0;
    for (const auto& s : timer_->end_repetition()) {
      double ms = use_gpu_clock_ && s.gpu_ms >= 0 ? s.gpu_ms : s.cpu_ms;
      pass_ms_.add(s.pass, ms);
      total += ms;
    }
    pass_ms_.add("total", total);
    if (const oit::FragmentStorage* lists = case_->fragments();
        lists && (depth_view_ || !counts_ || frame % kCountEvery == 0))
      counts_ = depth_->count(*lists, lists->defines(), case_size_.x, case_size_.y);
  }

  // The frame into the window's back buffer: the image (or the depth view) and the overlay.
  void compose() {
    glm::ivec2 fb = input_->framebuffer_size();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fb.x, fb.y);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (case_ && depth_view_ && case_->fragments() && counts_) {
      depth_->draw(fb.x, fb.y);
    } else if (case_) {
      presenter_->draw(case_->result_texture(), case_size_.x, case_size_.y, scene_.background, fb.x, fb.y,
                       case_->opaque_texture());
    } else {
      glClearColor(scene_.background.r, scene_.background.g, scene_.background.b, 1);
      glClear(GL_COLOR_BUFFER_BIT);
    }
    overlay_->draw(overlay_lines(fb), fb.x, fb.y, fb.y >= 480 && fb.x >= 640 ? 2 : 1);
  }

  // Small windows (tests, thumbnails) get the first lines and the message only, so the image shows.
  static constexpr int kCompactBelowHeight = 300;

  std::vector<TextLine> overlay_lines(glm::ivec2 fb) const {
    const glm::u8vec4 grey{165, 165, 165, 255}, yellow{255, 220, 90, 255}, red{255, 110, 100, 255},
        cyan{150, 215, 255, 255};
    std::vector<TextLine> lines;
    std::string title = scene_.name + " / " + settings_.get("view") + " (" + settings_.get("detail") + ")   " +
                        std::to_string(case_size_.x) + "x" + std::to_string(case_size_.y);
    if (double ms = frame_ms_.median("frame"); ms > 0) title += "   " + fixed(1000.0 / ms, 1) + " fps";
    lines.push_back({title});

    std::string tech = settings_.technique();
    if (settings_.uses_max_frags()) {
      tech += "   MAX_FRAGS " + std::to_string(case_ ? case_->max_frags() : 0);
      if (settings_.get("max_frags") == "0") tech += " (auto)";
    } else if (settings_.uses_nodes()) {
      tech += "   nodes " + settings_.get("nodes");
    }
    if (settings_.is_exact()) tech += "   capture: " + settings_.get("capture");
    lines.push_back({tech});

    std::string passes;
    for (const auto& [name, ms] : pass_ms_.medians()) passes += name + " " + fixed(ms, ms < 10 ? 2 : 1) + "  ";
    if (!passes.empty()) {
      lines.push_back({passes + "ms"});
      lines.push_back({"  median of " + std::to_string(pass_ms_.samples("total")) + " frames, " +
                           (use_gpu_clock_ ? "GL timer queries" : "CPU clock around glFinish"),
                       grey});
    }

    if (case_ && case_->fragments()) {
      std::string f = "fragments " + grouped(case_->fragments()->fragments());
      if (counts_) f += "   peak depth " + std::to_string(counts_->peak);
      if (counts_ && settings_.uses_max_frags() && counts_->peak > case_->max_frags()) f += "  > MAX_FRAGS: truncated";
      lines.push_back({f});
    } else {
      lines.push_back({"fragments: " + settings_.technique() + " keeps no per-pixel lists", grey});
    }
    if (depth_view_) {
      if (case_ && case_->fragments() && counts_)
        lines.push_back(
            {"depth complexity: black 0, blue 1 .. green .. red " + std::to_string(counts_->peak) + " (log)"});
      else
        lines.push_back({"depth complexity needs captured fragments: " + settings_.technique() +
                             " has none (exact techniques only)",
                         yellow});
    }
    glm::vec3 eye = camera_->view().eye;
    lines.push_back({"eye " + fixed(eye.x, 2) + " " + fixed(eye.y, 2) + " " + fixed(eye.z, 2) + "   speed " +
                         fixed(camera_->speed(), 2) + "/s",
                     grey});
    if (fb.y < kCompactBelowHeight) {
      std::vector<TextLine> compact(lines.begin(), lines.begin() + 2);
      if (!message_.empty()) compact.push_back({message_, message_is_error_ ? red : yellow});
      return compact;
    }
    if (!message_.empty()) lines.push_back({message_, message_is_error_ ? red : yellow});
    if (help_) {  // key_help() is for a terminal; on screen, short lines (the font has no fixed width)
      for (const char* line : {"WASD move   Q/E down/up   shift 4x   scroll: speed", "left drag: look around",
                               "T / shift+T: next / previous technique", "B: BASE-X <-> BMA-X",
                               "M / shift+M: MAX_FRAGS (or nodes) x2 / /2", "C: capture storage   Z: depth complexity",
                               "P: screenshot   V: save the camera as a view", "H: hide this   Esc: quit"})
        lines.push_back({line, cyan});
    } else {
      lines.push_back({"H: keys", grey});
    }
    return lines;
  }

  void save_view() {
    try {
      std::string name = save_view_to_scene_file(scene_.path, camera_->view(), options_.save_view);
      glm::vec3 e = camera_->view().eye;
      say("saved view \"" + name + "\" in " + scene_.path + " (eye " + fixed(e.x, 3) + " " + fixed(e.y, 3) + " " +
          fixed(e.z, 3) + ")");
    } catch (const std::exception& e) {
      ++errors_;
      say(std::string("view not saved: ") + e.what(), true);
    }
  }

  std::string screenshot_path() const {
    if (!options_.screenshot.empty()) return options_.screenshot;
    for (int i = 1;; ++i) {
      std::string p = "oitbench-" + scene_.name + "-" + settings_.technique() + "-" + std::to_string(i) + ".png";
      if (!std::filesystem::exists(p)) return p;
    }
  }

  void save_screenshot(const std::string& path) {
    glm::ivec2 fb = input_->framebuffer_size();
    try {
      write_window_png(path, fb.x, fb.y);
      say("screenshot " + path + " (" + std::to_string(fb.x) + "x" + std::to_string(fb.y) + ")");
    } catch (const std::exception& e) {
      ++errors_;
      say(std::string("screenshot not saved: ") + e.what(), true);
    }
  }

  ViewerOptions options_;
  oit::SceneDesc scene_;  // filled by make_settings, before settings_
  OitSettings settings_, built_settings_ = settings_;
  std::vector<ScriptedKey> script_;
  // GL: the context first, so that it outlives every GL object below.
  std::unique_ptr<Context> context_;
  GlInfo gl_;
  std::unique_ptr<ShaderLibrary> shaders_;
  std::unique_ptr<PassTimer> timer_;
  std::unique_ptr<WindowInput> input_;
  std::unique_ptr<ImagePresenter> presenter_;
  std::unique_ptr<TextOverlay> overlay_;
  std::unique_ptr<DepthComplexity> depth_;
  std::unique_ptr<FlyCamera> camera_;
  std::unique_ptr<CaseContext> case_context_;  // the case keeps references into it
  std::unique_ptr<oit::OitCase> case_;
  glm::ivec2 case_size_{0};
  Clock::time_point last_frame_;
  std::optional<std::pair<glm::ivec2, Clock::time_point> > pending_size_;
  bool use_gpu_clock_ = false;
  RollingMedians pass_ms_, frame_ms_;
  std::optional<DepthComplexity::Counts> counts_;
  bool rebuild_ = false, depth_view_ = false, help_ = false, screenshot_now_ = false;
  std::string message_;
  bool message_is_error_ = false;
  int errors_ = 0;
};

}  // namespace

int run_viewer(Registry& registry, const ViewerOptions& options) {
  Viewer viewer(registry, options);
  return viewer.run();
}

#endif

}  // namespace oitbench::viewer
