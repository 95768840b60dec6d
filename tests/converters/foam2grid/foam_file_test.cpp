// Reading OpenFOAM files (converters/foam2grid/foam_file.cpp): ascii and binary lists, the
// list shorthands OpenFOAM writes, dictionaries, and errors that name file and line.
#include "foam_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "error.h"

namespace fs = std::filesystem;
using namespace foam2grid;

namespace {

std::string write_file(const std::string& name, const std::string& text) {
  const fs::path dir = fs::path(LRIGID_BINARY_DIR) / "tests/converters/work/foam_file";
  fs::create_directories(dir);
  const std::string path = (dir / name).string();
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string header(const std::string& cls, bool binary) {
  return std::string("/* comment */\nFoamFile\n{\n    version 2.0;\n    format ") +
         (binary ? "binary" : "ascii") + ";\n    class " + cls +
         ";\n    arch \"LSB;label=32;scalar=64\";\n    object x;\n}\n// line comment\n\n";
}

}  // namespace

TEST(FoamFile, AsciiVectorListAndFaceList) {
  FoamFile pts(write_file(
      "points", header("vectorField", false) + "3\n(\n(0 0 0)\n(1 -2.5e-1 3)\n(1e3 2 nan)\n)\n"));
  std::vector<double> v;
  Cursor(pts, pts.body()).scalar_list(3, &v);
  ASSERT_EQ(v.size(), 9u);
  EXPECT_DOUBLE_EQ(v[4], -0.25);
  EXPECT_DOUBLE_EQ(v[6], 1000.0);
  EXPECT_TRUE(std::isnan(v[8]));

  FoamFile faces(
      write_file("faces", header("faceList", false) + "2\n(\n4(0 1 2 3)\n3(3 2 4)\n)\n"));
  std::vector<std::int64_t> off, lab;
  Cursor(faces, faces.body()).face_list(&off, &lab);
  EXPECT_EQ(off, (std::vector<std::int64_t>{0, 4, 7}));
  EXPECT_EQ(lab, (std::vector<std::int64_t>{0, 1, 2, 3, 3, 2, 4}));
}

TEST(FoamFile, BinaryCompactFacesAndScalarList) {
  std::string text = header("faceCompactList", true) + "3\n(";
  const std::int32_t offsets[3] = {0, 4, 7};
  text.append(reinterpret_cast<const char*>(offsets), sizeof(offsets));
  text += ")\n7\n(";
  const std::int32_t labels[7] = {0, 1, 2, 3, 41, 40, 9};  // 41 = ')' and 40 = '(' as bytes
  text.append(reinterpret_cast<const char*>(labels), sizeof(labels));
  text += ")\n";
  FoamFile faces(write_file("faces_bin", text));
  EXPECT_TRUE(faces.format().binary);
  std::vector<std::int64_t> off, lab;
  Cursor(faces, faces.body()).face_list(&off, &lab);
  EXPECT_EQ(off, (std::vector<std::int64_t>{0, 4, 7}));
  EXPECT_EQ(lab, (std::vector<std::int64_t>{0, 1, 2, 3, 41, 40, 9}));

  // a binary field: the dictionary parser must skip raw bytes holding ';' and '}'
  std::string field = header("volScalarField", true) +
                      "dimensions [0 2 -2 0 0 0 0];\ninternalField nonuniform List<scalar> 2\n(";
  const double vals[2] = {1.5, 0};
  char raw[16];
  std::memcpy(raw, vals, 16);
  raw[9] = ';';
  raw[10] = '}';
  field.append(raw, 16);
  field += ");\nboundaryField\n{\n    wall\n    {\n        type zeroGradient;\n    }\n}\n";
  FoamFile f(write_file("k_bin", field));
  Cursor c(f, f.body());
  const std::vector<DictEntry> top = c.dict(true);
  const DictEntry* in = find_entry(top, "internalField");
  ASSERT_NE(in, nullptr);
  const DictEntry* bf = find_entry(top, "boundaryField");
  ASSERT_NE(bf, nullptr);
  EXPECT_TRUE(bf->is_dict);
  ASSERT_NE(find_entry(bf->sub, "wall"), nullptr);
  std::vector<double> out;
  Cursor(f, in->begin).field_value(1, 2, &out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_DOUBLE_EQ(out[0], 1.5);
  std::memcpy(raw, vals, 16);
  raw[9] = ';';
  raw[10] = '}';
  double second;
  std::memcpy(&second, raw + 8, 8);
  EXPECT_EQ(std::memcmp(&out[1], &second, 8), 0);
}

TEST(FoamFile, UniformShorthandsAndEmptyNonuniform) {
  FoamFile f(write_file("U", header("volVectorField", false) + "internalField uniform (1 2 3);\n"
                                                               "a nonuniform 0();\n"
                                                               "b 3{0.5};\n"));
  Cursor c(f, f.body());
  const std::vector<DictEntry> top = c.dict(true);
  std::vector<double> v;
  Cursor(f, find_entry(top, "internalField")->begin).field_value(3, 2, &v);
  EXPECT_EQ(v, (std::vector<double>{1, 2, 3, 1, 2, 3}));
  Cursor(f, find_entry(top, "a")->begin).field_value(3, 0, &v);
  EXPECT_TRUE(v.empty());
  Cursor(f, find_entry(top, "b")->begin).scalar_list(1, &v);
  EXPECT_EQ(v, (std::vector<double>{0.5, 0.5, 0.5}));
}

TEST(FoamFile, ErrorsNameFileAndLine) {
  const std::string path = write_file("bad", header("labelList", false) + "3\n(\n0\n1\n)\n");
  FoamFile f(path);
  std::vector<std::int64_t> l;
  try {
    Cursor(f, f.body()).label_list(&l);
    FAIL() << "a list of 2 announced as 3 was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), Exit::kBadInput);
    const std::string m = e.what();
    EXPECT_NE(m.find(path), std::string::npos) << m;
    EXPECT_NE(m.find("line 16"), std::string::npos) << m;  // the closing ")"
    EXPECT_NE(m.find("says 3 elements but holds 2"), std::string::npos) << m;
  }
  try {
    FoamFile missing(path + "_none");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), Exit::kBadInput);
    EXPECT_NE(std::string(e.what()).find("file not found"), std::string::npos);
  }
}
