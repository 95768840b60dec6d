// lrigid view SCENE.json: watch a scene live. A VTK window draws the bodies (instanced glyphs of
// their body types' surfaces, placed with their orientation), the ground, the grid's solids and
// optionally a slice of |U| or k, while a worker thread (view_sim.h) simulates; keys steer it.
// Scripted: --frames N [--screenshot out.png] [--write-frames DIR] runs without a person.
// docs/viewer.md.
#include <omp.h>
#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkFloatArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkImageData.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkLegendBoxActor.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedShortArray.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "checks.h"
#include "commands.h"
#include "compile/compile_model.h"
#include "io/added_mass_cache.h"
#include "io/field_loader.h"
#include "io/result_writer.h"
#include "io/scene_json.h"
#include "util/error.h"
#include "draw_style.h"
#include "view_sim.h"
#include "vtk_annotate.h"
#include "vtk_draw.h"

namespace lrigid::app {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct ViewArgs {
  std::string scene;
  long long seed = -1;
  int threads = 0;
  std::string pace = "realtime";
  double fps = 30;                  // frames drawn per second at most (and the fixed pace's rate)
  int frames = 0;                   // > 0: draw this many frames, then exit
  std::string screenshot;           // written when the viewer ends
  std::string write_frames;         // every frame into this directory from the start
  std::string record_dir = "lrigid_frames";  // where `o` writes frames
  std::string shot_dir = ".";       // where `s` writes screenshots
  int width = 1280, height = 720;
  std::string slice = "none";
  double slice_z = NAN;             // m
  PictureOptions pic;               // camera, colouring, enlargement (draw_style.h)
  int multisamples = 0;             // OpenGL antialiasing samples (costly in software OpenGL)
  bool loop = false;
  bool hud = true;
  bool log = false;                 // print the heads-up line of every frame to stdout
  std::vector<std::string> press;   // FRAME:KEY, keys pressed by a script
};

const char* kControls =
    "Controls (keys in the window):\n"
    "  space      pause / resume\n"
    "  + / -      mean flow x1.25 / /1.25 (art-direction scale, docs/effects.md)\n"
    "  ] / [      turbulence x1.25 / /1.25\n"
    "  r          restart with the next seed\n"
    "  s          save a screenshot (--shot-dir)\n"
    "  o          start / stop writing every frame (--record-dir)\n"
    "  p          pace: realtime -> fast -> fixed\n"
    "  c          colour by body type -> state -> speed\n"
    "  q, Esc     quit\n"
    "  mouse      rotate (left), pan (middle), zoom (right, wheel)\n";

// The window's key handling: everything but the controls above is swallowed, so VTK's own keys
// (w: wireframe, s: surface, r: reset camera, ...) do not interfere.
class ViewStyle : public vtkInteractorStyleTrackballCamera {
 public:
  static ViewStyle* New();
  vtkTypeMacro(ViewStyle, vtkInteractorStyleTrackballCamera)
  std::function<bool(const std::string&)> on_key;
  void OnChar() override {
    vtkRenderWindowInteractor* rwi = this->Interactor;
    const std::string sym = rwi->GetKeySym() ? rwi->GetKeySym() : "";
    const char c = rwi->GetKeyCode();
    std::string key = sym == "space" ? " " : sym == "Escape" ? "Escape" : std::string(1, c);
    if (c == 0 && sym != "Escape") return;
    if (on_key) on_key(key);
  }
  void OnKeyPress() override {}
  void OnKeyRelease() override {}
};
vtkStandardNewMacro(ViewStyle)

Pace parse_pace(const std::string& s) {
  return s == "fast" ? Pace::Fast : s == "fixed" ? Pace::Fixed : Pace::RealTime;
}

std::string si(double v) {
  char b[32];
  if (v >= 1e6) std::snprintf(b, sizeof b, "%.2fM", v / 1e6);
  else if (v >= 1e3) std::snprintf(b, sizeof b, "%.1fk", v / 1e3);
  else std::snprintf(b, sizeof b, "%.0f", v);
  return b;
}

class Viewer {
 public:
  Viewer(const ViewArgs& a, const Scene& scene, const Model& model, ViewSimulation* sim)
      : a_(a), sim_(sim) {
    for (const auto& p : a.press) {
      const auto colon = p.find(':');
      int frame = -1;
      try {
        frame = colon == std::string::npos ? -1 : std::stoi(p.substr(0, colon));
      } catch (const std::exception&) {
      }
      const std::string key = colon == std::string::npos ? "" : p.substr(colon + 1);
      if (frame < 0 || key.empty())
        throw Error(ExitCode::Usage, "--press wants FRAME:KEY (e.g. 10:+ or 5:space), got \"" +
                                         p + "\"");
      presses_.emplace(frame, key == "space" ? " " : key);
    }
    by_ = a.pic.colouring();
    ren_->GradientBackgroundOn();
    ren_->SetBackground(0.93, 0.94, 0.96);
    ren_->SetBackground2(0.62, 0.68, 0.78);
    win_->SetSize(a.width, a.height);
    win_->SetMultiSamples(a.multisamples);
    win_->AddRenderer(ren_);
    win_->SetWindowName(("lrigid view " + scene.file).c_str());
    build_context(scene, model);
    build_glyphs(model);
    hud_->GetTextProperty()->SetFontSize(std::max(12, a.height / 46));
    hud_->GetTextProperty()->SetColor(0.08, 0.08, 0.12);
    hud_->GetTextProperty()->SetFontFamilyToCourier();
    hud_->SetPosition(10, 8);
    hud_->SetVisibility(a.hud);
    ren_->AddActor2D(hud_);
    if (!a.write_frames.empty()) start_recording(a.write_frames);
  }

  void run() {
    ViewFrame& f = frame_;
    sim_->latest(&f);
    vtkNew<vtkRenderWindowInteractor> iren;
    vtkNew<ViewStyle> style;
    style->on_key = [this](const std::string& k) { return key(k); };
    iren->SetInteractorStyle(style);
    iren->SetRenderWindow(win_);
    iren->Initialize();
    iren_ = iren;
    draw();  // frame 0: the initial state
    sim_->start();
    vtkNew<vtkCallbackCommand> tick;
    tick->SetClientData(this);
    tick->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
      static_cast<Viewer*>(self)->on_timer();
    });
    iren->AddObserver(vtkCommand::TimerEvent, tick);
    iren->CreateRepeatingTimer(unsigned(std::max(1.0, std::floor(1000.0 / a_.fps))));
    const auto start = Clock::now();
    if (!done_) iren->Start();
    sim_->stop();
    // what the run achieved, as a whole (docs/viewer.md quotes these lines)
    const double wall = std::chrono::duration<double>(Clock::now() - start).count();
    const ViewSimulation::Totals t = sim_->totals();
    std::fprintf(stderr,
                 "lrigid: view: %d frames in %.2f s (%.2f frames/s); simulated %.3f s (x%.3f of "
                 "real time); %llu body-steps, %.3g body-steps/s while stepping, stepping %.0f%% "
                 "of the time\n",
                 drawn_ - 1, wall, wall > 0 ? (drawn_ - 1) / wall : 0.0, t.simulated_seconds,
                 wall > 0 ? t.simulated_seconds / wall : 0.0,
                 static_cast<unsigned long long>(t.body_steps),
                 t.integrate_seconds > 0 ? double(t.body_steps) / t.integrate_seconds : 0.0,
                 wall > 0 ? 100 * t.integrate_seconds / wall : 0.0);
    sim_->rethrow_failure();
    if (!a_.screenshot.empty()) {
      write_png(win_, a_.screenshot);
      if (!a_.log) std::fprintf(stderr, "lrigid: wrote %s\n", a_.screenshot.c_str());
    }
    if (recording_)
      std::fprintf(stderr, "lrigid: wrote %d frames to %s\n", record_count_, record_dir_.c_str());
  }

 private:
  // what the window shows around the bodies; sets the camera's box
  void build_context(const Scene& scene, const Model& model) {
    // the bodies where they start, and where a uniform flow takes them in a few seconds
    const State s0 = initial_state(model, scene);
    for (const Vec3& x : s0.x) box_.add(x);
    start_x_ = s0.x;
    if (scene.uniform_field && !box_.empty()) {
      const Vec3 drift = model.mean_flow_scale * scene.uniform_U * std::min(scene.duration, 3.0);
      box_.add(box_.lo + drift);
      box_.add(box_.hi + drift);
    }
    if (scene.has_ground && !box_.empty())
      box_.add(Vec3(box_.lo.x(), box_.lo.y(), scene.ground_z));
    const std::string key = scene.file + ": fluid.field";
    if (!scene.uniform_field) {
      grid_ = read_grid_image(scene.field_path, key);
      double gb[6];
      grid_->GetBounds(gb);
      box_.add(Vec3(gb[0], gb[2], gb[4]));
      box_.add(Vec3(gb[1], gb[3], gb[5]));
      add_solids(ren_, grid_);
      if (a_.slice != "none") {
        const std::string array = a_.slice == "U" ? "|U|" : "k";
        const double z = std::isnan(a_.slice_z) ? gb[4] + 0.04 * (gb[5] - gb[4]) : a_.slice_z;
        const std::string title = a_.slice == "U" ? "|U| (m/s)" : "k (m^2/s^2)";
        if (!add_slice(ren_, grid_, array, z, title, a_.height / 2))
          fail_input(scene.field_path, "", "has no point array \"" +
                                               std::string(a_.slice == "U" ? "U" : "k") +
                                               "\" for --slice " + a_.slice);
      }
    } else if (a_.slice != "none") {
      throw Error(ExitCode::Usage,
                  where(scene.file, "fluid", "--slice " + a_.slice +
                                                 " needs a grid (fluid.field); this scene's "
                                                 "flow is uniform"));
    }
    if (scene.has_ground) add_ground(ren_, scene.ground_z, &box_);
  }

  void build_glyphs(const Model& model) {
    const int faces = std::min(320, shape_faces_for(model.body_count));
    std::vector<TriangleMesh> surfaces;
    for (const BodyType& t : model.types) surfaces.push_back(body_surface(t, faces));
    // the body entries (the scene's `bodies`; an entry's variants are types of the same entry)
    std::vector<std::string> type_name;
    std::vector<double> type_size;
    entry_of_type_.clear();
    for (size_t i = 0; i < model.types.size(); ++i) {
      entry_of_type_.push_back(model.types[i].spec);
      type_name.push_back(model.types[i].name);
      type_size.push_back(largest_extent(surfaces[i]));
    }
    EntryTally tally(entry_of_type_, type_name, type_size);
    // where the bodies start: what --frame ENTRY and the true-scale rule look at
    for (size_t i = 0; i < model.types.size(); ++i) {
      const BodyType& t = model.types[i];
      for (size_t b = t.first_body; b < t.first_body + t.count && b < start_x_.size(); ++b) {
        tally.add_body(i);
        tally.add_seen(i, start_x_[b]);
      }
    }
    entry_names_ = tally.names();
    box_.lo -= Vec3::Constant(tally.widest());
    box_.hi += Vec3::Constant(tally.widest());
    const CameraPose camera =
        choose_camera(a_.pic, box_, tally.boxes(), double(a_.width) / a_.height);
    factors_ = tally.factors(a_.pic, camera, a_.height);
    enlarged_ = enlargement_note(entry_names_, factors_);
    std::vector<double> scale;
    for (const BodyType& t : model.types) scale.push_back(factors_[t.spec]);
    for (size_t i = 0; i < model.types.size(); ++i) {
      vtkNew<vtkPoints> pts;
      for (const Vec3& v : surfaces[i].vertices) {
        const Vec3 p = scale[i] * v;
        pts->InsertNextPoint(p.data());
      }
      vtkNew<vtkCellArray> polys;
      for (const auto& f : surfaces[i].faces) {
        const vtkIdType ids[3] = {f[0], f[1], f[2]};
        polys->InsertNextCell(3, ids);
      }
      vtkNew<vtkPolyData> src;
      src->SetPoints(pts);
      src->SetPolys(polys);
      glyphs_->SetSourceData(int(i), src);
    }
    q_->SetName("q");
    q_->SetNumberOfComponents(4);
    index_->SetName("type");
    rgb_->SetName("colour");
    rgb_->SetNumberOfComponents(3);
    speed_->SetName("speed");
    points_->SetPoints(pts_);
    points_->GetPointData()->AddArray(q_);
    points_->GetPointData()->AddArray(index_);
    points_->GetPointData()->AddArray(rgb_);
    points_->GetPointData()->AddArray(speed_);
    glyphs_->SetInputData(points_);
    glyphs_->SetOrientationModeToQuaternion();
    glyphs_->SetOrientationArray("q");
    glyphs_->SourceIndexingOn();
    glyphs_->SetSourceIndexArray("type");
    glyphs_->ScalingOff();
    glyphs_->SetScalarModeToUsePointFieldData();
    speed_colours(lut_, 1);
    glyphs_->SetLookupTable(lut_);
    body_actor_->SetMapper(glyphs_);
    body_actor_->GetProperty()->SetSpecular(0.2);
    ren_->AddActor(body_actor_);
    speed_bar(speed_bar_, lut_, a_.height / 3);
    ren_->AddActor2D(speed_bar_);
    set_colouring();
    apply_camera(ren_, camera);
  }

  // the glyphs' colours, the speed bar and the legend for the colouring by_
  void set_colouring() {
    const bool speed = by_ == ColourBy::Speed;
    if (speed) {
      glyphs_->SelectColorArray("speed");
      glyphs_->SetColorModeToMapScalars();
    } else {
      glyphs_->SelectColorArray("colour");
      glyphs_->SetColorModeToDirectScalars();
    }
    speed_bar_->SetVisibility(speed);
    if (legend_) ren_->RemoveActor2D(legend_);
    legend_ = add_legend(ren_, legend_entries(by_, entry_names_, factors_,
                                              std::vector<bool>(kStateCount, true)),
                         a_.width, a_.height);
    if (frame_.x.size() == frame_.type.size() && !frame_.x.empty()) update_bodies(frame_);
  }

  // the bodies still in the domain (flying or resting) as glyph points
  void update_bodies(const ViewFrame& f) {
    size_t n = 0;
    auto shown = [](BodyStatus s) {
      return s == BodyStatus::Moving || s == BodyStatus::Landed || s == BodyStatus::Sleeping;
    };
    for (const BodyStatus s : f.status) n += shown(s);
    pts_->SetNumberOfPoints(vtkIdType(n));
    q_->SetNumberOfTuples(vtkIdType(n));
    index_->SetNumberOfTuples(vtkIdType(n));
    rgb_->SetNumberOfTuples(vtkIdType(n));
    speed_->SetNumberOfTuples(vtkIdType(n));
    vtkIdType k = 0;
    float vmax = 0;
    for (size_t i = 0; i < f.x.size(); ++i) {
      if (!shown(f.status[i])) continue;
      pts_->SetPoint(k, f.x[i].data());
      const Quat& q = f.q[i];
      q_->SetTuple4(k, q.w(), q.x(), q.y(), q.z());
      index_->SetValue(k, f.type[i]);
      unsigned char c[3];
      if (by_ == ColourBy::State && i < f.state.size()) state_colour(f.state[i], c);
      else type_colour(entry_of_type_[f.type[i]], c);
      rgb_->SetTypedTuple(k, c);
      speed_->SetValue(k, f.speed[i]);
      vmax = std::max(vmax, f.speed[i]);
      ++k;
    }
    // the speed scale follows the fastest body, shrinking slowly (no flicker)
    speed_max_ = std::max(double(vmax), 0.98 * speed_max_);
    const double range[2] = {0, std::max(speed_max_, 1e-3)};
    glyphs_->SetScalarRange(range);
    speed_colours(lut_, range[1]);
    pts_->Modified();
    q_->Modified();
    index_->Modified();
    rgb_->Modified();
    speed_->Modified();
    points_->Modified();
  }

  std::string hud_line(const ViewFrame& f) const {
    char b[512];
    std::string pace = pace_name(f.pace);
    if (f.pace == Pace::RealTime && f.behind) {
      char s[48];
      std::snprintf(s, sizeof s, "realtime BEHIND x%.2f", f.sim_speed);
      pace = s;
    } else if (f.pace != Pace::Fixed) {
      char s[48];
      std::snprintf(s, sizeof s, "%s x%.2f", pace.c_str(), f.sim_speed);
      pace = s;
    }
    std::snprintf(b, sizeof b,
                  "t = %.2f / %.2f s  flying %zu  resting %zu  exited %zu | %s body-steps/s, "
                  "busy %.0f%% | %.1f frames/s | %s%s%s",
                  f.t, f.duration, f.flying, f.resting, f.exited,
                  si(f.body_steps_per_second).c_str(), 100 * f.busy, fps_, pace.c_str(),
                  f.paused ? "  PAUSED" : "", f.finished ? "  END (r restarts)" : "");
    std::string line = b;
    std::snprintf(b, sizeof b, "\nmean flow x%.3g  turbulence x%.3g  seed %llu%s%s", f.mean_flow_scale,
                  f.turbulence_scale, static_cast<unsigned long long>(f.seed),
                  recording_ ? "  REC" : "", enlarged_.empty() ? "" : ("  " + enlarged_).c_str());
    line += b;
    line += "\nspace pause  +/- wind  [ ] turbulence  r restart  s shot  o record  p pace  "
            "c colour  q quit";
    return line;
  }

  void draw() {
    update_bodies(frame_);
    // frames per second, over the last second of draws
    const auto now = Clock::now();
    draws_.push_back(now);
    while (draws_.size() > 1 && now - draws_.front() > std::chrono::seconds(1)) draws_.pop_front();
    if (draws_.size() > 1)
      fps_ = double(draws_.size() - 1) /
             std::chrono::duration<double>(draws_.back() - draws_.front()).count();
    const std::string line = hud_line(frame_);
    hud_->SetInput(line.c_str());
    ren_->ResetCameraClippingRange();
    win_->Render();
    if (a_.log) std::printf("frame %d: %s\n", drawn_, line.substr(0, line.find('\n', line.find('\n') + 1)).c_str());
    if (recording_) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%06d.png", record_count_++);
      write_png(win_, (fs::path(record_dir_) / name).string());
    }
    last_draw_ = now;
    ++drawn_;
  }

  void on_timer() {
    try {
      sim_->rethrow_failure();
      // keys pressed by script before frame drawn_ (frame 0 is drawn before the first tick)
      while (!presses_.empty() && presses_.begin()->first <= drawn_) {
        const std::string k = presses_.begin()->second;
        presses_.erase(presses_.begin());
        key(k);
      }
      if (done_) return;
      if (frame_.pace == Pace::Fixed) sim_->advance_and_wait(1.0 / a_.fps);
      const bool fresh = sim_->latest(&frame_);
      // the simulation comes first: when it cannot keep the wall clock, draw less often
      const auto now = Clock::now();
      // (one frame a second while it is behind: drawing many bodies in software OpenGL costs
      // more CPU per frame than a stretch of steps, docs/viewer.md)
      interval_ = frame_.behind ? std::max(1.0, 1.0 / a_.fps) : 1.0 / a_.fps;
      const bool due = std::chrono::duration<double>(now - last_draw_).count() >= 0.9 * interval_;
      const bool scripted = a_.frames > 0;
      if (!due) return;
      if (!fresh && !scripted && !recording_ &&
          std::chrono::duration<double>(now - last_draw_).count() < 0.5)
        return;  // nothing new (paused): keep the HUD fresh twice a second
      draw();
      if (scripted && drawn_ > a_.frames) finish();
    } catch (...) {
      failure_ = std::current_exception();
      finish();
    }
  }

  void finish() {
    done_ = true;
    if (iren_) iren_->TerminateApp();
  }

  void start_recording(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw Error(ExitCode::Output, where(dir, "", "cannot create: " + ec.message()));
    record_dir_ = dir;
    recording_ = true;
  }

 public:
  bool key(const std::string& k) {
    if (k == " ") sim_->toggle_pause();
    else if (k == "+" || k == "=") sim_->scale_mean_flow(1.25);
    else if (k == "-") sim_->scale_mean_flow(1 / 1.25);
    else if (k == "]") sim_->scale_turbulence(1.25);
    else if (k == "[") sim_->scale_turbulence(1 / 1.25);
    else if (k == "r") sim_->restart();
    else if (k == "p")
      sim_->set_pace(frame_.pace == Pace::RealTime ? Pace::Fast
                     : frame_.pace == Pace::Fast   ? Pace::Fixed
                                                   : Pace::RealTime);
    else if (k == "c") {
      by_ = by_ == ColourBy::Type    ? ColourBy::State
            : by_ == ColourBy::State ? ColourBy::Speed
                                     : ColourBy::Type;
      set_colouring();
    } else if (k == "s") {
      // the next free lrigid_view_NNN.png
      std::string path;
      do {
        char name[48];
        std::snprintf(name, sizeof name, "lrigid_view_%03d.png", shot_++);
        path = (fs::path(a_.shot_dir) / name).string();
      } while (fs::exists(path));
      win_->Render();
      write_png(win_, path);
      std::fprintf(stderr, "lrigid: wrote %s\n", path.c_str());
    } else if (k == "o") {
      if (recording_) {
        recording_ = false;
        std::fprintf(stderr, "lrigid: wrote %d frames to %s\n", record_count_,
                     record_dir_.c_str());
      } else {
        start_recording(a_.record_dir);
        record_count_ = 0;
        std::fprintf(stderr, "lrigid: writing frames to %s\n", record_dir_.c_str());
      }
    } else if (k == "q" || k == "e" || k == "Escape") finish();
    else return false;
    return true;
  }

  void rethrow() {
    if (failure_) std::rethrow_exception(failure_);
  }

 private:
  const ViewArgs& a_;
  ViewSimulation* sim_;
  ViewFrame frame_;
  Bounds box_;
  vtkSmartPointer<vtkImageData> grid_;
  vtkNew<vtkRenderer> ren_;
  vtkNew<vtkRenderWindow> win_;
  vtkRenderWindowInteractor* iren_ = nullptr;
  vtkNew<vtkGlyph3DMapper> glyphs_;
  vtkNew<vtkPolyData> points_;
  vtkNew<vtkPoints> pts_;
  vtkNew<vtkFloatArray> q_;
  vtkNew<vtkUnsignedShortArray> index_;
  vtkNew<vtkUnsignedCharArray> rgb_;
  vtkNew<vtkFloatArray> speed_;
  vtkNew<vtkLookupTable> lut_;
  vtkNew<vtkScalarBarActor> speed_bar_;
  vtkNew<vtkActor> body_actor_;
  vtkNew<vtkTextActor> hud_;
  std::string enlarged_;          // which entries are drawn enlarged, for the heads-up text
  ColourBy by_ = ColourBy::Type;
  std::vector<Vec3> start_x_;     // (nbody) where the bodies start, m
  std::vector<std::string> entry_names_;  // (nentry)
  std::vector<size_t> entry_of_type_;     // (ntype) each body type's entry
  std::vector<double> factors_;           // (nentry) drawing factor
  vtkLegendBoxActor* legend_ = nullptr;   // held by the renderer
  double speed_max_ = 0;
  std::multimap<int, std::string> presses_;
  std::deque<Clock::time_point> draws_;
  Clock::time_point last_draw_ = Clock::now();
  double fps_ = 0, interval_ = 0;
  int drawn_ = 0;
  bool done_ = false;
  bool recording_ = false;
  std::string record_dir_;
  int record_count_ = 0;
  int shot_ = 0;
  std::exception_ptr failure_;
};

void view(const ViewArgs& a) {
  // the scene first, exactly as `lrigid run` reads it: its errors read the same
  Scene scene = read_scene(a.scene);
  if (a.seed >= 0) scene.seed = static_cast<uint64_t>(a.seed);
  check_memory(scene);
  check_picture_options(a.pic);
  require_display("view");
  FluidField field = load_field(scene, StreamMode::Auto, false);
  const Model model = compile_model(scene, std::move(field), cached_added_mass);
  // by default one core is left to the drawing (software OpenGL draws on the CPU too)
  const int threads = a.threads > 0 ? a.threads : std::max(1, omp_get_num_procs() - 1);
  ViewSimulation sim(scene, model, threads, parse_pace(a.pace), a.loop);  // its own copy
  Viewer viewer(a, scene, model, &sim);
  viewer.run();
  viewer.rethrow();
}

}  // namespace

void add_view_command(CLI::App& app) {
  auto args = std::make_shared<ViewArgs>();
  auto* cmd = app.add_subcommand(
      "view", "Watch a scene live in a window: simulate and draw at once (VTK/OpenGL, needs X)");
  cmd->footer(std::string("\n") + kControls +
              "\nScripted: --frames N [--screenshot out.png] [--write-frames DIR] draws N frames "
              "and exits (under xvfb-run -a without a display). docs/viewer.md");
  cmd->add_option("scene", args->scene, "Scene file (JSON, schema v1)")->required();
  cmd->add_option("--seed", args->seed, "Random seed (overrides the scene's seed), 0 or more")
      ->check(non_negative("a whole number, 0 or more (the random seed)"));
  cmd->add_option("--threads", args->threads, "Simulation threads (default: all cores but one, left to the drawing)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--pace", args->pace,
                  "realtime (simulated time follows the wall clock), fast (as fast as it can), "
                  "fixed (1/fps s of simulated time per drawn frame: reproducible movies)")
      ->check(CLI::IsMember({"realtime", "fast", "fixed"}));
  cmd->add_option("--fps", args->fps, "Frames drawn per second at most (default 30)")
      ->check(CLI::Range(1.0, 240.0));
  cmd->add_option("--frames", args->frames, "Draw this many frames after the first, then exit")
      ->check(CLI::Range(1, 10000000));
  cmd->add_option("--screenshot", args->screenshot, "PNG of the last frame, written at exit");
  cmd->add_option("--write-frames", args->write_frames,
                  "Write every drawn frame as DIR/frame_NNNNNN.png from the start");
  cmd->add_option("--record-dir", args->record_dir,
                  "Where the o key writes frames (default lrigid_frames)");
  cmd->add_option("--shot-dir", args->shot_dir, "Where the s key writes screenshots (default .)");
  cmd->add_option("--width", args->width, "Window width, pixels")->check(CLI::Range(16, 8192));
  cmd->add_option("--height", args->height, "Window height, pixels")->check(CLI::Range(16, 8192));
  cmd->add_option("--slice", args->slice,
                  "A horizontal slice of the grid under the bodies: none, U (|U|, m/s), k (m^2/s^2)")
      ->check(CLI::IsMember({"none", "U", "k"}));
  cmd->add_option("--slice-z", args->slice_z,
                  "Height of the slice, m (default: 4 % of the grid's height above its floor)");
  add_picture_options(cmd, &args->pic);
  cmd->add_option("--multisamples", args->multisamples,
                  "OpenGL antialiasing samples per pixel (default 0: software OpenGL draws "
                  "several times slower with 8)")
      ->check(CLI::Range(0, 16));
  cmd->add_flag("--loop", args->loop, "At the scene's end restart with the next seed");
  cmd->add_flag("!--no-hud", args->hud, "Hide the heads-up text");
  cmd->add_flag("--log", args->log, "Print the heads-up line of every drawn frame to stdout");
  cmd->add_option("--press", args->press,
                  "FRAME:KEY, a key pressed by script before frame FRAME is drawn (e.g. 10:+ or "
                  "5:space); repeatable")
      ->take_all();
  cmd->callback([args] { view(*args); });
}

}  // namespace lrigid::app
