// A scene checked against the bundled catalogue, read by the one catalogue loader.
#include <gtest/gtest.h>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Scene.h"
#include "srp/kb/KnowledgeBase.h"

using namespace srp::core;
using srp::kb::loadCatalogue;

namespace {
constexpr double kExact_m = 1e-12;
const std::string kScenePath = std::string(SRP_SIM_DIR) + "/scenes/default.json";

std::string expectInvalid(const nlohmann::json& j) {
  try {
    Scene::fromJson(j, "bad.json", ".").validate(loadCatalogue(ObjectCatalogue::defaultPath()));
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << j.dump();
  return "";
}
}  // namespace

TEST(ObjectCatalogue, BundledCatalogueHasTheThesisClasses) {
  const auto cat = loadCatalogue(ObjectCatalogue::defaultPath());
  ASSERT_EQ(cat.classes().size(), 6u);
  EXPECT_EQ(cat.at("gray box").classId, 0);  // Appendix C, table C.6
  EXPECT_EQ(cat.at("cuboid").classId, 3);
  EXPECT_EQ(cat.at("star").classId, 5);
  EXPECT_EQ(cat.ground("box", "blue")->name, "blue box");
  EXPECT_EQ(cat.ground("octagon")->classId, 4);
  EXPECT_EQ(cat.ground("box"), nullptr);  // two boxes: the colour is needed
  EXPECT_EQ(cat.ground("box", "green"), nullptr);
  EXPECT_THROW(cat.at("cylinder"), InvalidInputError);
  EXPECT_NE(cat.at("cuboid").meshPath.find("datasets/kb/meshes/cuboid.stl"), std::string::npos);
}

TEST(Scene, DefaultSceneLoadsValidatesAndRoundTrips) {
  const Scene s = Scene::load(kScenePath);
  s.validate(loadCatalogue(s.cataloguePath));
  EXPECT_EQ(s.objects.size(), 6u);
  EXPECT_EQ(s.intrinsics.width_px, 640);
  // Camera looks straight down: its z axis is world -z.
  EXPECT_NEAR((s.X_world_camera.linear().col(2) - Eigen::Vector3d(0, 0, -1)).norm(), 0.0, 1e-12);
  // X_base_camera is derived from the two world poses.
  const Pose3 X_world_camera_again = s.X_world_base * s.X_base_camera();
  EXPECT_LT((X_world_camera_again.matrix() - s.X_world_camera.matrix()).norm(), kExact_m);
  const Scene back = Scene::fromJson(s.toJson(), "roundtrip", "/some/other/folder");
  EXPECT_EQ(back.cataloguePath, s.cataloguePath);  // written elsewhere, the catalogue is still found
  ASSERT_EQ(back.objects.size(), s.objects.size());
  EXPECT_LT((back.objects[3].X_world_object.matrix() - s.objects[3].X_world_object.matrix()).norm(), 1e-12);
  EXPECT_EQ(back.intrinsics, s.intrinsics);
}

TEST(Scene, BadScenesNameTheField) {
  const nlohmann::json good = readJsonFile(kScenePath);
  nlohmann::json j = good;
  j["camera"].erase("X_world_camera");
  EXPECT_NE(expectInvalid(j).find("X_world_camera"), std::string::npos);
  j = good;
  j["objects"][2]["class"] = "cylinder";
  EXPECT_NE(expectInvalid(j).find("unknown class 'cylinder'"), std::string::npos);
  j = good;
  j["objects"][2]["X_world_object"]["translation"] = {0.9, 0.0, 0.0};
  EXPECT_NE(expectInvalid(j).find("outside the table"), std::string::npos);
  j = good;
  j.erase("table");
  EXPECT_NE(expectInvalid(j).find("'table'"), std::string::npos);
  j = good;
  j["camera"]["intrinsics"]["fx"] = -1;
  EXPECT_NE(expectInvalid(j).find("focal"), std::string::npos);
  // Names that would reach a robot program's comments: refused where the scene is read.
  for (const char* field : {"id", "color"}) {
    j = good;
    j["objects"][2][field] = "cuboid\r\n---\npoints: []";
    const std::string message = expectInvalid(j);
    EXPECT_NE(message.find(std::string("field '") + field + "'"), std::string::npos) << message;
    EXPECT_EQ(message.find('\r'), std::string::npos) << "the message itself is printable";
  }
}

TEST(Scene, InstancesOfOneClassCarryTheirOwnColour) {
  const auto cat = loadCatalogue(ObjectCatalogue::defaultPath());
  const Scene scene = Scene::load(std::string(SRP_SIM_DIR) + "/scenes/two_cuboids_two_stars.json");
  scene.validate(cat);
  const SceneObject* red = scene.findObject("cuboid_red");
  const SceneObject* blue = scene.findObject("cuboid_blue");
  ASSERT_TRUE(red && blue);
  EXPECT_EQ(red->className, blue->className);
  EXPECT_EQ(instanceColour(*red, cat.at("cuboid")), "red");
  EXPECT_EQ(instanceColour(*blue, cat.at("cuboid")), "blue");
  EXPECT_TRUE(instanceRgb(*blue, cat.at("cuboid")).isApprox(*rgbOfColourName("blue")));
  EXPECT_GT((instanceRgb(*blue, cat.at("cuboid")) - instanceRgb(*red, cat.at("cuboid"))).norm(), 0.5);
  // Without an override an instance has its class' colour.
  SceneObject plain{"c", "cuboid", Pose3::Identity(), "", std::nullopt};
  EXPECT_TRUE(instanceRgb(plain, cat.at("cuboid")).isApprox(cat.at("cuboid").rgb));
  EXPECT_EQ(nearestColourName(cat.at("cuboid").rgb), "red");
  EXPECT_EQ(nearestColourName(cat.at("star").rgb), "yellow");
  EXPECT_EQ(nearestColourName(Eigen::Vector3d(0.5, 0.5, 0.0), 0.05), "");
  // An explicit rgb wins over the colour word, and both round-trip.
  Scene copy = scene;
  copy.objects[2].rgb = Eigen::Vector3d(0.1, 0.2, 0.3);
  const Scene back = Scene::fromJson(copy.toJson(), "copy", ".");
  EXPECT_EQ(back.objects[2].colour, copy.objects[2].colour);
  ASSERT_TRUE(back.objects[2].rgb.has_value());
  EXPECT_TRUE(back.objects[2].rgb->isApprox(Eigen::Vector3d(0.1, 0.2, 0.3)));
}

TEST(Scene, UnknownColourWordWithoutRgbIsRefusedNamingTheField) {
  nlohmann::json j = readJsonFile(kScenePath);
  j["objects"][2]["color"] = "chartreuse-ish";
  const std::string message = expectInvalid(j);
  EXPECT_NE(message.find("'color'"), std::string::npos) << message;
  EXPECT_NE(message.find("rgb"), std::string::npos) << message;
  j["objects"][2]["rgb"] = {0.5, 1.0, 0.0};
  Scene::fromJson(j, "ok.json", ".").validate(loadCatalogue(ObjectCatalogue::defaultPath()));
}
