#include <gtest/gtest.h>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "srp/core/Error.h"
#include "srp/rawlog/DepthRegistration.h"
#include "srp/rawlog/LensDistortion.h"
#include "srp/rawlog/ObservationToFrame.h"
#include "srp/rawlog/RawlogReader.h"

using namespace srp::rawlog;

namespace {

const std::string kTestsRgbd = "/usr/share/mrpt/datasets/tests_rgbd.rawlog";

// Median distance [px] from the depth silhouettes (the nearer side of a depth
// jump) to the nearest colour edge (Canny), over pixels 8 px inside the image.
double medianDepthEdgeToColourEdge_px(const RgbdFrame& f) {
  cv::Mat grey, edges;
  cv::cvtColor(f.colour_bgr8, grey, cv::COLOR_BGR2GRAY);
  cv::GaussianBlur(grey, grey, cv::Size(3, 3), 0.0);
  cv::Canny(grey, edges, 50, 150);
  cv::Mat distance;
  cv::distanceTransform(edges == 0, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  std::vector<float> d;
  const cv::Mat& z = f.depth_m;
  constexpr int kBorder = 8;
  for (int r = kBorder; r < z.rows - kBorder; ++r)
    for (int c = kBorder; c < z.cols - kBorder; ++c) {
      const float here = z.at<float>(r, c);
      if (!(here > 0.f)) continue;
      bool silhouette = false;
      for (const auto& [dr, dc] : {std::pair{0, 1}, {0, -1}, {1, 0}, {-1, 0}}) {
        const float there = z.at<float>(r + dr, c + dc);
        if (there > 0.f && there - here > std::max(0.03f, 0.05f * here)) silhouette = true;
      }
      if (silhouette) d.push_back(distance.at<float>(r, c));
    }
  if (d.empty()) return 1e9;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

mrpt::obs::CObservation3DRangeScan::Ptr firstObservation(const std::string& path) {
  mrpt::io::CFileGZInputStream in(path);
  auto arch = mrpt::serialization::archiveFrom(in);
  for (;;) {
    mrpt::serialization::CSerializable::Ptr obj;
    arch >> obj;
    if (auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obj)) {
      obs->load();
      return obs;
    }
  }
}

}  // namespace

TEST(LensDistortion, UndistortInvertsDistort) {
  constexpr double kTol = 1e-9;
  const LensDistortion d{0.0586, 0.0386, 0.001, -0.0005, 0.01};
  for (double x = -0.6; x <= 0.6; x += 0.2)
    for (double y = -0.45; y <= 0.45; y += 0.15) {
      const Eigen::Vector2d p(x, y);
      EXPECT_LT((d.undistort(d.distort(p)) - p).norm(), kTol) << x << " " << y;
    }
  EXPECT_TRUE(LensDistortion{}.isZero());
}

// A slanted plane seen by a 320x240 depth camera and a 640x360 colour camera
// 25 mm to its side: every registered pixel matches the plane's exact depth
// along the colour ray, and the upsampling leaves no holes inside the plane.
TEST(DepthRegistration, PlaneIsExactAndUpsampledWithoutHoles) {
  constexpr double kDepthTol_m = 1e-4;
  const DepthRegistration::Camera depthCam{{285.0, 285.0, 159.5, 119.5, 320, 240}, {}};
  const DepthRegistration::Camera colourCam{{460.0, 461.0, 321.0, 178.0, 640, 360}, {0.05, -0.02, 0.0, 0.0, 0.0}};
  srp::core::Pose3 X_colour_depth = srp::core::Pose3::Identity();
  X_colour_depth.translation() = Eigen::Vector3d(-0.025, 0.001, 0.002);
  X_colour_depth.linear() = Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY()).toRotationMatrix();
  // Plane n . p = 0.8 in the depth frame, tilted 35 degrees.
  const Eigen::Vector3d n = Eigen::Vector3d(0.0, std::sin(0.61), std::cos(0.61));
  constexpr double kOffset_m = 0.8;
  cv::Mat depth(240, 320, CV_32FC1);
  for (int r = 0; r < 240; ++r)
    for (int c = 0; c < 320; ++c) {
      const Eigen::Vector3d ray((c - 159.5) / 285.0, (r - 119.5) / 285.0, 1.0);
      depth.at<float>(r, c) = static_cast<float>(kOffset_m / n.dot(ray));
    }
  const DepthRegistration reg(depthCam, colourCam, X_colour_depth);
  const cv::Mat out = reg.registerDepth(depth);
  ASSERT_EQ(out.cols, 640);
  ASSERT_EQ(out.rows, 360);
  // The plane in the colour frame: n_c . p = o_c.
  const Eigen::Vector3d n_c = X_colour_depth.linear() * n;
  const double o_c = kOffset_m + n_c.dot(X_colour_depth.translation());
  const DepthRegistration::Camera& cc = colourCam;
  int inside = 0, filled = 0;
  double maxErr = 0.0;
  for (int v = 0; v < 360; ++v)
    for (int u = 0; u < 640; ++u) {
      const Eigen::Vector2d xy = cc.distortion.undistort({(u - cc.K.cx_px) / cc.K.fx_px, (v - cc.K.cy_px) / cc.K.fy_px});
      const Eigen::Vector3d ray(xy.x(), xy.y(), 1.0);
      const double z = o_c / n_c.dot(ray);
      // Is the point inside the depth camera's image (2 px from its border)?
      const Eigen::Vector3d p_d = X_colour_depth.inverse() * (z * ray);
      const double ud = 285.0 * p_d.x() / p_d.z() + 159.5, vd = 285.0 * p_d.y() / p_d.z() + 119.5;
      if (ud < 2 || vd < 2 || ud > 317 || vd > 237) continue;
      ++inside;
      const float got = out.at<float>(v, u);
      if (got > 0.f) {
        ++filled;
        maxErr = std::max(maxErr, std::abs(got - z));
      }
    }
  EXPECT_GT(inside, 100000);
  EXPECT_EQ(filled, inside) << "no holes inside the plane";
  EXPECT_LT(maxErr, kDepthTol_m);
}

// A truly unregistered observation (320x240 depth, 640x360 colour, colour
// camera 25 mm to the side) is registered on read: colour-sized depth, the
// colour camera's intrinsics, the colour image untouched.
TEST(DepthRegistration, UnregisteredMrptObservationIsRegisteredOnRead) {
  constexpr double kDepthTol_m = 1e-3;  // the observation stores millimetres
  const srp::core::CameraIntrinsics Kd{285.0, 285.0, 159.5, 119.5, 320, 240}, Kc{460.0, 461.0, 321.0, 178.0, 640, 360};
  srp::core::Pose3 X_depth_colour = srp::core::Pose3::Identity();
  X_depth_colour.translation() = Eigen::Vector3d(0.025, 0.0, 0.0);
  mrpt::obs::CObservation3DRangeScan obs;
  obs.hasRangeImage = true;
  obs.range_is_depth = true;
  obs.rangeUnits = 0.001f;
  obs.rangeImage_setSize(Kd.height_px, Kd.width_px);
  for (int r = 0; r < Kd.height_px; ++r)
    for (int c = 0; c < Kd.width_px; ++c) obs.rangeImage(r, c) = static_cast<uint16_t>(700 + r);  // a tilted plane [mm]
  obs.cameraParams.ncols = Kd.width_px, obs.cameraParams.nrows = Kd.height_px;
  obs.cameraParams.setIntrinsicParamsFromValues(Kd.fx_px, Kd.fy_px, Kd.cx_px, Kd.cy_px);
  obs.cameraParamsIntensity.ncols = Kc.width_px, obs.cameraParamsIntensity.nrows = Kc.height_px;
  obs.cameraParamsIntensity.setIntrinsicParamsFromValues(Kc.fx_px, Kc.fy_px, Kc.cx_px, Kc.cy_px);
  const mrpt::poses::CPose3D depthOptical(0, 0, 0, -M_PI / 2, 0, -M_PI / 2);
  mrpt::math::CMatrixDouble44 H;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) H(i, j) = X_depth_colour.matrix()(i, j);
  obs.relativePoseIntensityWRTDepth = depthOptical + mrpt::poses::CPose3D(H);
  cv::Mat colour(Kc.height_px, Kc.width_px, CV_8UC3, cv::Scalar(10, 200, 30));
  obs.hasIntensityImage = true;
  obs.intensityImage = mrpt::img::CImage(colour, mrpt::img::DEEP_COPY);

  const ObservationCameras cams = observationCameras(obs);
  EXPECT_NEAR(cams.baseline_m, 0.025, 1e-9);
  EXPECT_TRUE(cams.X_colour_depth.isApprox(X_depth_colour.inverse(), 1e-9));
  std::string reason;
  EXPECT_TRUE(needsRegistration(cams, &reason));
  const RgbdFrame f = frameFromObservation(obs, 0);
  EXPECT_TRUE(f.depthRegisteredOnRead);
  EXPECT_EQ(f.intrinsics, Kc);
  ASSERT_EQ(f.depth_m.cols, Kc.width_px);
  ASSERT_EQ(f.colour_bgr8.cols, Kc.width_px);
  EXPECT_EQ(cv::norm(f.colour_bgr8, colour, cv::NORM_INF), 0.0) << "colour untouched";
  // Independent check: a colour pixel's depth, carried back to the depth camera, reads the same depth there.
  int checked = 0;
  for (int v = 20; v < Kc.height_px - 20; v += 13)
    for (int u = 100; u < Kc.width_px - 100; u += 17) {  // the depth camera sees u in [79, 595]
      const float z = f.depth_m.at<float>(v, u);
      ASSERT_GT(z, 0.f) << u << "," << v;
      const Eigen::Vector3d p_depth = X_depth_colour * Kc.backProject(u, v, z);
      const auto uv = Kd.project(p_depth);
      ASSERT_TRUE(uv && Kd.contains(uv->x(), uv->y()));
      EXPECT_NEAR(p_depth.z(), 0.7 + 0.001 * uv->y(), kDepthTol_m) << u << "," << v;
      ++checked;
    }
  EXPECT_GT(checked, 500);
  // The same through RawlogReader, from a rawlog written by MRPT itself.
  const std::string path = (std::filesystem::temp_directory_path() / "srp_rawlog_unregistered.rawlog").string();
  {
    mrpt::io::CFileGZOutputStream out(path);
    auto arch = mrpt::serialization::archiveFrom(out);
    arch << obs;
  }
  const auto frames = RawlogReader::readAll(path);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_TRUE(frames[0].depthRegisteredOnRead);
  EXPECT_EQ(frames[0].intrinsics, Kc);
  EXPECT_EQ(cv::norm(frames[0].depth_m, f.depth_m, cv::NORM_INF), 0.0);
  // Asked to keep it as recorded, the reader cannot pair 320x240 depth with 640x360 colour but by resizing the colour.
  EXPECT_EQ(frameFromObservation(obs, 0, DepthRegistrationMode::AsRecorded).intrinsics, Kd);
}

TEST(DepthRegistration, RejectsDepthOfAnotherSize) {
  const DepthRegistration reg({{285.0, 285.0, 159.5, 119.5, 320, 240}, {}}, {{285.0, 285.0, 159.5, 119.5, 320, 240}, {}},
                              srp::core::Pose3::Identity());
  EXPECT_THROW(reg.registerDepth(cv::Mat(480, 640, CV_32FC1, cv::Scalar(1.0))), srp::core::InvalidInputError);
}

// MRPT's sample RGB-D observation (an OpenNI2 Kinect-type camera, hardware
// registered): its stored cameras nominally differ (other intrinsics, colour
// centre 1.6 mm from the depth centre, so MRPT's coincide flag is false), yet
// its colour and depth are on one grid. The reader keeps it as recorded, and
// its depth silhouettes stay within 2 px (median) of colour edges.
TEST(DepthRegistration, MrptSampleKeepsItsAlignment) {
  constexpr double kMaxMedianEdgeDistance_px = 2.0;
  ASSERT_TRUE(std::filesystem::exists(kTestsRgbd)) << kTestsRgbd << " missing: install mrpt-common (Debian)";
  const auto obs = firstObservation(kTestsRgbd);
  const ObservationCameras cams = observationCameras(*obs);
  std::string reason;
  EXPECT_FALSE(cams.mrptCoincide);
  EXPECT_FALSE(needsRegistration(cams, &reason)) << reason;
  const RgbdFrame asRead = frameFromObservation(*obs, 0);
  EXPECT_FALSE(asRead.depthRegisteredOnRead);
  const double asRead_px = medianDepthEdgeToColourEdge_px(asRead);
  const RgbdFrame reprojected = frameFromObservation(*obs, 0, DepthRegistrationMode::Register);
  const double reprojected_px = medianDepthEdgeToColourEdge_px(reprojected);
  std::cout << "tests_rgbd: baseline " << 1e3 * cams.baseline_m << " mm, " << reason
            << "; median depth-edge to colour-edge distance as read " << asRead_px
            << " px, re-projected with its stored cameras " << reprojected_px << " px\n";
  EXPECT_LE(asRead_px, kMaxMedianEdgeDistance_px);
  // The reader's frame is the as-read one.
  const auto frames = RawlogReader::readAll(kTestsRgbd);
  ASSERT_FALSE(frames.empty());
  EXPECT_EQ(medianDepthEdgeToColourEdge_px(frames.front()), asRead_px);
}

// Real depth (ViSP's RealSense recording, frame 0, registered by the camera):
// registering it between two identical cameras must give it back unchanged,
// holes and noise included (no depth invented, none lost).
TEST(DepthRegistration, IdentityLeavesRealDepthUnchanged) {
  constexpr double kDepthTol_m = 1e-6;  // float rounding of the back-and-forth
  const std::string path = std::string(SRP_DATASETS_DIR) + "/real/visp-rbt-cube/depth_0000.png";
  const cv::Mat raw = cv::imread(path, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(raw.type(), CV_16UC1) << path;
  cv::Mat depth;
  raw.convertTo(depth, CV_32FC1, 0.001);
  const srp::core::CameraIntrinsics K{607.178466796875, 607.2342529296875, 321.39129638671875, 241.91822814941406, 640, 480};
  const DepthRegistration reg({K, {}}, {K, {}}, srp::core::Pose3::Identity());
  const cv::Mat out = reg.registerDepth(depth);
  int valid = 0, changed = 0, filledHoles = 0, lost = 0;
  for (int r = 0; r < depth.rows; ++r)
    for (int c = 0; c < depth.cols; ++c) {
      const float a = depth.at<float>(r, c), b = out.at<float>(r, c);
      if (a > 0.f) ++valid;
      if (a > 0.f && !(b > 0.f)) ++lost;
      else if (!(a > 0.f) && b > 0.f) ++filledHoles;
      else if (a > 0.f && std::abs(a - b) > kDepthTol_m) ++changed;
    }
  EXPECT_GT(valid, 200000);
  EXPECT_LT(valid, 640 * 480) << "the frame has holes to keep";
  EXPECT_EQ(lost, 0);
  EXPECT_EQ(filledHoles, 0);
  EXPECT_EQ(changed, 0);
}
