#include "srp/synth/HandModel.h"

#include <gtest/gtest.h>
#include <visp3/core/vpImage.h>
#include <visp3/detection/vpDetectorAprilTag.h>

#include <iostream>
#include <opencv2/imgproc.hpp>

#include "srp/core/Error.h"
#include "srp/core/Scene.h"
#include "srp/kb/ShapeMeshes.h"
#include "srp/synth/SceneRenderer.h"

namespace {

constexpr double kCornerTol_px = 1.0;  // acceptance: projected tag corners on the rendered tag
// The AprilTag library (inside ViSP's detector) puts pixel centres at +0.5;
// srp (CameraIntrinsics) at integers. Corrected for that, the fit is much tighter.
constexpr double kAprilTagPixelOffset_px = 0.5;
constexpr double kCorrectedCornerTol_px = 0.4;
constexpr int kBlackMax = 80, kWhiteMin = 150;  // 8-bit grey levels of lit black / white cells

// Renders the hand with its tag at a given pose over a table, like the demo camera sees it.
struct HandScene {
  srp::core::Scene scene = srp::core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  srp::synth::HandModel hand;
  srp::synth::SceneRenderer renderer{scene.intrinsics};
  std::vector<int> bodies;
  explicit HandScene(const srp::synth::HandModel::Options& options = {}) : hand(options) {
    renderer.setLighting(scene.lighting);
    renderer.addBody("table", srp::kb::makeBoxMesh({-0.8, -0.6, -0.02}, {0.8, 0.6, 0.0}), {0.76, 0.7, 0.6});
    for (const auto& p : hand.parts()) bodies.push_back(renderer.addBody(p.name, p.mesh_part, p.triangleRgb));
  }
  srp::rawlog::RgbdFrame render(const srp::core::Pose3& X_world_hand, double grip) {
    const auto poses = hand.partPoses(grip);
    for (std::size_t i = 0; i < bodies.size(); ++i) renderer.setBodyPose(bodies[i], X_world_hand * poses[i]);
    return renderer.render(scene.X_world_camera);
  }
  std::array<Eigen::Vector2d, 4> projectedCorners(const srp::core::Pose3& X_world_hand) const {
    std::array<Eigen::Vector2d, 4> px;
    const auto corners = hand.tagCorners_tag();
    const srp::core::Pose3 X_camera_tag = scene.X_world_camera.inverse() * X_world_hand * hand.X_hand_tag();
    for (int c = 0; c < 4; ++c) px[c] = *scene.intrinsics.project(X_camera_tag * corners[c]);
    return px;
  }
};

vpImage<unsigned char> toVisp(const cv::Mat& bgr) {
  cv::Mat grey;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  vpImage<unsigned char> I(grey.rows, grey.cols);
  for (int r = 0; r < grey.rows; ++r)
    for (int c = 0; c < grey.cols; ++c) I[r][c] = grey.at<unsigned char>(r, c);
  return I;
}

TEST(HandModel, TagIsTag36h11Id0WithBlackBorderAndWhiteMargin) {
  srp::synth::HandModel hand;
  const auto& cells = hand.tagCells();
  ASSERT_EQ(cells.size(), 10u);
  for (int i = 0; i < 10; ++i) {
    EXPECT_FALSE(cells[0][i]);  // white margin
    EXPECT_FALSE(cells[9][i]);
    if (i >= 1 && i <= 8) {
      EXPECT_TRUE(cells[1][i]);  // black border
      EXPECT_TRUE(cells[8][i]);
    }
  }
  srp::synth::HandModel::Options badId;
  badId.tagId = -1;
  EXPECT_THROW(srp::synth::HandModel{badId}, srp::core::InvalidInputError);
}

// The projected ground-truth corners land on the rendered tag: ViSP's AprilTag
// detector finds id 0 with corners within 1 px of them, and the pixels just
// inside / outside each corner are black / white.
TEST(HandModel, ProjectedTagCornersLandOnTheRenderedTag) {
  HandScene s;
  vpDetectorAprilTag detector(vpDetectorAprilTag::TAG_36h11);
  const std::vector<srp::core::Pose3> poses = {
      srp::core::makePoseYPR({0.02, 0.15, 0.18}, -1.7, 0.14, 0.0),
      srp::core::makePoseYPR({-0.12, 0.05, 0.25}, -1.2, 0.05, 0.1),
      srp::core::makePoseYPR({0.15, 0.22, 0.12}, -2.3, 0.2, -0.05)};
  double worst_px = 0.0;
  Eigen::Vector2d meanOffset_px = Eigen::Vector2d::Zero();
  double worstCorrected_px = 0.0;
  for (const auto& X_world_hand : poses) {
    const auto frame = s.render(X_world_hand, 0.5);
    const auto expected = s.projectedCorners(X_world_hand);
    vpImage<unsigned char> I = toVisp(frame.colour_bgr8);
    ASSERT_TRUE(detector.detect(I));
    ASSERT_EQ(detector.getNbObjects(), 1u);
    EXPECT_NE(detector.getMessage(0).find("id: 0"), std::string::npos) << detector.getMessage(0);
    const auto polygon = detector.getPolygon(0);
    ASSERT_EQ(polygon.size(), 4u);
    for (const auto& e : expected) {
      double best = 1e9;
      Eigen::Vector2d bestOffset = Eigen::Vector2d::Zero();
      for (const auto& p : polygon) {
        const Eigen::Vector2d offset = Eigen::Vector2d(p.get_u(), p.get_v()) - e;
        if (offset.norm() < best) {
          best = offset.norm();
          bestOffset = offset;
        }
      }
      meanOffset_px += bestOffset / 12.0;
      worst_px = std::max(worst_px, best);
      EXPECT_LT(best, kCornerTol_px) << "corner " << e.transpose();
      const double corrected = (bestOffset - Eigen::Vector2d::Constant(kAprilTagPixelOffset_px)).norm();
      worstCorrected_px = std::max(worstCorrected_px, corrected);
      EXPECT_LT(corrected, kCorrectedCornerTol_px) << "corner " << e.transpose();
    }
    // Pixel check on both sides of each corner, along the diagonal.
    cv::Mat grey;
    cv::cvtColor(frame.colour_bgr8, grey, cv::COLOR_BGR2GRAY);
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const auto& e : expected) centre += e / 4.0;
    for (const auto& e : expected) {
      const Eigen::Vector2d in = e + 2.0 * (centre - e).normalized(), out = e - 2.0 * (centre - e).normalized();
      EXPECT_LT(grey.at<unsigned char>(std::lround(in.y()), std::lround(in.x())), kBlackMax);
      EXPECT_GT(grey.at<unsigned char>(std::lround(out.y()), std::lround(out.x())), kWhiteMin);
    }
  }
  std::cout << "[measured] worst tag corner distance (ViSP detection vs ground truth): " << worst_px
            << " px, mean offset (" << meanOffset_px.transpose() << ") px, worst after removing AprilTag's +0.5 px: "
            << worstCorrected_px << " px\n";
}

TEST(HandModel, GripFlexesTheFingersTowardsThePalmSide) {
  srp::synth::HandModel hand;
  const auto open = hand.partPoses(0.0), closed = hand.partPoses(1.0);
  for (std::size_t i = 0; i < hand.parts().size(); ++i) {
    if (hand.parts()[i].name.find("distal") == std::string::npos) continue;
    const Eigen::Vector3d tipOpen = open[i] * Eigen::Vector3d(0.03, 0, 0);
    const Eigen::Vector3d tipClosed = closed[i] * Eigen::Vector3d(0.03, 0, 0);
    EXPECT_LT(tipClosed.z(), tipOpen.z() - 0.01) << hand.parts()[i].name;  // curls down, under the palm
  }
}

}  // namespace

namespace {

// Nothing of the hand rises over the tag plate at any grip: every corner of
// every other part that lies above the plate's footprint (plus a margin for
// oblique views) stays below the plate, and the palm's top a clear gap below
// it (no depth fighting). This is what keeps the tag readable while grasping.
TEST(HandModel, NoPartRisesOverTheTagPlateAtAnyGrip) {
  constexpr double kFootprintMargin_m = 0.008, kMinGapBelowPlate_m = 0.0015;
  srp::synth::HandModel hand;
  const double half = hand.tagPlateHalfSize_m() + kFootprintMargin_m;
  const double plateZ = hand.X_hand_tag().translation().z();
  for (double grip : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    const auto poses = hand.partPoses(grip);
    for (std::size_t i = 0; i < hand.parts().size(); ++i) {
      if (hand.parts()[i].name == "tag") continue;
      const auto& box = hand.parts()[i].bounds_part;
      for (int c = 0; c < 8; ++c) {
        const Eigen::Vector3d p = poses[i] * box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
        if (std::abs(p.x()) > half || std::abs(p.y()) > half) continue;
        EXPECT_LT(p.z(), plateZ - kMinGapBelowPlate_m) << hand.parts()[i].name << " corner " << c << " grip " << grip;
      }
    }
  }
}

}  // namespace

namespace {

using srp::synth::HandModel;

HandModel::Options wiredOptions() {
  HandModel::Options o;
  o.sensorWires.enabled = true;
  return o;
}

bool sameRgb(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).cwiseAbs().maxCoeff() < 1e-12; }

// The dressing only appends triangles to the parts' meshes, in the wire's or the tape's colour: the
// clean hand's triangles come first, unchanged. Wires lie on both segments of every digit and on the
// back of the hand; tape on every distal segment (the sensors), the back of the hand and round the
// wrist. Off (whatever its sizes), the hand is the clean one, triangle for triangle.
TEST(HandModel, SensorWiresAddWireAndTapeTrianglesInTheirColours) {
  const HandModel clean, dressed(wiredOptions());
  const auto& w = dressed.options().sensorWires;
  ASSERT_EQ(clean.parts().size(), dressed.parts().size());
  for (std::size_t i = 0; i < clean.parts().size(); ++i) {
    const auto& c = clean.parts()[i];
    const auto& d = dressed.parts()[i];
    ASSERT_EQ(c.name, d.name);
    ASSERT_EQ(d.mesh_part.size(), d.triangleRgb.size()) << d.name;
    ASSERT_GE(d.mesh_part.size(), c.mesh_part.size()) << d.name;
    for (std::size_t t = 0; t < c.mesh_part.size(); ++t) {
      EXPECT_EQ(c.mesh_part.triangles()[t], d.mesh_part.triangles()[t]) << d.name << " triangle " << t;
      EXPECT_TRUE(sameRgb(c.triangleRgb[t], d.triangleRgb[t])) << d.name << " triangle " << t;
    }
    int wire = 0, tape = 0;
    for (std::size_t t = c.mesh_part.size(); t < d.mesh_part.size(); ++t) {
      wire += sameRgb(d.triangleRgb[t], w.wireRgb);
      tape += sameRgb(d.triangleRgb[t], w.tapeRgb);
    }
    EXPECT_EQ(wire + tape, static_cast<int>(d.mesh_part.size() - c.mesh_part.size())) << d.name << ": other colours";
    const bool digit = d.name.find("finger") == 0 || d.name.find("thumb") == 0;
    const bool distal = d.name.find("distal") != std::string::npos;
    EXPECT_EQ(wire > 0, digit || d.name == "palm") << d.name << ": " << wire << " wire triangles";
    EXPECT_EQ(tape > 0, distal || d.name == "palm" || d.name == "wrist") << d.name << ": " << tape << " tape triangles";
    std::cout << "[measured] " << d.name << ": " << wire << " wire and " << tape << " tape triangles\n";
  }
  // Off, whatever the sizes: the clean hand.
  HandModel::Options off;
  off.sensorWires.wireDiameter_m = 0.003;
  off.sensorWires.wristBandWidth_m = 0.03;
  const HandModel offHand(off);
  for (std::size_t i = 0; i < clean.parts().size(); ++i) {
    EXPECT_EQ(offHand.parts()[i].mesh_part.triangles(), clean.parts()[i].mesh_part.triangles());
    EXPECT_EQ(offHand.parts()[i].triangleRgb, clean.parts()[i].triangleRgb);
  }
  HandModel::Options bad = wiredOptions();
  bad.sensorWires.tapeSize_m = 0.02;  // wider than a finger
  EXPECT_THROW(HandModel{bad}, srp::core::InvalidInputError);
}

// Rendered (colour and depth) over the table as the demo camera sees the back of the hand: the top
// of each wire piece on the back of the digits and the hand, where it is in view, is a dark pixel
// at the wire's depth, with skin 4 mm to either side; the clean hand shows skin there. Each sensor's
// tape on a fingertip is a light, neutral pixel. (3 mm wires: 2-3 px in the default camera.)
TEST(HandModel, RenderedSensorWiresLieWhereTheModelPutsThem) {
  constexpr int kWireMaxGrey = 60, kSkinMinGrey = 90, kTapeMinGrey = 170, kTapeMaxRedMinusBlue = 25;
  constexpr double kWireDepthTol_m = 0.002;  // the renderer's depth against the wire's top
  constexpr double kMinDarkShare = 0.9;      // of the wire pieces in view (an edge pixel may be mixed)
  HandModel::Options o = wiredOptions();
  o.sensorWires.wireDiameter_m = 0.003;
  HandScene dressed(o), clean;
  const srp::core::Pose3 X_world_hand = srp::core::makePoseYPR({0.02, 0.15, 0.18}, -1.7, 0.14, 0.0);
  constexpr double kGrip = 0.3;
  const auto frame = dressed.render(X_world_hand, kGrip), cleanFrame = clean.render(X_world_hand, kGrip);
  const auto poses = dressed.hand.partPoses(kGrip);
  const srp::core::Pose3 X_camera_world = dressed.scene.X_world_camera.inverse();
  cv::Mat grey, cleanGrey;
  cv::cvtColor(frame.colour_bgr8, grey, cv::COLOR_BGR2GRAY);
  cv::cvtColor(cleanFrame.colour_bgr8, cleanGrey, cv::COLOR_BGR2GRAY);
  const auto& w = o.sensorWires;
  int inView = 0, dark = 0, cleanDark = 0, skinBeside = 0, tapes = 0, lightTapes = 0;
  for (std::size_t i = 0; i < dressed.hand.parts().size(); ++i) {
    const auto& part = dressed.hand.parts()[i];
    const std::size_t first = clean.hand.parts()[i].mesh_part.size();
    const srp::core::Pose3 X_camera_part = X_camera_world * X_world_hand * poses[i];
    // The dressing is boxes (makeBoxMesh): each one's top face's centre and extent from its vertices.
    const std::size_t kBox = srp::kb::makeBoxMesh({0, 0, 0}, {1, 1, 1}).size();
    for (std::size_t t = first; t + kBox <= part.mesh_part.size(); t += kBox) {
      Eigen::AlignedBox3d box;
      for (std::size_t k = t; k < t + kBox; ++k)
        for (const auto& v : part.mesh_part.triangles()[k]) box.extend(v);
      const Eigen::Vector3d top(box.center().x(), box.center().y(), box.max().z());
      const bool isWire = sameRgb(part.triangleRgb[t], w.wireRgb);
      if (!isWire && part.name.find("distal") == std::string::npos) continue;  // tape: the fingertip sensors
      const Eigen::Vector3d p_camera = X_camera_part * top;
      const auto px = dressed.scene.intrinsics.project(p_camera);
      if (!px) continue;
      const int u = static_cast<int>(std::lround(px->x())), v = static_cast<int>(std::lround(px->y()));
      if (u < 1 || v < 1 || u >= grey.cols - 1 || v >= grey.rows - 1) continue;
      // In view: the rendered surface there is this box's top (nothing nearer hides it).
      const float z = frame.depth_m.at<float>(v, u);
      if (!(z > 0.f) || std::abs(z - p_camera.z()) > kWireDepthTol_m) continue;
      if (!isWire) {
        ++tapes;
        const cv::Vec3b bgr = frame.colour_bgr8.at<cv::Vec3b>(v, u);
        lightTapes += grey.at<uchar>(v, u) >= kTapeMinGrey && std::abs(bgr[2] - bgr[0]) <= kTapeMaxRedMinusBlue;
        continue;
      }
      ++inView;
      dark += grey.at<uchar>(v, u) <= kWireMaxGrey;
      cleanDark += cleanGrey.at<uchar>(v, u) <= kWireMaxGrey;
      // Skin 4 mm beside the wire, across its run (the box's shorter side in the part's plane).
      const Eigen::Vector3d across = box.sizes().x() < box.sizes().y() ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
      int skin = 0;
      for (double sgn : {-1.0, 1.0}) {
        const auto q = dressed.scene.intrinsics.project(X_camera_part * (top + sgn * (0.5 * w.wireDiameter_m + 0.004) * across -
                                                                         Eigen::Vector3d(0, 0, w.wireDiameter_m)));
        if (!q) continue;
        const int qu = static_cast<int>(std::lround(q->x())), qv = static_cast<int>(std::lround(q->y()));
        if (qu >= 0 && qv >= 0 && qu < grey.cols && qv < grey.rows && grey.at<uchar>(qv, qu) >= kSkinMinGrey) ++skin;
      }
      skinBeside += skin > 0;
    }
  }
  std::cout << "[measured] wire pieces in view " << inView << ", dark " << dark << " (clean hand: " << cleanDark
            << "), skin beside " << skinBeside << "; fingertip tapes in view " << tapes << ", light " << lightTapes
            << "\n";
  ASSERT_GE(inView, 20);  // the digits' and the hand's wires, seen from above
  EXPECT_GE(dark, kMinDarkShare * inView);
  EXPECT_LE(cleanDark, 0.05 * inView);
  EXPECT_GE(skinBeside, kMinDarkShare * inView);
  ASSERT_GE(tapes, 3);
  EXPECT_EQ(lightTapes, tapes);
}

}  // namespace
