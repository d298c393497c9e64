// A class seen without a CAD file travels with a scene file (and a task model)
// as its full definition: it round-trips exactly, and a bad number is refused
// naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "srp/core/Error.h"
#include "srp/core/ObjectClassJson.h"
#include "srp/core/Scene.h"

using namespace srp::core;

namespace {
constexpr double kExact_m = 0.0;  // JSON keeps doubles exactly

ObjectClass observedToy() {
  ObjectClass c;
  c.name = "toy";
  c.classId = 100;
  c.noun = "toy";
  c.colourName = "blue";
  c.kind = ObjectKind::Part;
  c.shape = "hull";
  c.rgb = Eigen::Vector3d(0.1, 0.2, 0.7);
  c.dimensions_m = Eigen::Vector3d(0.12, 0.08, 0.06);
  c.mass_kg = 0.09;
  c.footprint_object = {{-0.06, -0.04}, {0.06, -0.03}, {0.05, 0.04}, {-0.05, 0.04}};
  c.observed = true;
  return c;
}

std::string errorOf(const nlohmann::json& j) {
  try {
    objectClassFromJson(j, "scene.json: observed_classes[0]");
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted: " << j.dump();
  return "";
}
}  // namespace

TEST(ObjectClassJson, AnObservedHullRoundTripsExactly) {
  const ObjectClass c = observedToy();
  const ObjectClass back = objectClassFromJson(objectClassToJson(c), "test");
  EXPECT_EQ(back.name, c.name);
  EXPECT_EQ(back.classId, c.classId);
  EXPECT_EQ(back.shape, "hull");
  EXPECT_TRUE(back.observed);
  EXPECT_TRUE(back.hasColour);
  EXPECT_EQ(back.colourName, "blue");
  EXPECT_LE((back.dimensions_m - c.dimensions_m).norm(), kExact_m);
  ASSERT_EQ(back.footprint_object.size(), c.footprint_object.size());
  for (std::size_t i = 0; i < c.footprint_object.size(); ++i)
    EXPECT_LE((back.footprint_object[i] - c.footprint_object[i]).norm(), kExact_m);
  EXPECT_EQ(objectClassToJson(back), objectClassToJson(c));
}

TEST(ObjectClassJson, BadNumbersAreRefusedNamingTheField) {
  const nlohmann::json good = objectClassToJson(observedToy());
  auto bad = good;
  bad["dimensions_m"][1] = std::numeric_limits<double>::infinity();
  EXPECT_NE(errorOf(bad).find("dimensions_m"), std::string::npos);
  bad = good;
  bad["dimensions_m"] = {0.1, 0.08, 0.0};
  EXPECT_NE(errorOf(bad).find("dimensions_m"), std::string::npos);
  bad = good;
  bad["mass_kg"] = -1.0;
  EXPECT_NE(errorOf(bad).find("mass_kg"), std::string::npos);
  bad = good;
  bad["rgb"] = {0.1, 1.5, 0.2};
  EXPECT_NE(errorOf(bad).find("rgb"), std::string::npos);
  bad = good;
  bad["footprint_m"][2] = {0.5, 0.0};  // outside the class' 0.12 x 0.08 extent
  EXPECT_NE(errorOf(bad).find("footprint_m"), std::string::npos);
  bad = good;
  bad["footprint_m"] = {{0.0, 0.0}, {0.01, 0.0}};
  EXPECT_NE(errorOf(bad).find("footprint_m"), std::string::npos);
  bad = good;
  bad["kind"] = "container";  // a container needs walls
  EXPECT_NE(errorOf(bad).find("wall_thickness_m"), std::string::npos);
  bad = good;
  bad.erase("shape");
  EXPECT_NE(errorOf(bad).find("shape"), std::string::npos);
}

TEST(Scene, CarriesObservedClassesAndValidatesObjectsOfThem) {
  ObjectClass cuboid;
  cuboid.name = cuboid.noun = "cuboid";
  cuboid.classId = 3;
  cuboid.shape = "cuboid";
  cuboid.dimensions_m = {0.05, 0.03, 0.03};
  cuboid.mass_kg = 0.04;
  const ObjectCatalogue kb({cuboid});
  Scene s;
  s.name = "test";
  SceneObject part;
  part.id = part.className = "cuboid";
  SceneObject toy;
  toy.id = "toy";
  toy.className = "toy";
  toy.X_world_object.translation() = Eigen::Vector3d(0.1, 0.2, 0.0);
  s.objects = {part, toy};
  EXPECT_THROW(s.validate(kb), InvalidInputError) << "a class neither catalogue nor scene knows";
  s.observedClasses.push_back(observedToy());
  s.validate(kb);
  s.intrinsics = {500.0, 500.0, 319.5, 239.5, 640, 480};
  const Scene back = Scene::fromJson(s.toJson(), "roundtrip", ".");
  ASSERT_EQ(back.observedClasses.size(), 1u);
  EXPECT_EQ(objectClassToJson(back.observedClasses[0]), objectClassToJson(s.observedClasses[0]));
  const ObjectCatalogue merged = back.withObservedClasses(kb);
  EXPECT_EQ(merged.classes().size(), kb.classes().size() + 1);
  EXPECT_TRUE(merged.at("toy").observed);
  // An observed class may not take a catalogue class' name or id.
  Scene clash = s;
  clash.observedClasses[0].classId = 3;
  try {
    clash.withObservedClasses(kb);
    ADD_FAILURE() << "an observed class with the cuboid's class_id was accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("clashes with the catalogue's class 'cuboid'"), std::string::npos) << e.what();
  }
}
