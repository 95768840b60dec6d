// What `lrigid render` and `lrigid view` both let the user choose about the picture, and how
// those choices become a camera, colours and a legend: the flags --camera-position,
// --camera-target, --fov, --frame, --color-by and --body-scale (--enlarge), the default framing,
// the true-scale rule per body entry (camera.h), the state colours. No VTK (vtk_draw.h draws).
#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "body/shape.h"
#include "camera.h"

namespace lrigid::app {

enum class ColourBy { Type, State, Speed };

struct PictureOptions {
  std::vector<double> camera_position;  // m; empty: the default framing's
  std::vector<double> camera_target;    // m; empty: the default framing's
  double fov_deg = kDefaultFovDeg;      // vertical field of view, degrees
  std::vector<std::string> frame;       // empty, {ENTRY} or {x0, x1, y0, y1, z0, z1} (m)
  std::string colour_by = "type";       // type, state or speed
  double body_scale = 0;                // > 0: every body drawn this many times larger
  ColourBy colouring() const;
};

// Registers the flags above on `cmd` (both commands call it, so they read the same).
void add_picture_options(CLI::App* cmd, PictureOptions* o);

// Checks what can be checked before anything is read: the field of view in (0, 180) degrees,
// a camera position apart from its target, a --frame of one name or of 6 numbers with
// x0 < x1, y0 < y1, z0 < z1. Throws lrigid::Error(ExitCode::Usage) naming the flag and value.
void check_picture_options(const PictureOptions& o);

// The body entries of a scene (the `bodies` of the scene file; their variants share one) as the
// picture knows them: each entry's name and the box its visible bodies span over the frames
// drawn (widened by half the largest body), for --frame ENTRY.
struct EntryBoxes {
  std::vector<std::string> names;
  std::vector<Bounds> boxes;
};

// The camera the flags ask for. Without flags: the default framing of `whole` (fit_box from
// default_view_direction(), 30 degrees). --frame fits an entry's box (an unknown name is an
// error listing the names) or the given box instead; --fov changes the field of view of the fit;
// --camera-target moves the picture's centre there (the camera keeps its offset from it),
// --camera-position puts the camera there (looking at the target). `aspect` = width / height.
CameraPose choose_camera(const PictureOptions& o, const Bounds& whole, const EntryBoxes& entries,
                         double aspect);

// The largest extent of a body's surface (its bounding box's longest side), m: its size for the
// true-scale rule.
double largest_extent(const TriangleMesh& surface);

// The body entries as the picture sees them, gathered from the body types and from the bodies
// where they are drawn: their names, the boxes --frame ENTRY fits, and what the true-scale rule
// weighs (each body's size, where the bodies are).
class EntryTally {
 public:
  // per body type: the entry it belongs to, its name and its size (m, largest_extent)
  EntryTally(const std::vector<size_t>& type_entry, const std::vector<std::string>& type_name,
             const std::vector<double>& type_size);
  void add_body(size_t type);                 // a body of the type: its size counts once
  void add_seen(size_t type, const Vec3& x);  // a body of the type drawn at x (m)
  size_t entry_of(size_t type) const { return type_entry_[type]; }
  const std::vector<std::string>& names() const { return names_; }
  // the entries' boxes, each widened by half its largest body
  EntryBoxes boxes() const;
  // half the largest body of all, m
  double widest() const;
  // the drawing factor of each entry: --body-scale for all when given, else the true-scale rule
  // (camera.h true_scale_factor)
  std::vector<double> factors(const PictureOptions& o, const CameraPose& c, int height) const;

 private:
  std::vector<size_t> type_entry_;
  std::vector<double> type_size_;
  std::vector<std::string> names_;          // (nentry)
  std::vector<double> reach_;               // (nentry) half the largest body, m
  std::vector<std::vector<double>> sizes_;  // (nentry) each body's size, m
  std::vector<std::vector<Vec3>> seen_;     // (nentry) where its bodies are drawn, m
  std::vector<Bounds> boxes_;               // (nentry) of seen_
};

// "drawn enlarged: leaf x2.3, paper x1.5" for the entries drawn larger than true (factor > 1.05),
// empty when none is.
std::string enlargement_note(const std::vector<std::string>& names,
                             const std::vector<double>& factors);

// Colour of a body state (State::state_code: 0 flying, 1 sliding, 2 resting, 3 sleeping,
// 4 exited, 5 landed, 6 failed), RGB 0..255: warm and saturated, so resting and sleeping bodies
// stand out on the blue k and |U| slices and the grey ground.
void state_colour(int code, unsigned char rgb[3]);

// One line of the legend: a swatch in `rgb` (none when !swatch) and its label.
struct LegendEntry {
  std::string label;
  unsigned char rgb[3] = {0, 0, 0};
  bool swatch = true;
};

// The legend of a colouring: per entry (type) its colour, name and enlargement; per state shown
// (state) its colour and name, with the enlargements as lines without swatch; for speed only
// the enlargements (the colour bar says the rest). `states_shown` (kStateCount) says which
// states to list.
std::vector<LegendEntry> legend_entries(ColourBy by, const std::vector<std::string>& entry_names,
                                        const std::vector<double>& factors,
                                        const std::vector<bool>& states_shown);

}  // namespace lrigid::app
