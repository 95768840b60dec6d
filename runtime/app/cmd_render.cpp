// lrigid render RESULTS_DIR [-o preview.png] [--frames N --gif out.gif]
// Draws the bodies of a finished run with VTK (offscreen; needs an X display: xvfb-run -a),
// over a slice of k (or streamlines of U) from the run's grid, the ground otherwise.
#include <unistd.h>
#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkLineSource.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>
#include <vtkStreamTracer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "checks.h"
#include "commands.h"
#include "draw_style.h"
#include "io/result_writer.h"
#include "model/state.h"
#include "util/error.h"
#include "vtk_annotate.h"
#include "vtk_draw.h"

namespace lrigid::app {

namespace {

namespace fs = std::filesystem;

struct RenderArgs {
  std::string dir;
  std::string out;
  std::string gif;
  int frames = 0;
  int width = 1280, height = 720;
  double time = -1;  // s; < 0: the last frame
  std::string context = "auto";
  PictureOptions pic;  // camera, colouring, enlargement (draw_style.h)
  bool quiet = false;
};

using Rgb = std::array<unsigned char, 3>;

// all visible bodies of frame f as one surface, body type t drawn scale[t] times its size and
// body b in colour rgb[b]
vtkSmartPointer<vtkPolyData> bodies_at(const GltfAnimation& a, size_t f,
                                       const std::vector<double>& scale,
                                       const std::vector<Rgb>& rgb) {
  const size_t nb = a.bodies();
  auto pts = vtkSmartPointer<vtkPoints>::New();
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  auto col = vtkSmartPointer<vtkUnsignedCharArray>::New();
  col->SetName("colour");
  col->SetNumberOfComponents(3);
  for (size_t b = 0; b < nb; ++b) {
    if (a.hidden_at(f, b)) continue;  // not released yet, or removed at the grid's edge
    const TriangleMesh& s = a.types[size_t(a.body_type[b])].surface;
    const Mat3 R = a.q[f * nb + b].normalized().toRotationMatrix();
    const Vec3& x = a.x[f * nb + b];
    const double k = scale[size_t(a.body_type[b])];
    const vtkIdType p0 = pts->GetNumberOfPoints();
    for (const Vec3& v : s.vertices) {
      const Vec3 p = R * (k * v) + x;
      pts->InsertNextPoint(p.data());
    }
    for (const auto& tri : s.faces) {
      const vtkIdType ids[3] = {p0 + tri[0], p0 + tri[1], p0 + tri[2]};
      polys->InsertNextCell(3, ids);
      col->InsertNextTypedTuple(rgb[b].data());
    }
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pts);
  poly->SetPolys(polys);
  poly->GetCellData()->SetScalars(col);
  return poly;
}

// |v| of every body at frame f from its positions (m/s): the central difference over the
// neighbouring frames, one-sided at the first and the last; 0 with a single frame
std::vector<double> speeds_at(const GltfAnimation& a, size_t f) {
  const size_t nb = a.bodies(), nf = a.times.size();
  std::vector<double> v(nb, 0.0);
  if (nf < 2) return v;
  const size_t f0 = f == 0 ? 0 : f - 1, f1 = f + 1 < nf ? f + 1 : f;
  const double dt = a.times[f1] - a.times[f0];
  if (!(dt > 0)) return v;
  for (size_t b = 0; b < nb; ++b) v[b] = (a.x[f1 * nb + b] - a.x[f0 * nb + b]).norm() / dt;
  return v;
}

class Renderer {
 public:
  // `frames`: the frames that will be drawn (what --frame ENTRY and the true-scale rule look at)
  Renderer(const RenderArgs& args, const Results& r, const std::vector<size_t>& frames)
      : args_(args), r_(r), by_(args.pic.colouring()) {
    const GltfAnimation& a = r.frames;
    const size_t nb = a.bodies();
    // the body entries (a scene's `bodies`; an entry's variants are types of the same entry)
    std::vector<size_t> type_entry;
    std::vector<std::string> type_name;
    std::vector<double> type_size;
    for (const auto& t : a.types) {
      type_entry.push_back(t.entry);
      type_name.push_back(t.name);
      type_size.push_back(largest_extent(t.surface));
    }
    EntryTally tally(type_entry, type_name, type_size);
    for (size_t b = 0; b < nb; ++b) tally.add_body(size_t(a.body_type[b]));
    for (const size_t f : frames)
      for (size_t b = 0; b < nb; ++b)
        if (!a.hidden_at(f, b)) tally.add_seen(size_t(a.body_type[b]), a.x[f * nb + b]);
    entry_names_ = tally.names();
    // the default view: every visible body over the whole run (the camera does not move)
    for (size_t f = 0; f < a.times.size(); ++f)
      for (size_t b = 0; b < nb; ++b)
        if (!a.hidden_at(f, b)) box_.add(a.x[f * nb + b]);
    if (!box_.empty()) {
      box_.lo -= Vec3::Constant(tally.widest());
      box_.hi += Vec3::Constant(tally.widest());
    }

    if (by_ == ColourBy::State && a.state.empty())
      throw Error(ExitCode::Usage,
                  where((fs::path(args.dir) / "trajectories.csv").string(), "state",
                        "no state column (results of an older lrigid run): --color-by state "
                        "needs the bodies' states; run the scene again, or use --color-by type "
                        "or speed"));
    std::vector<bool> states_shown(kStateCount, false);
    double vmax = 0;
    for (const size_t f : frames) {
      const std::vector<double> v = speeds_at(a, f);
      for (size_t b = 0; b < nb; ++b) {
        if (a.hidden_at(f, b)) continue;
        vmax = std::max(vmax, v[b]);
        if (!a.state.empty()) states_shown[a.state[f * nb + b]] = true;
      }
    }

    ren_->GradientBackgroundOn();
    ren_->SetBackground(0.93, 0.94, 0.96);
    ren_->SetBackground2(0.62, 0.68, 0.78);
    win_->SetOffScreenRendering(1);
    win_->SetSize(args.width, args.height);
    win_->AddRenderer(ren_);
    add_context();
    camera_ = choose_camera(args.pic, box_, tally.boxes(), double(args.width) / args.height);
    // one drawing factor per entry: true size unless its bodies would be too small to see
    const std::vector<double> factor = tally.factors(args.pic, camera_, args.height);
    for (const auto& t : a.types) scale_.push_back(factor[t.entry]);
    const std::string note = enlargement_note(entry_names_, factor);
    if (!note.empty() && args.pic.body_scale <= 0 && !args.quiet)
      std::fprintf(stderr,
                   "lrigid: render: %s (at true size their median body would span under %g "
                   "pixels; --body-scale 1 draws true size)\n",
                   note.c_str(), kMinBodyPixels);
    add_legend(ren_, legend_entries(by_, entry_names_, factor, states_shown), args.width,
               args.height);
    if (by_ == ColourBy::Speed) {
      speed_colours(lut_, vmax);
      speed_bar(bar_, lut_, args.height / 3);
      ren_->AddActor2D(bar_);
    }
    body_mapper_->SetScalarModeToUseCellData();
    body_mapper_->SetColorModeToDirectScalars();
    body_actor_->SetMapper(body_mapper_);
    body_actor_->GetProperty()->SetSpecular(0.2);
    ren_->AddActor(body_actor_);
    text_->GetTextProperty()->SetFontSize(std::max(12, args.height / 36));
    text_->GetTextProperty()->SetColor(0.1, 0.1, 0.15);
    text_->SetPosition(12, 10);
    ren_->AddActor2D(text_);
    // fixed camera over the whole run: bodies move, the view does not
    apply_camera(ren_, camera_);
  }

  void draw(size_t f, const std::string& png) {
    const GltfAnimation& a = r_.frames;
    const size_t nb = a.bodies();
    std::vector<Rgb> rgb(nb);
    const std::vector<double> v = by_ == ColourBy::Speed ? speeds_at(a, f) : std::vector<double>();
    for (size_t b = 0; b < nb; ++b) {
      if (by_ == ColourBy::Type) {
        type_colour(a.types[size_t(a.body_type[b])].entry, rgb[b].data());
      } else if (by_ == ColourBy::State) {
        state_colour(a.state[f * nb + b], rgb[b].data());
      } else {
        const unsigned char* c = lut_->MapValue(v[b]);
        rgb[b] = {c[0], c[1], c[2]};
      }
    }
    body_mapper_->SetInputData(bodies_at(a, f, scale_, rgb));
    char buf[128];
    // the bodies drawn: not those hidden (removed at the grid's edge, or not released yet)
    size_t shown = 0;
    for (size_t b = 0; b < nb; ++b) shown += a.hidden_at(f, b) ? 0 : 1;
    if (shown == nb)
      std::snprintf(buf, sizeof buf, "t = %.2f s   %zu bodies", a.times[f], nb);
    else
      std::snprintf(buf, sizeof buf, "t = %.2f s   %zu of %zu bodies shown", a.times[f], shown,
                    nb);
    // the colours and the enlargement are in the legend; the caption says where we are
    const std::string label = buf + context_note_;
    text_->SetInput(label.c_str());
    text_->GetTextProperty()->SetFontSize(std::max(12, args_.height / 36));
    fit_caption(text_, ren_, args_.width, 12);
    ren_->ResetCameraClippingRange();
    win_->Render();
    write_png(win_, png);
  }

 private:
  void add_context() {
    const auto& s = r_.summary;
    const bool has_field = s.contains("field") && s["field"].is_string();
    std::string mode = args_.context;
    if (mode == "auto") mode = has_field ? "k" : "ground";
    if ((mode == "k" || mode == "streamlines") && !has_field)
      throw Error(ExitCode::Usage,
                  where((fs::path(args_.dir) / "summary.json").string(), "field",
                        "--context " + mode + " needs a grid run (uniform flow has none)"));
    if (mode == "k" || mode == "streamlines") {
      vtkSmartPointer<vtkImageData> img =
          read_grid_image(s["field"].get<std::string>(), "summary.json \"field\"");
      grid_ = img;
      double gb[6];
      img->GetBounds(gb);
      // the camera frames the bodies (and the floor below them), not the whole grid
      box_.add(Vec3(box_.lo.x(), box_.lo.y(), gb[4]));
      add_solids(ren_, img);
      // the domain: the grid's box; in water, the tank's walls and its surface (the grid's top)
      const bool water = s.contains("fluid_density") && s["fluid_density"].is_number() &&
                         s["fluid_density"].get<double>() >= 100;
      add_domain(ren_, img, water);
      if (water) {
        // a tank is small: show all of it
        box_.add(Vec3(gb[0], gb[2], gb[4]));
        box_.add(Vec3(gb[1], gb[3], gb[5]));
      }
      context_note_ = std::string(water ? "   tank: walls, floor, water surface (grid top)"
                                        : "   grid outline") +
                      (mode == "k" ? ", slice of k near the floor" : ", streamlines of U");
      // k just above the grid's floor (obstacles show as k = 0, the value the grid keeps at
      // invalid points), drawn as a map a little below the floor: bodies lying on the ground
      // stay on top of it (drawn at its height, the translucent slice faded them)
      if (mode == "k")
        add_slice(ren_, img, "k", gb[4] + 0.04 * (gb[5] - gb[4]), "k (m^2/s^2)", args_.height / 2,
                  gb[4] - 0.002 * (gb[5] - gb[4]));
      else
        add_streamlines(img, gb);
      return;
    }
    if (mode == "ground" && s.contains("ground_z") && s["ground_z"].is_number()) {
      add_ground(ren_, s["ground_z"].get<double>(), &box_);
    } else if (mode != "ground" && mode != "none") {
      throw Error(
          ExitCode::Usage,
          "--context must be auto, k, streamlines, ground or none, got \"" + args_.context + "\"");
    }
  }

  // streamlines of U seeded along a line across the inflow side
  void add_streamlines(vtkImageData* img, const double gb[6]) {
    if (!img->GetPointData()->GetArray("U")) return;
    img->GetPointData()->SetActiveVectors("U");
    vtkNew<vtkLineSource> seeds;
    const double zc = gb[4] + 0.3 * (gb[5] - gb[4]);
    seeds->SetPoint1(gb[0] + 0.02 * (gb[1] - gb[0]), gb[2] + 0.05 * (gb[3] - gb[2]), zc);
    seeds->SetPoint2(gb[0] + 0.02 * (gb[1] - gb[0]), gb[3] - 0.05 * (gb[3] - gb[2]), zc);
    seeds->SetResolution(24);
    vtkNew<vtkStreamTracer> st;
    st->SetInputData(img);
    st->SetSourceConnection(seeds->GetOutputPort());
    st->SetIntegrationDirectionToForward();
    st->SetMaximumPropagation(4 * (gb[1] - gb[0] + gb[3] - gb[2] + gb[5] - gb[4]));
    st->SetIntegratorTypeToRungeKutta45();
    vtkNew<vtkPolyDataMapper> m;
    m->SetInputConnection(st->GetOutputPort());
    m->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(m);
    actor->GetProperty()->SetColor(0.25, 0.3, 0.45);
    actor->GetProperty()->SetLineWidth(1.5);
    ren_->AddActor(actor);
  }

  const RenderArgs& args_;
  const Results& r_;
  ColourBy by_;
  Bounds box_;
  CameraPose camera_;
  std::vector<std::string> entry_names_;  // (nentry) each body entry's name
  std::vector<double> scale_;  // (ntype) drawing scale of each body type: its entry's factor
  vtkNew<vtkRenderer> ren_;
  vtkNew<vtkRenderWindow> win_;
  vtkSmartPointer<vtkImageData> grid_;  // kept alive for the streamlines' pipeline
  vtkNew<vtkPolyDataMapper> body_mapper_;
  vtkNew<vtkActor> body_actor_;
  vtkNew<vtkLookupTable> lut_;  // speed colours
  vtkNew<vtkScalarBarActor> bar_;
  vtkNew<vtkTextActor> text_;
  std::string context_note_;  // what the context shows, for the caption
};

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

size_t frame_at(const std::vector<double>& times, double t) {
  if (t < 0) return times.size() - 1;
  size_t best = 0;
  for (size_t i = 1; i < times.size(); ++i)
    if (std::abs(times[i] - t) < std::abs(times[best] - t)) best = i;
  return best;
}

void render(RenderArgs a) {
  if (a.out.empty() && a.gif.empty()) a.out = (fs::path(a.dir) / "preview.png").string();
  if (!a.gif.empty() && a.frames < 2) a.frames = 60;
  if (a.frames > 0 && a.gif.empty())
    throw Error(ExitCode::Usage, "--frames needs --gif OUT.gif (where to write the animation)");
  std::string convert;
  if (!a.gif.empty()) {
    // ImageMagick assembles the frames (VTK has no GIF writer)
    for (const char* p : {"/usr/bin/convert", "/usr/bin/convert-im6.q16"})
      if (convert.empty() && fs::exists(p)) convert = p;
    if (convert.empty())
      throw Error(ExitCode::Runtime, "--gif needs ImageMagick's convert (Debian package "
                                     "imagemagick; scripts/install-deps installs it)");
  }
  check_picture_options(a.pic);
  require_display("render");
  const Results r = read_results(a.dir, 80);
  const auto& times = r.frames.times;
  const size_t nf = times.size();
  const int n = a.frames;
  // the frames drawn: the PNG's, then the GIF's, evenly spread over the run
  auto gif_frame = [&](int i) {
    return nf == 1 ? size_t(0) : size_t(std::lround(double(i) * double(nf - 1) / (n - 1)));
  };
  std::vector<size_t> drawn;
  if (!a.out.empty()) drawn.push_back(frame_at(times, a.time));
  if (!a.gif.empty())
    for (int i = 0; i < n; ++i) drawn.push_back(gif_frame(i));
  Renderer ren(a, r, drawn);
  if (!a.out.empty()) {
    ren.draw(drawn.front(), a.out);
    if (!a.quiet) std::fprintf(stderr, "lrigid: wrote %s\n", a.out.c_str());
  }
  if (!a.gif.empty()) {
    const std::string tmp_dir = a.gif + ".frames.tmp" + std::to_string(::getpid());
    std::error_code ec;
    fs::create_directories(tmp_dir, ec);
    if (ec) throw Error(ExitCode::Output, where(tmp_dir, "", "cannot create: " + ec.message()));
    struct Cleanup {
      std::string d;
      ~Cleanup() {
        std::error_code e;
        fs::remove_all(d, e);
      }
    } cleanup{tmp_dir};
    for (int i = 0; i < n; ++i) {
      const size_t f = gif_frame(i);
      char name[32];
      std::snprintf(name, sizeof name, "frame_%05d.png", i);
      ren.draw(f, (fs::path(tmp_dir) / name).string());
      if (!a.quiet && isatty(STDERR_FILENO))
        std::fprintf(stderr, "\rlrigid: frame %d / %d", i + 1, n);
    }
    if (!a.quiet && isatty(STDERR_FILENO)) std::fputc('\n', stderr);
    // play at simulated speed, within what GIF viewers honour (2..50 hundredths of a second)
    const double span = nf > 1 ? times.back() - times.front() : 1.0;
    const int delay = std::clamp(int(std::lround(100 * span / std::max(1, n - 1))), 2, 50);
    const std::string tmp_gif = a.gif + ".tmp" + std::to_string(::getpid()) + ".gif";
    const std::string cmd = shell_quote(convert) + " -delay " + std::to_string(delay) +
                            " -loop 0 " + shell_quote(tmp_dir) + "/frame_*.png -layers Optimize " +
                            shell_quote(tmp_gif);
    if (std::system(cmd.c_str()) != 0 || !fs::exists(tmp_gif)) {
      fs::remove(tmp_gif, ec);
      throw Error(ExitCode::Output, where(a.gif, "", "ImageMagick could not assemble the GIF"));
    }
    fs::rename(tmp_gif, a.gif, ec);
    if (ec)
      throw Error(ExitCode::Output, where(a.gif, "", "cannot move into place: " + ec.message()));
    if (!a.quiet) std::fprintf(stderr, "lrigid: wrote %s (%d frames)\n", a.gif.c_str(), n);
  }
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  auto* cmd = app.add_subcommand(
      "render", "Draw a run's bodies to a PNG (and a GIF) with VTK; needs X: use xvfb-run -a");
  cmd->add_option("results", args->dir, "Results directory of lrigid run")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("-o,--output", args->out, "PNG of one frame (default RESULTS/preview.png)");
  cmd->add_option("--time", args->time, "Time of the PNG's frame, s (default: the last)");
  cmd->add_option("--frames", args->frames, "Frames of the animation (default 60 with --gif)")
      ->check(CLI::Range(2, 100000));
  cmd->add_option("--gif", args->gif, "Animated GIF to write (ImageMagick assembles it)");
  cmd->add_option("--width", args->width, "Image width, pixels")->check(CLI::Range(16, 8192));
  cmd->add_option("--height", args->height, "Image height, pixels")->check(CLI::Range(16, 8192));
  cmd->add_option("--context", args->context,
                  "What to draw behind the bodies: auto (k slice for grid runs, else the "
                  "ground), k, streamlines, ground, none");
  add_picture_options(cmd, &args->pic);
  cmd->add_flag("--quiet", args->quiet, "Print nothing but errors");
  cmd->callback([args] { render(*args); });
}

}  // namespace lrigid::app
