// The check families near-corner and table-level and the development family facing (srp::synth
// Viewpoint.h) rendered as acceptance.perception.ViewpointFamilies scores them (ViewpointDemos.h's
// familySpecs: their six demonstrations, light, parts and forearms), at 320x240, against the render's own
// ground truth and the hand model's geometry. No hand detector runs here: a check family is scored once
// per round on the final detector.
//
// What the family must be to check the palm: the optical axis meets the table and both boxes are in the
// image; the hand is in view in most frames of every phase with the hand out (reach, grasp, move,
// release, retract) and out of view while the demonstrator waits (idle); the palm centre projects onto
// the hand (where the depth at its pixel is valid, it is the hand model's own nearest surface along that
// pixel's ray, not the held part's nor a box's); the forearm leaves the image through the edge its family
// says (near-corner, table-level: the left or right edge on the demonstrator's side; facing: the top
// edge, the arm coming towards the camera), the sleeve's elbow end beyond it or behind the camera, never
// ending inside the image; the sensor model leaves depth on the hand.
//
// SRP_RENDER_SHEET=<dir> writes one PNG per demonstration there: a colour frame from the middle of
// every phase, left to right (for a person to check that the render is sane). SRP_VIEW_WIDTH=px renders
// at another width (4:3); SRP_VIEW_DIR=<dir> keeps the renders there (named as
// acceptance.perception.ViewpointFamilies names them, which scores a render it finds there).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "ViewpointDemos.h"
#include "srp/core/Error.h"
#include "srp/rawlog/RawlogReader.h"
#include "srp/synth/HandModel.h"

namespace srp::perception {
namespace {

constexpr int kWidth_px = 320;
/// The phases with the hand out of its rest: in view in at least this share of each one's frames (facing:
/// kMinFacingHandInViewShare; the low camera sees far along the demonstrator's direction and the hand
/// rests farther out: 66-100 % of each phase's frames at 320x240, 73-100 % at 640x480).
constexpr double kMinHandInViewShare = 0.75, kMinFacingHandInViewShare = 0.6;
/// The waits at the start and the end: the hand in view in at most this share.
constexpr double kMaxIdleHandShare = 0.05;
/// Frames whose palm projects inside the image with a valid depth there: the depth within kOnHandTol_m
/// of the hand model's nearest surface along that pixel's ray in at least this share (the visible
/// surface there is the hand's or the forearm's, not the held part's nor a box's).
constexpr double kMinPalmOnHandShare = 0.9;
constexpr double kOnHandTol_m = 0.006;  // depth noise (~1 mm at 0.7 m), 1 mm steps, a pixel's slope on a grazing face
/// Mean valid-depth fraction on the visible hand (sensor model's dropout; the default demo: 0.32 at 320x240).
constexpr double kMinHandValidDepth = 0.3;
/// Hand-in-view frames whose sleeve's elbow end lies beyond the edge the arm enters from (within
/// kEdgeMargin of the width from it: the sleeve's end face then shows as a strip of a few pixels at most),
/// and beyond it, beyond the next edge on the demonstrator's half (the bottom one after a side edge, a side
/// one after the top edge) or behind the camera (the arm cut by the image or passing beside the camera).
/// No sleeve ends inside the image.
constexpr double kMinArmThroughEntryShare = 0.9, kMinArmCutShare = 0.99, kEdgeMargin = 0.02;

/// The image edge a family's arm enters from.
enum class ArmEntry { DemonstratorsSide, Top };

const char* const kPhases[] = {"idle", "reach", "grasp", "move", "release", "retract"};

struct RenderFigures {
  std::map<std::string, std::pair<int, int>> inViewByPhase;  // phase -> (hand in view, frames)
  int palmChecked = 0, palmOnHand = 0;
  int armFrames = 0, armThroughEntry = 0, armThroughNext = 0, armBehind = 0, armInside = 0;
  double handValidDepthSum = 0.0;
  int handValidDepthFrames = 0;
  bool containersInView = true, axisOnTable = true;
};

/// The sleeve's far (elbow) end in the hand frame at `grip`.
Eigen::Vector3d elbow_hand(const synth::HandModel& hand, double grip) {
  const auto poses = hand.partPoses(grip);
  for (std::size_t i = 0; i < hand.parts().size(); ++i)
    if (hand.parts()[i].name == "sleeve") {
      const auto& b = hand.parts()[i].bounds_part;
      return poses[i] * Eigen::Vector3d(b.min().x(), b.center().y(), b.center().z());
    }
  throw core::InvalidInputError("HandModel has no part 'sleeve'");
}

/// Depth (camera z) of the hand model's nearest surface along `ray_camera` (from the camera's centre),
/// the hand at `X_camera_hand` with `grip`; +inf when the ray misses it. Every HandPart is a box (its bounds).
double nearestHandDepth_m(const synth::HandModel& hand, double grip, const core::Pose3& X_camera_hand,
                          const Eigen::Vector3d& ray_camera) {
  const auto poses = hand.partPoses(grip);
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hand.parts().size(); ++i) {
    const core::Pose3 X_part_camera = (X_camera_hand * poses[i]).inverse();
    const Eigen::Vector3d o = X_part_camera.translation(), d = X_part_camera.linear() * ray_camera;
    const auto& b = hand.parts()[i].bounds_part;
    double tIn = 0.0, tOut = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3 && tIn <= tOut; ++a) {
      if (std::abs(d[a]) < 1e-12) {
        if (o[a] < b.min()[a] || o[a] > b.max()[a]) tIn = tOut + 1.0;
        continue;
      }
      double t0 = (b.min()[a] - o[a]) / d[a], t1 = (b.max()[a] - o[a]) / d[a];
      if (t0 > t1) std::swap(t0, t1);
      tIn = std::max(tIn, t0);
      tOut = std::min(tOut, t1);
    }
    if (tIn <= tOut) best = std::min(best, tIn * ray_camera.z());
  }
  return best;
}

RenderFigures checkRender(const testing::ViewpointDemoSpec& spec, const std::string& rawlog, ArmEntry entry) {
  const auto gt = synth::DemoGroundTruth::load(synth::groundTruthPathFor(rawlog));
  const auto& K = gt.intrinsics;
  RenderFigures out;
  // The table under the optical axis, and both boxes (their bases' centres) inside the image.
  const core::Pose3& X_world_camera = gt.X_world_camera;
  const Eigen::Vector3d o = X_world_camera.translation(), d = X_world_camera.linear().col(2);
  const Eigen::Vector3d foot = o - (o.z() / d.z()) * d;
  out.axisOnTable = d.z() < 0.0 && std::abs(foot.x()) < 0.6 && std::abs(foot.y()) < 0.4;  // the 1.2 x 0.8 m table
  for (const auto& obj : gt.objects) {
    if (obj.className.find("box") == std::string::npos) continue;
    const auto uv = K.project(X_world_camera.inverse() * obj.X_world_object_initial.translation());
    if (!uv || uv->x() < 0 || uv->y() < 0 || uv->x() > K.width_px - 1 || uv->y() > K.height_px - 1)
      out.containersInView = false;
  }
  // The side the demonstrator waits on: the rest pose's side of the image.
  const Eigen::Vector3d rest_camera = X_world_camera.inverse() * gt.frames.front().X_world_hand.translation();
  const double restSide = rest_camera.x();  // > 0: right of the optical axis
  const synth::HandModel hand;
  // The middle frame of every phase, for SRP_RENDER_SHEET.
  std::map<std::string, std::vector<int>> framesOfPhase;
  for (const auto& truth : gt.frames) framesOfPhase[truth.phase].push_back(truth.index);
  std::map<std::string, cv::Mat> sheet;
  srp::rawlog::RawlogReader reader(rawlog);
  for (const auto& truth : gt.frames) {
    const auto frame = reader.next();
    if (!frame) throw core::InvalidInputError(rawlog + ": fewer frames than its ground truth");
    auto& counts = out.inViewByPhase[truth.phase];
    ++counts.second;
    if (truth.handInView) ++counts.first;
    const auto& phaseFrames = framesOfPhase[truth.phase];
    if (truth.index == phaseFrames[phaseFrames.size() / 2]) sheet[truth.phase] = frame->colour_bgr8.clone();
    if (!truth.handInView) continue;
    if (truth.handValidDepthFraction) {
      out.handValidDepthSum += *truth.handValidDepthFraction;
      ++out.handValidDepthFrames;
    }
    const core::Pose3 X_camera_world = gt.X_world_camera_at(truth.index).inverse();
    const auto uv = K.project(truth.p_camera_palm_m);
    if (uv) {
      const int u = static_cast<int>(std::lround(uv->x())), v = static_cast<int>(std::lround(uv->y()));
      if (u >= 0 && v >= 0 && u < K.width_px && v < K.height_px) {
        const float z = frame->depth_m.at<float>(v, u);
        if (z > 0.0f) {
          ++out.palmChecked;
          const Eigen::Vector3d ray_camera((u - K.cx_px) / K.fx_px, (v - K.cy_px) / K.fy_px, 1.0);
          const double handZ_m = nearestHandDepth_m(hand, truth.grip, X_camera_world * truth.X_world_hand, ray_camera);
          if (std::abs(z - handZ_m) <= kOnHandTol_m) ++out.palmOnHand;
        }
      }
    }
    const Eigen::Vector3d elbow_camera = X_camera_world * truth.X_world_hand * elbow_hand(hand, truth.grip);
    ++out.armFrames;
    const auto e = K.project(elbow_camera);
    if (!e) {  // behind the camera: the arm passes beside it
      ++out.armBehind;
      continue;
    }
    const bool demonstratorsHalf = restSide > 0.0 ? e->x() > K.cx_px : e->x() < K.cx_px;
    const double margin_px = kEdgeMargin * K.width_px;
    const bool beyondSide = e->x() < margin_px || e->x() > K.width_px - 1 - margin_px;
    const bool beyondBottom = e->y() > K.height_px - 1, beyondTop = e->y() < 0.0;
    if (entry == ArmEntry::DemonstratorsSide) {
      if (demonstratorsHalf && beyondSide) ++out.armThroughEntry;
      else if (demonstratorsHalf && beyondBottom) ++out.armThroughNext;
    } else {
      if (e->y() < margin_px) ++out.armThroughEntry;
      else if (demonstratorsHalf && beyondSide) ++out.armThroughNext;
    }
    if (!beyondSide && !beyondBottom && !beyondTop) ++out.armInside;
  }
  if (const char* dir = std::getenv("SRP_RENDER_SHEET")) {
    std::vector<cv::Mat> row;
    for (const char* phase : kPhases)
      if (sheet.count(phase)) row.push_back(sheet[phase]);
    cv::Mat image;
    cv::hconcat(row, image);
    std::filesystem::create_directories(dir);
    cv::imwrite((std::filesystem::path(dir) / (spec.name() + ".png")).string(), image);
  }
  return out;
}

void expectFamilyRendersSanely(synth::ViewpointFamily family, ArmEntry entry) {
  const char* width = std::getenv("SRP_VIEW_WIDTH");
  const auto specs = testing::familySpecs(family, width ? std::atoi(width) : kWidth_px);
  // Fresh renders (removed afterwards; a folder per family: CTest may run the families at once) unless
  // SRP_VIEW_DIR keeps them.
  const char* keep = std::getenv("SRP_VIEW_DIR");
  const std::filesystem::path folder = keep ? std::filesystem::path(keep)
                                            : std::filesystem::path(SRP_BINARY_DIR) / "viewpoint_family_renders" /
                                                  synth::viewpointFamilyName(family);
  if (!keep) std::filesystem::remove_all(folder);
  for (const auto& spec : specs) {
    SCOPED_TRACE(spec.name());
    const auto t0 = std::chrono::steady_clock::now();
    const std::string rawlog = testing::renderViewpointDemo(spec, folder.string());
    const double render_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const RenderFigures f = checkRender(spec, rawlog, entry);
    std::printf("%s: rendered in %.1f s wall (0 when kept in SRP_VIEW_DIR)\n", spec.name().c_str(), render_s);
    EXPECT_TRUE(f.axisOnTable) << "the optical axis meets the table";
    EXPECT_TRUE(f.containersInView) << "both boxes in the image";
    for (const char* phase : kPhases) {
      ASSERT_TRUE(f.inViewByPhase.count(phase)) << phase;
      const auto [inView, frames] = f.inViewByPhase.at(phase);
      const double share = static_cast<double>(inView) / frames;
      std::printf("  %-8s hand in view %3d / %3d\n", phase, inView, frames);
      if (std::string(phase) == "idle")
        EXPECT_LE(share, kMaxIdleHandShare) << phase;
      else
        EXPECT_GE(share, family == synth::ViewpointFamily::Facing ? kMinFacingHandInViewShare : kMinHandInViewShare)
            << phase;
    }
    std::printf("  palm on the hand %d / %d; of %d hand frames the elbow beyond the %s edge %d, beyond the %s "
                "edge %d, behind the camera %d, inside %d; hand valid depth %.2f\n",
                f.palmOnHand, f.palmChecked, f.armFrames, entry == ArmEntry::Top ? "top" : "side", f.armThroughEntry,
                entry == ArmEntry::Top ? "side" : "bottom", f.armThroughNext, f.armBehind, f.armInside,
                f.handValidDepthSum / std::max(1, f.handValidDepthFrames));
    ASSERT_GT(f.palmChecked, 0);
    EXPECT_GE(static_cast<double>(f.palmOnHand) / f.palmChecked, kMinPalmOnHandShare);
    ASSERT_GT(f.armFrames, 0);
    EXPECT_GE(static_cast<double>(f.armThroughEntry) / f.armFrames, kMinArmThroughEntryShare);
    EXPECT_GE(static_cast<double>(f.armThroughEntry + f.armThroughNext + f.armBehind) / f.armFrames, kMinArmCutShare);
    EXPECT_EQ(f.armInside, 0) << "a sleeve ending inside the image";
    ASSERT_GT(f.handValidDepthFrames, 0);
    EXPECT_GE(f.handValidDepthSum / f.handValidDepthFrames, kMinHandValidDepth);
  }
  if (!keep) std::filesystem::remove_all(folder);
}

TEST(ViewpointFamilyRenders, NearCornerSeesTheArmFromTheDemonstratorsSide) {
  expectFamilyRendersSanely(synth::ViewpointFamily::NearCorner, ArmEntry::DemonstratorsSide);
}

TEST(ViewpointFamilyRenders, TableLevelSeesTheArmFromTheDemonstratorsSide) {
  expectFamilyRendersSanely(synth::ViewpointFamily::TableLevel, ArmEntry::DemonstratorsSide);
}

TEST(ViewpointFamilyRenders, FacingSeesTheArmComeFromTheTopEdge) {
  expectFamilyRendersSanely(synth::ViewpointFamily::Facing, ArmEntry::Top);
}

}  // namespace
}  // namespace srp::perception
