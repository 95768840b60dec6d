#include "grid_io.h"

#include <unistd.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLImageDataWriter.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <regex>
#include <sstream>

#include "error.h"

namespace fs = std::filesystem;

namespace foam2grid {

std::string temp_name(const std::string& path) {
  const fs::path p(path);
  return (p.parent_path() / ("." + p.filename().string() + ".tmp" + std::to_string(getpid())))
      .string();
}

void write_vti(const std::string& path, const GridSpec& grid, const std::vector<FieldSpec>& specs,
               GridFields* data, const GridMeta& meta) {
  vtkNew<vtkImageData> image;
  image->SetDimensions(static_cast<int>(grid.dims[0]), static_cast<int>(grid.dims[1]),
                       static_cast<int>(grid.dims[2]));
  image->SetOrigin(grid.origin[0], grid.origin[1], grid.origin[2]);
  image->SetSpacing(grid.spacing[0], grid.spacing[1], grid.spacing[2]);
  const vtkIdType np = static_cast<vtkIdType>(grid.n_points());
  for (std::size_t s = 0; s < specs.size(); ++s) {
    vtkNew<vtkFloatArray> a;
    a->SetName(specs[s].name.c_str());
    a->SetNumberOfComponents(specs[s].ncomp);
    // borrow the buffer (save = 1: VTK does not free it)
    a->SetArray(data->arrays[s].data(), np * specs[s].ncomp, 1);
    image->GetPointData()->AddArray(a);
  }
  vtkNew<vtkUnsignedCharArray> valid;
  valid->SetName("valid");
  valid->SetArray(data->valid.data(), np, 1);
  image->GetPointData()->AddArray(valid);
  if (!data->wall_distance.empty()) {
    vtkNew<vtkFloatArray> wd;
    wd->SetName("wall_distance");
    wd->SetArray(data->wall_distance.data(), np, 1);
    image->GetPointData()->AddArray(wd);
  }

  vtkNew<vtkDoubleArray> nu;
  nu->SetName("kinematic_viscosity");
  nu->InsertNextValue(meta.kinematic_viscosity);
  vtkNew<vtkStringArray> name;
  name->SetName("case_name");
  name->InsertNextValue(meta.case_name);
  vtkNew<vtkDoubleArray> time;
  time->SetName("time");
  time->InsertNextValue(meta.time);
  vtkNew<vtkStringArray> version;
  version->SetName("converter_version");
  version->InsertNextValue(meta.converter_version);
  image->GetFieldData()->AddArray(nu);
  image->GetFieldData()->AddArray(name);
  image->GetFieldData()->AddArray(time);
  image->GetFieldData()->AddArray(version);

  const std::string tmp = temp_name(path);
  vtkNew<vtkXMLImageDataWriter> w;
  w->SetFileName(tmp.c_str());
  w->SetInputData(image);
  w->SetDataModeToAppended();
  w->EncodeAppendedDataOff();
  w->SetCompressorTypeToZLib();
  // level 1: about as small as the default 5 on float fields, several times faster
  w->SetCompressionLevel(1);
  w->SetHeaderTypeToUInt64();
  const int ok = w->Write();
  if (!ok || w->GetErrorCode() != 0) {
    std::remove(tmp.c_str());
    throw Error(Exit::kOutput,
                path + ": cannot write the grid file (VTK writer failed on " + tmp + ")");
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw Error(Exit::kOutput, path + ": cannot rename " + tmp + ": " + ec.message());
  }
}

void write_pvd(const std::string& path, const std::vector<double>& times,
               const std::vector<std::string>& files) {
  const std::string tmp = temp_name(path);
  {
    std::ofstream out(tmp);
    if (!out) throw Error(Exit::kOutput, path + ": cannot create " + tmp);
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n";
    for (std::size_t i = 0; i < times.size(); ++i) {
      // shortest text that reads back as the same double
      char buf[64];
      const auto r = std::to_chars(buf, buf + sizeof(buf), times[i]);
      out << "    <DataSet timestep=\"" << std::string(buf, r.ptr)
          << "\" group=\"\" part=\"0\" file=\"" << files[i] << "\"/>\n";
    }
    out << "  </Collection>\n</VTKFile>\n";
    out.flush();
    if (!out) {
      std::remove(tmp.c_str());
      throw Error(Exit::kOutput, path + ": write to " + tmp + " failed");
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw Error(Exit::kOutput, path + ": cannot rename " + tmp + ": " + ec.message());
  }
}

namespace {

void info_vti(const std::string& path, std::ostream& os) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) fail_input("--info: file '" + path + "' not found");
  vtkNew<vtkXMLImageDataReader> r;
  if (!r->CanReadFile(path.c_str()))
    fail_input("--info: '" + path + "' is not a VTK ImageData file");
  r->SetFileName(path.c_str());
  r->Update();
  if (r->GetErrorCode() != 0) fail_input("--info: cannot read '" + path + "'");
  vtkImageData* im = r->GetOutput();
  int d[3];
  double o[3], h[3];
  im->GetDimensions(d);
  im->GetOrigin(o);
  im->GetSpacing(h);
  const vtkIdType np = im->GetNumberOfPoints();
  os << path << "\n";
  os << "  dimensions  " << d[0] << " x " << d[1] << " x " << d[2] << " = " << np << " points\n";
  os << "  spacing     " << h[0] << " " << h[1] << " " << h[2] << " m\n";
  os << "  bounds      x [" << o[0] << ", " << o[0] + (d[0] - 1) * h[0] << "]  y [" << o[1] << ", "
     << o[1] + (d[1] - 1) * h[1] << "]  z [" << o[2] << ", " << o[2] + (d[2] - 1) * h[2] << "] m\n";
  vtkFieldData* fd = im->GetFieldData();
  for (int i = 0; i < fd->GetNumberOfArrays(); ++i) {
    vtkAbstractArray* a = fd->GetAbstractArray(i);
    if (a == nullptr || a->GetNumberOfValues() == 0) continue;
    os << "  " << std::left << std::setw(20) << a->GetName() << " "
       << a->GetVariantValue(0).ToString() << "\n";
  }
  vtkDataArray* valid = im->GetPointData()->GetArray("valid");
  vtkIdType nvalid = 0;
  if (valid) {
    for (vtkIdType i = 0; i < np; ++i) nvalid += valid->GetTuple1(i) != 0 ? 1 : 0;
    os << "  invalid     " << std::setprecision(4)
       << 100.0 * static_cast<double>(np - nvalid) / static_cast<double>(std::max<vtkIdType>(np, 1))
       << " % of the points (valid = 0)\n";
  } else {
    os << "  (no 'valid' array)\n";
  }
  os << "  field (over valid points)        min           max           mean\n";
  os << std::setprecision(6);
  for (int i = 0; i < im->GetPointData()->GetNumberOfArrays(); ++i) {
    vtkDataArray* a = im->GetPointData()->GetArray(i);
    if (a == nullptr || a == valid) continue;
    const int nc = a->GetNumberOfComponents();
    // vectors: magnitude
    double mn = std::numeric_limits<double>::infinity(), mx = -mn, sum = 0;
    vtkIdType n = 0;
    for (vtkIdType p = 0; p < np; ++p) {
      if (valid && valid->GetTuple1(p) == 0) continue;
      double v = 0;
      if (nc == 1) {
        v = a->GetComponent(p, 0);
      } else {
        for (int k = 0; k < nc; ++k) v += a->GetComponent(p, k) * a->GetComponent(p, k);
        v = std::sqrt(v);
      }
      mn = std::min(mn, v);
      mx = std::max(mx, v);
      sum += v;
      ++n;
    }
    std::string label = std::string(a->GetName()) + (nc > 1 ? " (magnitude)" : "");
    os << "  " << std::left << std::setw(24) << label << std::right << std::setw(14)
       << (n ? mn : NAN) << std::setw(14) << (n ? mx : NAN) << std::setw(14)
       << (n ? sum / static_cast<double>(n) : NAN) << "\n";
  }
}

}  // namespace

void print_info(const std::string& path, std::ostream& os) {
  if (path.size() > 4 && path.substr(path.size() - 4) == ".pvd") {
    std::ifstream in(path);
    if (!in) fail_input("--info: file '" + path + "' not found");
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    const std::regex ds(R"re(<DataSet[^>]*timestep="([^"]*)"[^>]*file="([^"]*)")re");
    std::vector<std::pair<std::string, std::string>> sets;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), ds); it != std::sregex_iterator();
         ++it) {
      sets.emplace_back((*it)[1], (*it)[2]);
    }
    if (sets.empty()) fail_input("--info: '" + path + "' holds no DataSet entries");
    os << path << ": collection of " << sets.size() << " grids\n  times (s):";
    for (auto& s : sets) os << " " << s.first;
    os << "\n";
    const fs::path dir = fs::path(path).parent_path();
    for (auto& s : sets) {
      os << "\n[time " << s.first << "] ";
      info_vti((dir / s.second).string(), os);
    }
    return;
  }
  info_vti(path, os);
}

}  // namespace foam2grid
