#include "srp/execution/RandomScene.h"

#include <gtest/gtest.h>

#include "srp/core/Error.h"
#include "srp/execution/CellDescription.h"

using namespace srp::execution;

TEST(RandomScene, SeededPartsInsideTheBoxAndApart) {
  const auto base = CellDescription::loadScene();
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    const CellDescription a = randomizeCell(base, "blue box", seed);
    const CellDescription b = randomizeCell(base, "blue box", seed);
    const CellObject& box = *a.find("blue box");
    std::vector<const CellObject*> parts;
    for (const auto& o : a.objects)
      if (o.kind == CellObjectKind::Part) {
        EXPECT_TRUE(isInside(o, box)) << o.name << " seed " << seed;
        EXPECT_NEAR(o.X_world_object.translation().z(), box.wallThickness_m, 1e-12);
        EXPECT_TRUE(o.X_world_object.isApprox(b.find(o.name)->X_world_object)) << "not deterministic";
        parts.push_back(&o);
      }
    for (std::size_t i = 0; i < parts.size(); ++i)
      for (std::size_t j = i + 1; j < parts.size(); ++j)
        EXPECT_GT((parts[i]->X_world_object.translation() - parts[j]->X_world_object.translation()).norm(), 0.04);
  }
  EXPECT_THROW(randomizeCell(base, "red box", 1), srp::core::InvalidInputError);
}
