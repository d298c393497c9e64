#include "srp/perception/TagBoard.h"

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpPixelMeterConversion.h>
#include <visp3/vision/vpPose.h>

#include <cmath>

#include "srp/core/Error.h"
#include "srp/interop/PoseConversions.h"

namespace srp::perception {

TagBoardLayout TagBoardLayout::grid(double tagSize_m, double spacing_m, int tagsAlongX, int tagsAlongY,
                                    int firstId, const Eigen::Matrix3d& R_board_tag) {
  core::require(tagSize_m > 0 && spacing_m >= tagSize_m && tagsAlongX > 0 && tagsAlongY > 0,
                "TagBoardLayout::grid: need tag size > 0, spacing >= tag size and at least one tag");
  TagBoardLayout layout;
  layout.tagSize_m = tagSize_m;
  for (int ix = 0; ix < tagsAlongX; ++ix)
    for (int iy = 0; iy < tagsAlongY; ++iy) {
      core::Pose3 X = core::Pose3::Identity();
      X.linear() = R_board_tag;
      X.translation() = Eigen::Vector3d(ix * spacing_m + tagSize_m / 2, iy * spacing_m + tagSize_m / 2, 0.0);
      layout.X_board_tag[firstId + ix * tagsAlongY + iy] = X;
    }
  return layout;
}

TagBoardLayout TagBoardLayout::vispRbtBoard() {
  // Measured from the recording: tag x along board y, tag y along board x,
  // tag z along -board z (the board's z comes out of its face).
  Eigen::Matrix3d R;
  R << 0, 1, 0, 1, 0, 0, 0, 0, -1;
  constexpr double kTagSize_m = 0.0955;
  return grid(kTagSize_m, 1.25 * kTagSize_m, 3, 4, 0, R);
}

std::optional<BoardPose> estimateBoardPose(const std::vector<TagDetection>& tags, const TagBoardLayout& layout,
                                           const core::CameraIntrinsics& k) {
  vpCameraParameters cam;
  cam.initPersProjWithoutDistortion(k.fx_px, k.fy_px, k.cx_px, k.cy_px);
  vpPose pose;
  const TagDetection* best = nullptr;
  int used = 0;
  struct Obs {
    Eigen::Vector3d p_board;
    Eigen::Vector2d uv;
  };
  std::vector<Obs> obs;
  for (const TagDetection& t : tags) {
    const auto it = layout.X_board_tag.find(t.id);
    if (it == layout.X_board_tag.end()) continue;
    ++used;
    if (!best || t.reprojectionError_px < best->reprojectionError_px) best = &t;
    // The detector's corners are for its tag size; rescale to the board's.
    const double scale = layout.tagSize_m / (2.0 * t.corners_tag_m[0].head<2>().cwiseAbs().maxCoeff());
    for (int c = 0; c < 4; ++c) {
      const Eigen::Vector3d p = it->second * (t.corners_tag_m[c] * scale);
      double x = 0.0, y = 0.0;
      vpPixelMeterConversion::convertPoint(cam, t.corners_px[c].x(), t.corners_px[c].y(), x, y);
      vpPoint pt(p.x(), p.y(), p.z());
      pt.set_x(x);
      pt.set_y(y);
      pose.addPoint(pt);
      obs.push_back({p, t.corners_px[c]});
    }
  }
  if (!best) return std::nullopt;
  const double scaleBest = layout.tagSize_m / (2.0 * best->corners_tag_m[0].head<2>().cwiseAbs().maxCoeff());
  core::Pose3 X_camera_tag = best->X_camera_tag;
  X_camera_tag.translation() *= scaleBest;
  vpHomogeneousMatrix cMo = interop::toVisp(X_camera_tag * layout.X_board_tag.at(best->id).inverse());
  pose.computePose(vpPose::VIRTUAL_VS, cMo);

  BoardPose out;
  out.X_camera_board = interop::fromVisp(cMo);
  out.tagsUsed = used;
  double sq = 0.0;
  for (const Obs& o : obs) {
    const Eigen::Vector3d p = out.X_camera_board * o.p_board;
    const Eigen::Vector2d uv(k.fx_px * p.x() / p.z() + k.cx_px, k.fy_px * p.y() / p.z() + k.cy_px);
    sq += (uv - o.uv).squaredNorm();
  }
  out.rmsReprojection_px = std::sqrt(sq / static_cast<double>(obs.size()));
  return out;
}

}  // namespace srp::perception
