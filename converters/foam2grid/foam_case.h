// An OpenFOAM case on disk: its times, its mesh (one part, or one part per processor* directory
// of a decomposed case) and its volume fields, read as OpenFOAM stores them.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace foam2grid {

using Label = std::int64_t;

/// One patch of constant/polyMesh/boundary.
struct Patch {
  std::string name;
  std::string type;  ///< mesh type: patch, wall, symmetry, empty, processor, cyclic, ...
  Label start = 0;   ///< first face
  Label size = 0;    ///< number of faces
  /// True for patches whose faces give boundary point values (not empty, not coupled).
  bool gives_point_values() const;
  /// True for patches that constrain point vectors to the tangent plane (symmetry, wedge).
  bool is_symmetry() const;
};

/// One polyMesh (the whole case or one processor) with the geometry OpenFOAM derives from it.
struct MeshPart {
  std::string dir;                  ///< case or processorN directory
  std::vector<double> points;       ///< (nPoints x 3) coordinates, m
  std::vector<Label> face_offsets;  ///< (nFaces + 1) start of each face in face_points
  std::vector<Label> face_points;   ///< point labels of all faces, in OpenFOAM order
  std::vector<Label> owner;         ///< (nFaces) owner cell
  std::vector<Label> neighbour;     ///< (nInternalFaces) neighbour cell
  Label n_cells = 0;
  std::vector<Patch> patches;
  std::vector<Label> point_global;  ///< (nPoints) global point label; empty: identity

  // derived geometry (compute_geometry), as OpenFOAM's primitiveMesh computes it
  std::vector<double> boundary_face_centres;  ///< (nBoundaryFaces x 3) m
  std::vector<double> boundary_face_areas;    ///< (nBoundaryFaces x 3) area vectors, m^2
  std::vector<double> cell_centres;           ///< (nCells x 3) m
  std::vector<double> cell_volumes;           ///< (nCells) m^3
  std::vector<Label> cell_face_offsets;       ///< (nCells + 1)
  std::vector<Label> cell_faces;              ///< faces of each cell
  std::vector<int> tet_base;                  ///< (nFaces) base point of each face's triangle fan

  Label n_points() const { return static_cast<Label>(points.size() / 3); }
  Label n_faces() const { return static_cast<Label>(owner.size()); }
  Label n_internal_faces() const { return static_cast<Label>(neighbour.size()); }
  Label global(Label p) const { return point_global.empty() ? p : point_global[p]; }
};

/// Where the mesh and fields come from.
enum class CaseSource { kAuto, kReconstructed, kDecomposed };

/// The case directory as found on disk.
struct FoamCase {
  std::string dir;                      ///< absolute case directory
  std::string name;                     ///< its last path component
  bool decomposed = false;              ///< read from processor* directories
  std::vector<std::string> part_dirs;   ///< the case dir, or processor0, processor1, ...
  std::vector<std::string> time_names;  ///< written times (directory names), ascending
  std::vector<double> time_values;      ///< the same as numbers, s
};

/// Opens a case: checks the directory, picks reconstructed or decomposed data and lists times.
FoamCase open_case(const std::string& dir, CaseSource source);

/// Reads only the points of every part (for the bounding box before the rest).
void read_points(const FoamCase& fc, std::vector<MeshPart>* parts);
/// Reads faces, owner, neighbour, boundary (and pointProcAddressing) and derives the geometry.
void read_topology(const FoamCase& fc, std::vector<MeshPart>* parts);

/// Boundary face centres and areas, cell centres and volumes (OpenFOAM's formulas), cell-face
/// lists and
/// the base point of each face's triangle fan (the first point that gives positive tets).
void compute_geometry(MeshPart* m);

/// A set of fields on one part, stacked component-wise: ncomp values per cell and per face.
struct PartFields {
  int ncomp = 0;                 ///< total components (U counts 3)
  std::vector<double> cells;     ///< (nCells x ncomp)
  std::vector<double> boundary;  ///< (nBoundaryFaces x ncomp) patch face values
};

/// One requested field: name and components (1 or 3).
struct FieldSpec {
  std::string name;
  int ncomp = 1;
  int offset = 0;  ///< first component in the stacked arrays
};

/// Reads the fields at time_name on one part, with boundary face values as OpenFOAM evaluates
/// them (value entries; zeroGradient; noSlip; symmetry). Fails on missing files or NaN.
void read_fields(const MeshPart& m, const std::string& time_name,
                 const std::vector<FieldSpec>& fields, PartFields* out);

/// nu from constant/transportProperties, m^2/s.
double read_viscosity(const std::string& case_dir);

}  // namespace foam2grid
