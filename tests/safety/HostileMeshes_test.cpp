// Meshes that cannot crash us: NaN / Inf / huge / millimetre / flat / empty
// meshes, headers that declare more than the file holds, and random bytes, in
// every format a user may give, through `srp kb add` (kb::addMeshClass), the
// catalogue loader and the pose fitter's grid. Each is refused with srp's own
// error or accepted as a part of 1 mm - 2 m with a volume; nothing crashes,
// nothing allocates what the file does not hold (ASan/UBSan: make test-sanitize).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "ScratchFolder.h"
#include "srp/core/Error.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/kb/MeshValidator.h"
#include "srp/kb/ShapeMeshes.h"
#include "srp/perception/ObjectModel.h"
#include "srp/perception/ObjectPoseFitter.h"

namespace fs = std::filesystem;

namespace {

enum class Expect { Refused, Accepted, Either };

struct Case {
  std::string name;
  std::string bytes;
  Expect expect = Expect::Refused;  ///< Either: a mutation that may leave a valid part (then it must be one)
};

std::string asciiStl(const std::vector<std::array<double, 9>>& triangles) {
  std::ostringstream o;
  o.precision(17);
  o << "solid x\n";
  for (const auto& t : triangles) {
    o << "facet normal 0 0 0\nouter loop\n";
    for (int v = 0; v < 3; ++v) o << "vertex " << t[3 * v] << " " << t[3 * v + 1] << " " << t[3 * v + 2] << "\n";
    o << "endloop\nendfacet\n";
  }
  o << "endsolid x\n";
  return o.str();
}

std::string binaryStl(const srp::kb::TriangleMesh& mesh, std::uint32_t declared, double scale, float poison = 0.f,
                      bool poisonAll = false) {
  std::string b(80, ' ');
  if (declared == 0) declared = static_cast<std::uint32_t>(mesh.size());  // 0: the true count
  b.append(reinterpret_cast<const char*>(&declared), 4);
  for (std::size_t i = 0; i < mesh.size(); ++i) {
    float r[12] = {};
    for (int v = 0; v < 3; ++v)
      for (int k = 0; k < 3; ++k) r[3 + 3 * v + k] = static_cast<float>(mesh.triangles()[i][v][k] * scale);
    if (poison != 0.f && (poisonAll || i == 3)) r[4] = poison;
    b.append(reinterpret_cast<const char*>(r), sizeof(r));
    b.append(2, '\0');
  }
  return b;
}

std::string objBox(double side, const std::string& override = "") {
  std::ostringstream o;
  o.precision(17);
  const double h = side / 2;
  for (int i = 0; i < 8; ++i)
    o << "v " << ((i & 1) ? h : -h) << " " << ((i & 2) ? h : -h) << " " << ((i & 4) ? side : 0.0) << "\n";
  o << override;
  o << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  return o.str();
}

std::vector<Case> meshCases() {
  std::vector<Case> cases;
  const auto box = srp::kb::makeBoxMesh({-0.02, -0.02, 0}, {0.02, 0.02, 0.04});
  cases.push_back({"good.stl", binaryStl(box, 0, 1.0), Expect::Accepted});
  cases.push_back({"good.obj", objBox(0.05), Expect::Accepted});
  cases.push_back({"nan.stl", binaryStl(box, 0, 1.0, std::nanf(""))});
  cases.push_back({"inf.stl", binaryStl(box, 0, 1.0, INFINITY)});
  cases.push_back({"minus_inf.stl", binaryStl(box, 0, 1.0, -INFINITY)});
  cases.push_back({"all_nan.stl", binaryStl(box, 0, 1.0, std::nanf(""), true)});
  cases.push_back({"huge_float.stl", binaryStl(box, 0, 1.0, 3e38f)});
  cases.push_back({"wide_3_19m.stl", binaryStl(box, 0, 3.19 / 0.04)});
  cases.push_back({"one_km.stl", binaryStl(box, 0, 1000.0 / 0.04)});
  cases.push_back({"millimetres_30.stl", binaryStl(box, 0, 30.0 / 0.04)});
  cases.push_back({"tiny_0_1mm.stl", binaryStl(box, 0, 1e-4 / 0.04)});
  cases.push_back({"declares_2e9.stl", binaryStl(box, 2000000000u, 1.0)});
  cases.push_back({"declares_max.stl", binaryStl(box, 0xFFFFFFFFu, 1.0)});
  cases.push_back({"truncated.stl", binaryStl(box, 0, 1.0).substr(0, 84 + 50 * 5)});
  cases.push_back({"header_only.stl", binaryStl(box, 0, 1.0).substr(0, 84)});
  cases.push_back({"empty.stl", ""});
  cases.push_back({"one_triangle.stl", asciiStl({{0, 0, 0, 0.05, 0, 0, 0, 0.05, 0}})});
  cases.push_back({"flat_square.stl", asciiStl({{0, 0, 0, 0.05, 0, 0, 0.05, 0.05, 0}, {0, 0, 0, 0.05, 0.05, 0, 0, 0.05, 0}})});
  cases.push_back({"degenerate_point.stl", asciiStl({{0, 0, 0, 0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 0, 0, 0, 0}})});
  cases.push_back({"ascii_nan.stl", asciiStl({{0, 0, 0, NAN, 0, 0, 0, 0.05, 0}})});
  cases.push_back({"ascii_1e308.stl", asciiStl({{0, 0, 0, 1e308, 0, 0, 0, 0.05, 1e308}})});
  cases.push_back({"obj_nan.obj", objBox(0.05, "v nan nan nan\nf 1 2 9\n")});
  cases.push_back({"obj_inf.obj", objBox(0.05, "v inf 0 0\nf 1 2 9\n")});
  cases.push_back({"obj_bad_index.obj", objBox(0.05, "f 1 2 99999999\n")});
  cases.push_back({"obj_negative_index.obj", objBox(0.05, "f -1 -2 -99999999\n")});
  cases.push_back({"obj_millimetres.obj", objBox(50.0)});
  cases.push_back({"ply_2e9_vertices.ply",
                   "ply\nformat ascii 1.0\nelement vertex 2000000000\nproperty float x\nproperty float y\nproperty "
                   "float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"});
  cases.push_back({"ply_binary_2e9_faces.ply",
                   std::string("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float "
                               "y\nproperty float z\nelement face 2000000000\nproperty list uchar int "
                               "vertex_indices\nend_header\n") + std::string(36 + 13, '\0')});
  cases.push_back({"ply_count_overflow.ply",
                   "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\nproperty float x\nend_header\n"});
  cases.push_back({"ply_no_end_header.ply", "ply\nformat ascii 1.0\n" + std::string(70000, 'c')});
  cases.push_back({"dae_count_bomb.dae",
                   "<?xml version=\"1.0\"?><COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" "
                   "version=\"1.4.1\"><library_geometries><geometry id=\"g\"><mesh><source id=\"p\"><float_array "
                   "id=\"a\" count=\"2000000000\">0 0 0</float_array></source></mesh></geometry></library_geometries>"
                   "</COLLADA>"});
  cases.push_back({"gltf_accessor_bomb.gltf",
                   R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
                      "bufferViews": [{"buffer": 0, "byteLength": 36}],
                      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 2000000000, "type": "VEC3"}],
                      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}],
                      "scenes": [{"nodes": [0]}], "scene": 0})"});
  // Random bytes and random mutations of a good binary STL.
  std::mt19937 rng(35);
  const std::string good = binaryStl(box, 0, 1.0);
  for (int i = 0; i < 40; ++i) {
    std::string m = good;
    for (int k = 0; k < 1 + static_cast<int>(rng() % 8); ++k) m[rng() % m.size()] = static_cast<char>(rng());
    cases.push_back({"mutated_" + std::to_string(i) + ".stl", m, Expect::Either});
    std::string noise(rng() % 2000, '\0');
    for (char& c : noise) c = static_cast<char>(rng());
    const char* ext[] = {".stl", ".obj", ".ply", ".dae", ".glb"};
    cases.push_back({"noise_" + std::to_string(i) + ext[i % 5], (i % 5 == 2 ? "ply\n" : "") + noise});
  }
  return cases;
}

}  // namespace

TEST(HostileMeshes, EveryMeshIsRefusedOrAValidPart) {
  const srp::safety::ScratchFolder scratch("meshes");
  const fs::path& dir = scratch.path;
  int accepted = 0, refused = 0, crashedOrForeign = 0, fitted = 0;
  for (const Case& c : meshCases()) {
    const fs::path file = dir / c.name;
    std::ofstream(file, std::ios::binary) << c.bytes;
    const std::string catalogue = (dir / ("catalogue_" + c.name + ".json")).string();
    srp::kb::MeshClassEntry e;
    e.name = "part";
    e.meshPath = file.string();
    try {
      const srp::core::ObjectClass cls = srp::kb::addMeshClass(catalogue, e);
      ++accepted;
      EXPECT_NE(c.expect, Expect::Refused) << c.name << " accepted: " << cls.dimensions_m.transpose();
      EXPECT_TRUE(cls.dimensions_m.allFinite() && cls.dimensions_m.maxCoeff() <= 2.0 && cls.dimensions_m.maxCoeff() >= 1e-3)
          << c.name;
      EXPECT_TRUE(std::isfinite(cls.mass_kg) && cls.mass_kg > 0.0) << c.name;
      // The catalogue reads it back, and the pose fitter builds its grid on it.
      const auto loaded = srp::kb::loadCatalogue(catalogue);
      const auto model = srp::perception::ObjectModel::fromCatalogue(loaded.at("part"));
      const srp::perception::ObjectPoseFitter fitter(model);
      ++fitted;
    } catch (const srp::core::Error& err) {
      ++refused;
      EXPECT_NE(c.expect, Expect::Accepted) << c.name << " refused: " << err.what();
      EXPECT_FALSE(fs::exists(catalogue)) << c.name << ": a refused part left a catalogue";
    } catch (const std::exception& err) {
      ++crashedOrForeign;
      ADD_FAILURE() << c.name << ": not an srp error: " << err.what();
    }
  }
  std::printf("[ sweep ] meshes: %d cases, %d accepted (and fitted: %d), %d refused, %d foreign errors\n",
              accepted + refused + crashedOrForeign, accepted, fitted, refused, crashedOrForeign);
  EXPECT_EQ(crashedOrForeign, 0);
}

// The units of a file in millimetres make it a valid part; a flat part is
// accepted when declared flat; a part that looks like millimetres warns.
TEST(HostileMeshes, UnitsScaleAndFlatPartsAreExplicit) {
  const srp::safety::ScratchFolder scratch("units");
  const fs::path& dir = scratch.path;
  const auto box = srp::kb::makeBoxMesh({-0.02, -0.02, 0}, {0.02, 0.02, 0.04});
  std::ofstream(dir / "mm.stl", std::ios::binary) << binaryStl(box, 0, 1000.0);  // 40 units = 40 mm
  std::ofstream(dir / "flat.stl") << asciiStl({{0, 0, 0, 0.05, 0, 0, 0.05, 0.05, 0}, {0, 0, 0, 0.05, 0.05, 0, 0, 0.05, 0}});
  std::ofstream(dir / "big.stl", std::ios::binary) << binaryStl(box, 0, 0.8 / 0.04);  // 0.8 m
  srp::kb::MeshClassEntry e;
  e.name = "mm part";
  e.meshPath = (dir / "mm.stl").string();
  const std::string catalogue = (dir / "parts.json").string();
  EXPECT_THROW(srp::kb::addMeshClass(catalogue, e), srp::core::InvalidInputError);
  e.scale = srp::kb::unitScale("mm");
  const auto mm = srp::kb::addMeshClass(catalogue, e);
  constexpr double kSizeTol_m = 1e-6;
  EXPECT_NEAR(mm.dimensions_m.x(), 0.04, kSizeTol_m);
  EXPECT_NEAR(srp::kb::loadCatalogue(catalogue).at("mm part").dimensions_m.z(), 0.04, kSizeTol_m);
  e = {};
  e.name = "label";
  e.meshPath = (dir / "flat.stl").string();
  EXPECT_THROW(srp::kb::addMeshClass(catalogue, e), srp::core::InvalidInputError);
  e.flat = true;
  const auto flat = srp::kb::addMeshClass(catalogue, e);
  EXPECT_GT(flat.mass_kg, 0.0);
  EXPECT_GE(flat.dimensions_m.minCoeff(), 1e-3);
  e = {};
  e.name = "big";
  e.meshPath = (dir / "big.stl").string();
  std::vector<std::string> warnings;
  srp::kb::addMeshClass(catalogue, e, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("--units mm"), std::string::npos) << warnings[0];
  // A mesh that is the catalogue itself is refused before anything is written.
  e = {};
  e.name = "self";
  e.meshPath = catalogue;
  EXPECT_THROW(srp::kb::addMeshClass(catalogue, e), srp::core::InvalidInputError);
  EXPECT_EQ(srp::kb::loadCatalogue(catalogue).classes().size(), 3u);
}

// The fitter's grid: a 2 m part at the default 2 mm cells would need 1e9 cells;
// the bound coarsens the cells instead.
TEST(HostileMeshes, FitterGridIsBounded) {
  srp::perception::ObjectModel model;
  model.name = "two metre part";
  for (int i = 0; i < 200; ++i) {
    const double s = i / 199.0;
    model.surface.push_back({Eigen::Vector3d(2.0 * s, 2.0 * (1 - s), 2.0 * s * s), Eigen::Vector3d::UnitZ()});
  }
  srp::perception::ObjectPoseFitter::Options o;
  o.maxGridCells = 2'000'000;
  const srp::perception::ObjectPoseFitter fitter(model, o);  // 4 bytes a cell: at most 8 MB
  model.surface[7].p_m.x() = NAN;
  EXPECT_THROW(srp::perception::ObjectPoseFitter(model, o), srp::core::InvalidInputError);
}
