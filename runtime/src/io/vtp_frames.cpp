#include "io/vtp_frames.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <cstdio>

#include "io/result_writer.h"
#include "util/error.h"

namespace lrigid {

namespace {

// one .vtp file: appended raw binary (no base64), 32-bit ids, or ExitCode::Output naming it.
// VTK builds the file in memory (writing to the file itself, it seeks back and forth to fill in
// the offsets, a system call each), then it goes out in one write.
void write_polydata(vtkPolyData* poly, const std::string& path, VtpCompression c) {
  // the arrays are kept from frame to frame: VTK then keeps their ranges in their information,
  // and would write it, so that the first frame of a process would differ from the others
  // (and a resumed run from an uninterrupted one): every frame starts from none
  for (vtkFieldData* fd : {static_cast<vtkFieldData*>(poly->GetPointData()),
                           static_cast<vtkFieldData*>(poly->GetCellData())})
    for (int i = 0; i < fd->GetNumberOfArrays(); ++i)
      if (fd->GetAbstractArray(i)->HasInformation())
        fd->GetAbstractArray(i)->GetInformation()->Clear();
  if (poly->GetPoints()->GetData()->HasInformation())
    poly->GetPoints()->GetData()->GetInformation()->Clear();
  vtkNew<vtkXMLPolyDataWriter> w;
  w->WriteToOutputStringOn();
  w->SetInputData(poly);
  w->SetDataModeToAppended();
  w->EncodeAppendedDataOff();
  w->SetIdTypeToInt32();
  if (c == VtpCompression::LZ4) w->SetCompressorTypeToLZ4(), w->SetCompressionLevel(1);
  else if (c == VtpCompression::ZLib) w->SetCompressorTypeToZLib(), w->SetCompressionLevel(1);
  else w->SetCompressorTypeToNone();
  if (w->Write() != 1 || w->GetErrorCode() != vtkErrorCode::NoError)
    throw Error(ExitCode::Output, where(path, "", "cannot build the .vtp frame"));
  const std::string bytes = w->GetOutputString();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  const bool ok = f && std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  if (!f || std::fclose(f) != 0 || !ok)
    throw Error(ExitCode::Output, where(path, "", "cannot write .vtp frame (disk full?)"));
}

template <class A>
vtkSmartPointer<A> named(const char* name, int components, vtkIdType tuples) {
  auto a = vtkSmartPointer<A>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(tuples);
  return a;
}

// cells of `n` items of `per` points each, point ids 0.. in order
vtkSmartPointer<vtkCellArray> cells_in_order(vtkIdType n, vtkIdType per) {
  vtkNew<vtkIdTypeArray> offsets, conn;
  offsets->SetNumberOfTuples(n + 1);
  conn->SetNumberOfTuples(n * per);
  for (vtkIdType i = 0; i <= n; ++i) offsets->SetValue(i, i * per);
  for (vtkIdType i = 0; i < n * per; ++i) conn->SetValue(i, i);
  auto c = vtkSmartPointer<vtkCellArray>::New();
  c->SetData(offsets, conn);
  return c;
}

}  // namespace

TriangleMesh series_surface(const BodyType& type, int target_faces) {
  if (type.shape.type != ShapeType::Box) return body_surface(type, target_faces);
  const Vec3& h = type.shape.half_extents;
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)  // corner i: bit 0 x, bit 1 y, bit 2 z (set: +h)
    m.vertices.push_back(Vec3(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(),
                              i & 4 ? h.z() : -h.z()) - type.com);
  // two triangles per face, counter-clockwise seen from outside
  m.faces = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6},   // z = -h, +h
             {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},   // y = -h, +h
             {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};  // x = -h, +h
  return m;
}

struct BodiesFrames::Impl {
  const Model& model;
  VtpCompression compression;
  size_t n = ~size_t(0);
  vtkSmartPointer<vtkPolyData> poly;
  vtkSmartPointer<vtkDoubleArray> xyz, orient, vel, angvel;
  vtkSmartPointer<vtkUnsignedCharArray> status, state;

  // the arrays and the vertices, once: the bodies and their types do not change during a run
  void build(const State& st) {
    n = st.size();
    const vtkIdType nb = vtkIdType(n);
    xyz = named<vtkDoubleArray>("Points", 3, nb);
    vtkNew<vtkPoints> pts;
    pts->SetData(xyz);
    orient = named<vtkDoubleArray>("orientation", 4, nb);  // quaternion w, x, y, z (body -> world)
    vel = named<vtkDoubleArray>("velocity", 3, nb);
    angvel = named<vtkDoubleArray>("angular_velocity", 3, nb);
    auto id = named<vtkIntArray>("body", 1, nb);
    auto type = named<vtkIntArray>("type", 1, nb);
    status = named<vtkUnsignedCharArray>("status", 1, nb);  // 0 moving, 1 landed, 2 exited, 3 failed
    // 0 flying, 1 sliding, 2 resting, 3 sleeping, 4 exited, 5 landed, 6 failed (State::state_code)
    state = named<vtkUnsignedCharArray>("state", 1, nb);
    for (vtkIdType i = 0; i < nb; ++i) id->SetValue(i, int(i)), type->SetValue(i, st.type[i]);
    poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(pts);
    poly->SetVerts(cells_in_order(nb, 1));
    for (vtkDataArray* a : {static_cast<vtkDataArray*>(orient), static_cast<vtkDataArray*>(vel),
                            static_cast<vtkDataArray*>(angvel), static_cast<vtkDataArray*>(id),
                            static_cast<vtkDataArray*>(type), static_cast<vtkDataArray*>(status),
                            static_cast<vtkDataArray*>(state)})
      poly->GetPointData()->AddArray(a);
  }
};

BodiesFrames::BodiesFrames(const Model& model, VtpCompression c)
    : p_(new Impl{model, c, ~size_t(0), {}, {}, {}, {}, {}, {}, {}}) {}
BodiesFrames::~BodiesFrames() = default;

void BodiesFrames::write(const State& st, const std::string& path) {
  Impl& p = *p_;
  if (p.n != st.size()) p.build(st);
  double* x = p.xyz->GetPointer(0);
  double* q = p.orient->GetPointer(0);
  double* v = p.vel->GetPointer(0);
  double* w = p.angvel->GetPointer(0);
  unsigned char* s = p.status->GetPointer(0);
  unsigned char* c = p.state->GetPointer(0);
  for (size_t i = 0; i < p.n; ++i) {
    c[i] = st.state_code(i);
    const Mat3 R = st.q[i].toRotationMatrix();
    const Vec3 vi = body_velocity(p.model, st, i, R), wi = R * st.w[i];
    for (int k = 0; k < 3; ++k) x[3 * i + k] = st.x[i][k], v[3 * i + k] = vi[k], w[3 * i + k] = wi[k];
    q[4 * i] = st.q[i].w(), q[4 * i + 1] = st.q[i].x(), q[4 * i + 2] = st.q[i].y(),
          q[4 * i + 3] = st.q[i].z();
    s[i] = static_cast<unsigned char>(st.status[i]);
  }
  for (vtkDataArray* a : {static_cast<vtkDataArray*>(p.xyz), static_cast<vtkDataArray*>(p.orient),
                          static_cast<vtkDataArray*>(p.vel), static_cast<vtkDataArray*>(p.angvel),
                          static_cast<vtkDataArray*>(p.status), static_cast<vtkDataArray*>(p.state)})
    a->Modified();
  p.poly->Modified();
  write_polydata(p.poly, path, p.compression);
}

struct ShapesFrames::Impl {
  std::vector<TriangleMesh> surfaces;
  VtpCompression compression;
  size_t n = ~size_t(0);
  std::vector<std::vector<float>> local;  // (ntype) the surfaces' vertices as float, body frame
  vtkSmartPointer<vtkPolyData> poly;
  vtkSmartPointer<vtkFloatArray> xyz;     // float is plenty for display and halves the files
  vtkSmartPointer<vtkUnsignedCharArray> status, state;

  void build(const State& st) {
    n = st.size();
    local.clear();
    for (const TriangleMesh& m : surfaces) {
      std::vector<float> f;
      for (const Vec3& v : m.vertices) f.insert(f.end(), {float(v.x()), float(v.y()), float(v.z())});
      local.push_back(std::move(f));
    }
    vtkIdType np = 0, nc = 0;
    for (size_t i = 0; i < n; ++i) {
      np += vtkIdType(surfaces[st.type[i]].vertices.size());
      nc += vtkIdType(surfaces[st.type[i]].faces.size());
    }
    xyz = named<vtkFloatArray>("Points", 3, np);
    vtkNew<vtkPoints> pts;
    pts->SetData(xyz);
    vtkNew<vtkIdTypeArray> offsets, conn;
    offsets->SetNumberOfTuples(nc + 1);
    conn->SetNumberOfTuples(3 * nc);
    auto id = named<vtkIntArray>("body", 1, nc);
    auto type = named<vtkIntArray>("type", 1, nc);
    status = named<vtkUnsignedCharArray>("status", 1, nc);  // 0 moving, 1 landed, 2 exited, 3 failed
    state = named<vtkUnsignedCharArray>("state", 1, nc);    // State::state_code
    vtkIdType p0 = 0, c = 0;
    for (size_t i = 0; i < n; ++i) {
      const TriangleMesh& s = surfaces[st.type[i]];
      for (const auto& f : s.faces) {
        offsets->SetValue(c, 3 * c);
        for (int k = 0; k < 3; ++k) conn->SetValue(3 * c + k, p0 + f[k]);
        id->SetValue(c, int(i));
        type->SetValue(c, st.type[i]);
        ++c;
      }
      p0 += vtkIdType(s.vertices.size());
    }
    offsets->SetValue(nc, 3 * nc);
    auto polys = vtkSmartPointer<vtkCellArray>::New();
    polys->SetData(offsets, conn);
    poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(pts);
    poly->SetPolys(polys);
    poly->GetCellData()->AddArray(id);
    poly->GetCellData()->AddArray(type);
    poly->GetCellData()->AddArray(status);
    poly->GetCellData()->AddArray(state);
  }
};

ShapesFrames::ShapesFrames(std::vector<TriangleMesh> surfaces, VtpCompression c)
    : p_(new Impl{std::move(surfaces), c, ~size_t(0), {}, {}, {}, {}, {}}) {}
ShapesFrames::~ShapesFrames() = default;

void ShapesFrames::write(const State& st, const std::string& path) {
  Impl& p = *p_;
  if (p.n != st.size()) p.build(st);
  float* out = p.xyz->GetPointer(0);
  unsigned char* s = p.status->GetPointer(0);
  unsigned char* c = p.state->GetPointer(0);
  for (size_t i = 0; i < p.n; ++i) {
    // a body removed at the grid's edge ("outside": "remove") shrinks to a point: hidden
    const float shown = i < st.hidden.size() && st.hidden[i] ? 0.f : 1.f;
    const Eigen::Matrix3f R = shown * st.q[i].toRotationMatrix().cast<float>();
    const Eigen::Vector3f x = st.x[i].cast<float>();
    const std::vector<float>& loc = p.local[st.type[i]];
    for (size_t k = 0; k < loc.size(); k += 3, out += 3) {
      Eigen::Map<Eigen::Vector3f> o(out);
      o = R * Eigen::Map<const Eigen::Vector3f>(&loc[k]) + x;
    }
    const size_t faces = p.surfaces[st.type[i]].faces.size();
    std::fill(s, s + faces, static_cast<unsigned char>(st.status[i]));
    std::fill(c, c + faces, st.state_code(i));
    s += faces;
    c += faces;
  }
  p.xyz->Modified();
  p.status->Modified();
  p.state->Modified();
  p.poly->Modified();
  write_polydata(p.poly, path, p.compression);
}

FramesThread::FramesThread(const Model& model, std::vector<TriangleMesh> surfaces,
                           VtpCompression c)
    : bodies_(model, c), shapes_(std::move(surfaces), c) {}

FramesThread::~FramesThread() {
  try {
    wait();
  } catch (...) {
    // destroyed on an error path already: the first error is the one reported
  }
}

void FramesThread::wait() {
  if (pending_.valid()) pending_.get();
}

void FramesThread::write(const State& st, std::string bodies_path, std::string shapes_path) {
  wait();
  copy_.t = st.t;
  copy_.step = st.step;
  copy_.x = st.x;
  copy_.q = st.q;
  copy_.v = st.v;
  copy_.w = st.w;
  copy_.u_seen = st.u_seen;
  copy_.type = st.type;
  copy_.status = st.status;
  copy_.contact = st.contact;
  copy_.hidden = st.hidden;
  pending_ = std::async(std::launch::async, [this, b = std::move(bodies_path),
                                             s = std::move(shapes_path)] {
    bodies_.write(copy_, b);
    shapes_.write(copy_, s);
  });
}

}  // namespace lrigid
