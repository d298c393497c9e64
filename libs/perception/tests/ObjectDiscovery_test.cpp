// ObjectDiscovery against known geometry (BoxWorld.h, a ray-cast table scene):
// a blue part the hand carries from the table into a grey bin. The part's and
// the bin's models and places are compared with the boxes they were rendered
// from; the colour word and a demonstration where nothing moves are refused.
#include "srp/perception/ObjectDiscovery.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "BoxWorld.h"
#include "srp/core/Error.h"

namespace srp::perception {
namespace {

using testing::BoxWorld;

// Stride 2 at about 1 m: the feet of the sampled points are ~7 mm apart.
constexpr double kSize_m = 0.015;   // a model's footprint sides and height against the rendered box
constexpr double kPlace_m = 0.015;  // a place (footprint centre) against the rendered one (the bin's walls hide the part's foot)

const Eigen::Vector3d kPartSize_m{0.10, 0.06, 0.14};
const Eigen::Vector3d kBinSize_m{0.30, 0.22, 0.09};
const Eigen::Vector2d kStart_m{-0.25, 0.05}, kBin_m{0.20, 0.10};
constexpr double kBinWall_m = 0.012;
constexpr int kFrames = 40;
const cv::Vec3b kBlue{200, 90, 30}, kGrey{128, 128, 128};

/// The demonstration: frames 0-11 the part stands at kStart (the hand comes
/// from frame 6 and is above it from frame 9), 12-21 it is carried (lifted
/// 0.2 m, along a line, lowered into the bin), 22-39 it stands in the bin (the
/// hand leaves after frame 27). The palm is 0.13 m above the part's top while
/// it holds it (no hand mask: the points within 12 cm of the palm are the hand).
/// `moves` false: the hand comes and goes, the part stays.
struct Demo {
  std::vector<rawlog::RgbdFrame> frames;
  std::vector<std::optional<Eigen::Vector3d>> palm_table;
  core::Pose3 X_table_camera = testing::lookAt({0.0, -0.55, 0.9}, {0.0, 0.1, 0.0});  // a head camera, 54 deg down
};

Demo makeDemo(bool moves) {
  Demo d;
  BoxWorld world;
  const auto bin = testing::openBox({kBin_m.x(), kBin_m.y(), 0.0}, kBinSize_m, kBinWall_m, kGrey);
  for (int i = 0; i < kFrames; ++i) {
    Eigen::Vector3d bottom(kStart_m.x(), kStart_m.y(), 0.0);
    if (moves && i >= 12 && i <= 21) {
      const double s = (i - 11) / 11.0;  // 0 at the start, 1 in the bin
      const double along = std::min(1.0, 1.3 * s);  // over the bin before it is lowered into it
      bottom.head<2>() = (1 - along) * kStart_m + along * kBin_m;
      bottom.z() = kBinWall_m + 0.2 * std::sin(M_PI * s);
    } else if (moves && i > 21) {
      bottom = Eigen::Vector3d(kBin_m.x(), kBin_m.y(), kBinWall_m);
    }
    world.boxes = bin;
    world.boxes.push_back(testing::solidBox(bottom, kPartSize_m, kBlue));
    d.frames.push_back(world.render(d.X_table_camera, i, i / 10.0));
    const Eigen::Vector3d top = bottom + Eigen::Vector3d(0, 0, kPartSize_m.z() + 0.13);
    std::optional<Eigen::Vector3d> palm;
    if (i >= 6 && i < 9) palm = top + Eigen::Vector3d(0.3 - 0.1 * (i - 6), -0.1, 0.1);
    else if (i >= 9 && i <= 27) palm = top;
    d.palm_table.push_back(palm);
  }
  return d;
}

std::vector<UnknownObject> toyAndBin(std::optional<std::string> colour = std::nullopt) {
  UnknownObject toy;
  toy.name = toy.noun = "toy";
  toy.colour = colour;
  UnknownObject bin;
  bin.name = bin.noun = "bin";
  bin.role = UnknownObject::Role::ReleasePlace;
  bin.of = "toy";
  return {toy, bin};
}

ObjectDiscovery::Result discover(const Demo& d, std::vector<UnknownObject> objects) {
  ObjectDiscovery discovery(std::move(objects));
  const core::Pose3 X_camera_table = d.X_table_camera.inverse();
  for (std::size_t i = 0; i < d.frames.size(); ++i) {
    const auto& palm = d.palm_table[i];
    discovery.add(d.frames[i], X_camera_table,
                  palm ? std::optional<Eigen::Vector3d>(X_camera_table * *palm) : std::nullopt, cv::Mat());
  }
  return discovery.finish({}, 100);
}

Eigen::Vector2d placeOf(const ObjectPoseSample& s, const core::Pose3& X_table_camera) {
  return (X_table_camera * s.X_camera_object.translation()).head<2>();
}

TEST(ObjectDiscovery, FindsTheCarriedPartAndTheBinItIsLetGoIn) {
  const Demo d = makeDemo(true);
  const ObjectDiscovery::Result r = discover(d, toyAndBin());
  ASSERT_EQ(r.classes.size(), 2u);
  ASSERT_EQ(r.trajectories.size(), 2u);

  const core::ObjectClass& toy = r.classes[0];
  EXPECT_EQ(toy.name, "toy");
  EXPECT_EQ(toy.kind, core::ObjectKind::Part);
  EXPECT_EQ(toy.shape, "hull");
  EXPECT_TRUE(toy.observed);
  EXPECT_EQ(toy.classId, 100) << "the first free id";
  EXPECT_NEAR(toy.dimensions_m.x(), kPartSize_m.x(), kSize_m) << "x along the longer side";
  EXPECT_NEAR(toy.dimensions_m.y(), kPartSize_m.y(), kSize_m);
  EXPECT_NEAR(toy.dimensions_m.z(), kPartSize_m.z(), kSize_m);
  EXPECT_GE(toy.footprint_object.size(), 4u);
  EXPECT_EQ(toy.colourName, "blue");

  const core::ObjectClass& bin = r.classes[1];
  EXPECT_EQ(bin.kind, core::ObjectKind::Container) << "its inside is lower than its rim";
  EXPECT_EQ(bin.shape, "open_box");
  EXPECT_NEAR(bin.dimensions_m.x(), kBinSize_m.x(), kSize_m);
  EXPECT_NEAR(bin.dimensions_m.y(), kBinSize_m.y(), kSize_m);
  EXPECT_NEAR(bin.dimensions_m.z(), kBinSize_m.z(), kSize_m);
  EXPECT_EQ(bin.colourName, "gray");

  // The toy's track: at its start place until it leaves, carried, then in the bin.
  const ObjectTrajectory& t = r.trajectories[0];
  ASSERT_EQ(t.samples.size(), static_cast<std::size_t>(kFrames));
  const Eigen::Vector2d first = placeOf(t.samples.front(), d.X_table_camera);
  const Eigen::Vector2d last = placeOf(t.samples.back(), d.X_table_camera);
  std::printf("[ figures  ] toy %.3f x %.3f x %.3f m (rendered %.2f x %.2f x %.2f), bin %.3f x %.3f x %.3f m "
              "(%.2f x %.2f x %.2f); toy's start %.1f mm, end %.1f mm from the rendered places\n",
              toy.dimensions_m.x(), toy.dimensions_m.y(), toy.dimensions_m.z(), kPartSize_m.x(), kPartSize_m.y(),
              kPartSize_m.z(), bin.dimensions_m.x(), bin.dimensions_m.y(), bin.dimensions_m.z(), kBinSize_m.x(),
              kBinSize_m.y(), kBinSize_m.z(), 1e3 * (first - kStart_m).norm(), 1e3 * (last - kBin_m).norm());
  EXPECT_LT((first - kStart_m).norm(), kPlace_m) << first.transpose();
  EXPECT_LT((last - kBin_m).norm(), kPlace_m) << last.transpose();
  EXPECT_TRUE(t.samples.front().detected);
  EXPECT_TRUE(t.samples.back().detected);
  int carriedSeen = 0;
  for (int i = 12; i <= 21; ++i) carriedSeen += t.samples[static_cast<std::size_t>(i)].detected;
  EXPECT_GE(carriedSeen, 5) << "the part is in view while carried";
  const ObjectTrajectory& b = r.trajectories[1];
  EXPECT_TRUE(b.isStatic);
  EXPECT_LT((placeOf(b.samples.front(), d.X_table_camera) - kBin_m).norm(), kPlace_m);
}

TEST(ObjectDiscovery, AColourWordTheMovedPartDoesNotBearIsRefused) {
  const Demo d = makeDemo(true);
  EXPECT_NO_THROW(discover(d, toyAndBin("blue")));
  try {
    discover(d, toyAndBin("red"));
    FAIL() << "a red toy was found";
  } catch (const core::InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("no segment moved by the hand is red"), std::string::npos) << e.what();
  }
}

TEST(ObjectDiscovery, APartTheHandDoesNotMoveIsRefusedNamingWhatStood) {
  const Demo d = makeDemo(false);
  try {
    discover(d, toyAndBin());
    FAIL() << "a toy was found in a demonstration where nothing moves";
  } catch (const core::InvalidInputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no segment on the table was moved by the hand"), std::string::npos) << what;
    EXPECT_NE(what.find("blue segment"), std::string::npos) << "names what stood there: " << what;
  }
}

// srp kb add --from-demo: the segment at a pixel of one frame, measured.
TEST(ObjectDiscovery, MeasuresWhatStandsAtAPixel) {
  const Demo d = makeDemo(false);
  const rawlog::RgbdFrame& f = d.frames.front();
  const core::Pose3 X_camera_table = d.X_table_camera.inverse();
  const auto pixelOf = [&](const Eigen::Vector3d& p_table) {
    const Eigen::Vector3d p = X_camera_table * p_table;
    return Eigen::Vector2d(f.intrinsics.fx_px * p.x() / p.z() + f.intrinsics.cx_px,
                           f.intrinsics.fy_px * p.y() / p.z() + f.intrinsics.cy_px);
  };
  const auto toy = ObjectDiscovery::measureAt(f, X_camera_table, pixelOf({kStart_m.x(), kStart_m.y(), kPartSize_m.z()}),
                                              ObjectDiscovery::Options{});
  ASSERT_TRUE(toy.has_value());
  EXPECT_NEAR(toy->size_m.x(), kPartSize_m.x(), kSize_m);
  EXPECT_NEAR(toy->size_m.y(), kPartSize_m.y(), kSize_m);
  EXPECT_NEAR(toy->size_m.z(), kPartSize_m.z(), kSize_m);
  EXPECT_LT((toy->X_table_object.translation().head<2>() - kStart_m).norm(), kPlace_m);
  EXPECT_EQ(toy->colourWord, "blue");
  EXPECT_GT(toy->rgb.z(), toy->rgb.x()) << "linear RGB, blue above red";
  const auto bin = ObjectDiscovery::measureAt(f, X_camera_table, pixelOf({kBin_m.x() + kBinSize_m.x() / 2, kBin_m.y(), kBinSize_m.z()}),
                                              ObjectDiscovery::Options{});
  ASSERT_TRUE(bin.has_value()) << "a pixel on the bin's right wall";
  EXPECT_NEAR(bin->size_m.x(), kBinSize_m.x(), kSize_m);
  EXPECT_NEAR(bin->size_m.z(), kBinSize_m.z(), kSize_m);
  EXPECT_FALSE(ObjectDiscovery::measureAt(f, X_camera_table, pixelOf({0.0, -0.25, 0.0}), ObjectDiscovery::Options{}))
      << "the bare table top";
}

}  // namespace
}  // namespace srp::perception
