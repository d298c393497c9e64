#pragma once
/// \file BoardEvidence.h
/// \brief The real_cube notebook's helpers for "how well does the AprilTag
/// board itself determine its pose in a frame?": the raw tag corners that
/// ViSP stored per frame, least-squares refits of the board pose from them
/// (OpenCV solvePnP), the first-order covariance of that pose carried to a
/// point (the cube), a fit constrained to put that point at a given place,
/// and image indicators of motion blur / rolling shutter. Only the board's
/// data and the images enter here: no estimate of ours.
/// Notebook code (not a library): kept next to main.cpp, used only by it.

#include <array>
#include <map>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/Pose.h"
#include "srp/perception/TagBoard.h"

namespace srp::notebook::board {

/// One tag as ViSP detected it in one frame: its 4 corners [px] in the
/// detector's order, its own single-tag pose, the detector's confidence.
struct TagCorners {
  int id = -1;
  std::array<Eigen::Vector2d, 4> corners_px;
  core::Pose3 X_camera_tag = core::Pose3::Identity();
  double confidence = 0.0;
};

inline core::Pose3 poseFromRows(const nlohmann::json& m) {
  return core::poseFromJson(nlohmann::json{{"matrix", m}}, "4x4 row-major pose");
}

/// Per frame, the tags of apriltag_board_poses.json's "detections".
inline std::vector<std::vector<TagCorners>> readDetections(const nlohmann::json& boardPoses) {
  core::require(boardPoses.contains("detections"),
                "apriltag_board_poses.json has no \"detections\": use the file shipped in datasets/real/visp-rbt-cube");
  std::vector<std::vector<TagCorners>> out;
  for (const auto& frame : boardPoses.at("detections")) {
    std::vector<TagCorners> tags;
    for (const auto& [key, d] : frame.items()) {
      TagCorners t;
      t.id = std::stoi(key);
      // Stored as ViSP's vpImagePoint, (i, j) = (row, column): u is the second.
      for (int c = 0; c < 4; ++c) t.corners_px[c] = {d.at("tag_corners")[c][1].get<double>(), d.at("tag_corners")[c][0].get<double>()};
      t.X_camera_tag = poseFromRows(d.at("cMo"));
      t.confidence = d.at("confidence").get<double>();
      tags.push_back(t);
    }
    out.push_back(tags);
  }
  return out;
}

struct Intrinsics {
  double fx, fy, cx, cy;
  cv::Matx33d K() const { return {fx, 0, cx, 0, fy, cy, 0, 0, 1}; }
  Eigen::Vector2d project(const Eigen::Vector3d& p) const { return {fx * p.x() / p.z() + cx, fy * p.y() / p.z() + cy}; }
};

/// The tag-frame coordinates of the detector's 4 corners, in its order: the
/// one of the 8 orders (4 starting corners x 2 directions) under which the
/// tags' own poses reproject their corners best in the given frame; also
/// returns that RMS [px] (checked by the caller: it must be ~1 px or less).
inline std::array<Eigen::Vector3d, 4> cornerOrder(const std::vector<TagCorners>& tags, double tagSize_m,
                                                  const Intrinsics& k, double& rms_px) {
  const double h = tagSize_m / 2;
  const std::array<Eigen::Vector3d, 4> ring = {Eigen::Vector3d(-h, -h, 0), Eigen::Vector3d(h, -h, 0),
                                               Eigen::Vector3d(h, h, 0), Eigen::Vector3d(-h, h, 0)};
  std::array<Eigen::Vector3d, 4> best{};
  rms_px = 1e9;
  for (int start = 0; start < 4; ++start)
    for (int dir : {1, 3}) {
      std::array<Eigen::Vector3d, 4> order;
      for (int c = 0; c < 4; ++c) order[c] = ring[(start + dir * c) % 4];
      double sse = 0;
      int n = 0;
      for (const auto& t : tags)
        for (int c = 0; c < 4; ++c, ++n) sse += (k.project(t.X_camera_tag * order[c]) - t.corners_px[c]).squaredNorm();
      if (std::sqrt(sse / n) < rms_px) {
        rms_px = std::sqrt(sse / n);
        best = order;
      }
    }
  return best;
}

/// The board layout in ViSP's tag frames: the tag centres of the regular grid
/// (`TagBoardLayout::vispRbtBoard`, 1.25 tag sizes apart, in the frame of the
/// stored board poses) with the tags' orientation on the board taken from the
/// data: the mean of inverse(board) * cMo over the given frame's tags, rounded
/// to the nearest signed axis permutation (ViSP's tag frame differs from the
/// one our own detector uses). `snap_deg` gets the mean's angle to that permutation.
inline perception::TagBoardLayout vispTagFrames(const std::vector<TagCorners>& tags, const core::Pose3& X_camera_board,
                                                double& snap_deg) {
  Eigen::Matrix3d mean = Eigen::Matrix3d::Zero();
  for (const auto& t : tags) mean += (X_camera_board.inverse() * t.X_camera_tag).linear() / double(tags.size());
  Eigen::Matrix3d R = mean.array().round().matrix();
  core::require((R * R.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-9 && R.determinant() > 0,
                "vispTagFrames: the tags' orientation on the board is not an axis permutation; check the detections");
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(mean, Eigen::ComputeFullU | Eigen::ComputeFullV);
  snap_deg = core::rotationAngleBetween(svd.matrixU() * svd.matrixV().transpose(), R) * 180 / M_PI;
  perception::TagBoardLayout layout = perception::TagBoardLayout::vispRbtBoard();
  for (auto& [id, X] : layout.X_board_tag) X.linear() = R;
  return layout;
}

/// 2D-3D pairs of one frame: each detected board tag's corners and their
/// points in the board frame.
struct Correspondences {
  std::vector<cv::Point3d> p_board_m;
  std::vector<cv::Point2d> uv_px;
  int tags = 0;
};
inline Correspondences correspondences(const std::vector<TagCorners>& tags, const perception::TagBoardLayout& layout,
                                       const std::array<Eigen::Vector3d, 4>& corners_tag_m) {
  Correspondences c;
  for (const auto& t : tags) {
    const auto it = layout.X_board_tag.find(t.id);
    if (it == layout.X_board_tag.end()) continue;
    ++c.tags;
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3d p = it->second * corners_tag_m[i];
      c.p_board_m.emplace_back(p.x(), p.y(), p.z());
      c.uv_px.emplace_back(t.corners_px[i].x(), t.corners_px[i].y());
    }
  }
  return c;
}

inline void toRvecTvec(const core::Pose3& X, cv::Vec3d& rvec, cv::Vec3d& tvec) {
  const Eigen::AngleAxisd aa(X.linear());
  const Eigen::Vector3d r = aa.axis() * aa.angle();
  rvec = {r.x(), r.y(), r.z()};
  tvec = {X.translation().x(), X.translation().y(), X.translation().z()};
}
inline core::Pose3 fromRvecTvec(const cv::Vec3d& rvec, const cv::Vec3d& tvec) {
  core::Pose3 X = core::Pose3::Identity();
  const Eigen::Vector3d r(rvec[0], rvec[1], rvec[2]);
  if (r.norm() > 0) X.linear() = Eigen::AngleAxisd(r.norm(), r.normalized()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(tvec[0], tvec[1], tvec[2]);
  return X;
}

/// Residuals [px] (u, v interleaved) of a board pose.
inline Eigen::VectorXd residuals(const Correspondences& c, const core::Pose3& X_camera_board, const Intrinsics& k) {
  Eigen::VectorXd r(2 * c.uv_px.size());
  for (size_t i = 0; i < c.uv_px.size(); ++i) {
    const Eigen::Vector2d q = k.project(X_camera_board * Eigen::Vector3d(c.p_board_m[i].x, c.p_board_m[i].y, c.p_board_m[i].z));
    r[2 * i] = q.x() - c.uv_px[i].x;
    r[2 * i + 1] = q.y() - c.uv_px[i].y;
  }
  return r;
}
inline double rms_px(const Correspondences& c, const core::Pose3& X, const Intrinsics& k) {
  const Eigen::VectorXd r = residuals(c, X, k);
  return std::sqrt(r.squaredNorm() / (r.size() / 2));  // per corner (2D distance)
}

/// Least-squares board pose: IPPE's best (planar) solution, refined by
/// Levenberg-Marquardt (SOLVEPNP_ITERATIVE from it). `secondToFirst` gets
/// IPPE's second solution's RMS over its first (planar ambiguity: ~1 means
/// the two mirror poses fit alike).
inline core::Pose3 refit(const Correspondences& c, const Intrinsics& k, double& secondToFirst) {
  std::vector<cv::Mat> rvecs, tvecs;
  cv::Mat errors;
  cv::solvePnPGeneric(c.p_board_m, c.uv_px, k.K(), cv::noArray(), rvecs, tvecs, false, cv::SOLVEPNP_IPPE, cv::noArray(),
                      cv::noArray(), errors);
  core::require(!rvecs.empty(), "board refit: IPPE found no pose (fewer than 4 corners?)");
  secondToFirst = rvecs.size() > 1 ? errors.at<double>(1) / errors.at<double>(0) : 0.0;
  cv::Vec3d rvec(rvecs[0]), tvec(tvecs[0]);
  cv::solvePnP(c.p_board_m, c.uv_px, k.K(), cv::noArray(), rvec, tvec, true, cv::SOLVEPNP_ITERATIVE);
  return fromRvecTvec(rvec, tvec);
}

/// First-order covariance of a least-squares pose, with the corner noise taken
/// from its own residuals: sigma^2 = SSR / (2N - 6), Cov = sigma^2 (J^T J)^-1
/// over the pose's (rvec, tvec); then carried to the point p_board (in the
/// camera frame, metres): Cov_p = J_p Cov J_p^T.
struct PointCovariance {
  double sigma_px = 0;          ///< per-coordinate corner noise from the residuals
  Eigen::Matrix3d cov_m2;       ///< covariance of the point in the camera frame
  double sigmaTotal_mm() const { return std::sqrt(cov_m2.trace()) * 1e3; }
  double sigmaMaxAxis_mm() const {
    return std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov_m2).eigenvalues().maxCoeff()) * 1e3;
  }
};
inline PointCovariance pointCovariance(const Correspondences& c, const core::Pose3& X_camera_board, const Intrinsics& k,
                                       const Eigen::Vector3d& p_board) {
  cv::Vec3d rvec, tvec;
  toRvecTvec(X_camera_board, rvec, tvec);
  std::vector<cv::Point2d> projected;
  cv::Mat jacobian;
  cv::projectPoints(c.p_board_m, rvec, tvec, k.K(), cv::noArray(), projected, jacobian);
  Eigen::MatrixXd J(jacobian.rows, 6);
  for (int r = 0; r < jacobian.rows; ++r)
    for (int col = 0; col < 6; ++col) J(r, col) = jacobian.at<double>(r, col);
  const Eigen::VectorXd res = residuals(c, X_camera_board, k);
  PointCovariance out;
  out.sigma_px = std::sqrt(res.squaredNorm() / double(res.size() - 6));
  const Eigen::Matrix<double, 6, 6> cov = out.sigma_px * out.sigma_px * (J.transpose() * J).inverse();
  // d(R(rvec) p + t)/d(rvec, tvec), the rotation part by central differences.
  Eigen::Matrix<double, 3, 6> Jp = Eigen::Matrix<double, 3, 6>::Zero();
  constexpr double kStep = 1e-6;
  for (int a = 0; a < 3; ++a) {
    cv::Vec3d plus = rvec, minus = rvec;
    plus[a] += kStep;
    minus[a] -= kStep;
    Jp.col(a) = (fromRvecTvec(plus, tvec) * p_board - fromRvecTvec(minus, tvec) * p_board) / (2 * kStep);
  }
  Jp.rightCols<3>() = Eigen::Matrix3d::Identity();
  out.cov_m2 = Jp * cov * Jp.transpose();
  return out;
}

/// The best board pose (least squares on the corners) among those that put
/// the board point p_board at p_camera: rotations about that point, Gauss-Newton
/// from `start` (which must already map p_board to p_camera).
inline core::Pose3 fitWithPointFixed(const Correspondences& c, const Intrinsics& k, const core::Pose3& start,
                                     const Eigen::Vector3d& p_board) {
  const Eigen::Vector3d p_camera = start * p_board;
  auto rotated = [&](const core::Pose3& X, const Eigen::Vector3d& w) {
    core::Pose3 R = core::Pose3::Identity();
    if (w.norm() > 0) R.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
    core::Pose3 Y = X;
    Y.linear() = R.linear() * X.linear();
    Y.translation() = p_camera + R.linear() * (X.translation() - p_camera);
    return Y;
  };
  core::Pose3 X = start;
  for (int it = 0; it < 20; ++it) {
    const Eigen::VectorXd r0 = residuals(c, X, k);
    Eigen::MatrixXd J(r0.size(), 3);
    constexpr double kStep = 1e-7;
    for (int a = 0; a < 3; ++a) {
      Eigen::Vector3d w = Eigen::Vector3d::Zero();
      w[a] = kStep;
      J.col(a) = (residuals(c, rotated(X, w), k) - r0) / kStep;
    }
    const Eigen::Vector3d step = -(J.transpose() * J).ldlt().solve(J.transpose() * r0);
    X = rotated(X, step);
    if (step.norm() < 1e-10) break;
  }
  return X;
}

/// Variance of the Laplacian of the grey image inside the detected tags' quads
/// (a blur indicator: motion blur lowers it).
inline double tagSharpness(const cv::Mat& grey, const std::vector<TagCorners>& tags) {
  cv::Mat mask = cv::Mat::zeros(grey.size(), CV_8U);
  for (const auto& t : tags) {
    std::vector<cv::Point> quad;
    for (const auto& p : t.corners_px) quad.emplace_back(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y())));
    cv::fillConvexPoly(mask, quad, 255);
  }
  cv::Mat lap;
  cv::Laplacian(grey, lap, CV_64F, 3);
  cv::Scalar mean, stddev;
  cv::meanStdDev(lap, mean, stddev, mask);
  return stddev[0] * stddev[0];
}

/// Rows spanned by the detected tags' corners [px] (rolling shutter: the
/// time between the first and the last row read).
inline double rowSpan_px(const std::vector<TagCorners>& tags) {
  double lo = 1e9, hi = -1e9;
  for (const auto& t : tags)
    for (const auto& p : t.corners_px) {
      lo = std::min(lo, p.y());
      hi = std::max(hi, p.y());
    }
  return tags.empty() ? 0.0 : hi - lo;
}

/// Mean image displacement [px] of the board's corner points between two board poses.
inline double imageMotion_px(const Correspondences& c, const core::Pose3& a, const core::Pose3& b, const Intrinsics& k) {
  double sum = 0;
  for (const auto& p : c.p_board_m) {
    const Eigen::Vector3d q(p.x, p.y, p.z);
    sum += (k.project(a * q) - k.project(b * q)).norm();
  }
  return c.p_board_m.empty() ? 0.0 : sum / c.p_board_m.size();
}

}  // namespace srp::notebook::board

namespace srp::notebook::board {

/// Small left-multiplied update of a pose: rotation vector w, translation v.
inline core::Pose3 updated(const core::Pose3& X, const Eigen::Matrix<double, 6, 1>& d) {
  core::Pose3 Y = X;
  const Eigen::Vector3d w = d.head<3>();
  if (w.norm() > 0) Y.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix() * X.linear();
  Y.translation() = X.translation() + d.tail<3>();
  return Y;
}

/// The board's layout calibrated from its own corners (a bundle adjustment):
/// every tag's pose on the board and every frame's board pose, jointly, by
/// Gauss-Newton on the corner reprojection, from the grid layout and the
/// stored board poses. One tag (`fixedId`) keeps its grid pose (the gauge);
/// only tags seen in at least `minViews` of the given frames are calibrated,
/// the others are left out of the returned layout.
inline perception::TagBoardLayout calibrateLayout(const std::vector<std::vector<TagCorners>>& detections,
                                                  const std::vector<core::Pose3>& X_camera_board,
                                                  const std::vector<int>& frames, const perception::TagBoardLayout& grid,
                                                  const std::array<Eigen::Vector3d, 4>& corners_tag_m,
                                                  const Intrinsics& k, int fixedId, int minViews, double& rmsBefore_px,
                                                  double& rmsAfter_px) {
  std::map<int, int> views;
  for (int f : frames)
    for (const auto& t : detections[f]) views[t.id] += grid.X_board_tag.count(t.id) ? 1 : 0;
  core::require(views[fixedId] > 0, "calibrateLayout: the gauge tag " + std::to_string(fixedId) + " is never seen");
  std::map<int, int> tagIndex;  // id -> parameter block (the fixed tag has none)
  perception::TagBoardLayout layout;
  layout.tagSize_m = grid.tagSize_m;
  for (const auto& [id, n] : views)
    if (n >= minViews) {
      layout.X_board_tag[id] = grid.X_board_tag.at(id);
      if (id != fixedId) tagIndex[id] = static_cast<int>(tagIndex.size());
    }
  std::vector<core::Pose3> cams;
  for (int f : frames) cams.push_back(X_camera_board[f]);
  const int nT = static_cast<int>(tagIndex.size()), nF = static_cast<int>(frames.size()), nP = 6 * (nT + nF);
  auto blockResiduals = [&](const core::Pose3& cam, const core::Pose3& tag, const TagCorners& t) {
    Eigen::Matrix<double, 8, 1> r;
    for (int c = 0; c < 4; ++c) r.segment<2>(2 * c) = k.project(cam * (tag * corners_tag_m[c])) - t.corners_px[c];
    return r;
  };
  auto sse = [&]() {
    double s = 0;
    int n = 0;
    for (int fi = 0; fi < nF; ++fi)
      for (const auto& t : detections[frames[fi]])
        if (layout.X_board_tag.count(t.id)) {
          s += blockResiduals(cams[fi], layout.X_board_tag.at(t.id), t).squaredNorm();
          n += 4;
        }
    return std::make_pair(s, n);
  };
  {
    const auto [s, n] = sse();
    rmsBefore_px = std::sqrt(s / n);
  }
  for (int it = 0; it < 15; ++it) {
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(nP, nP);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(nP);
    for (int fi = 0; fi < nF; ++fi)
      for (const auto& t : detections[frames[fi]]) {
        if (!layout.X_board_tag.count(t.id)) continue;
        const core::Pose3& tag = layout.X_board_tag.at(t.id);
        const auto r0 = blockResiduals(cams[fi], tag, t);
        const bool tagFree = tagIndex.count(t.id) > 0;
        Eigen::Matrix<double, 8, 12> J = Eigen::Matrix<double, 8, 12>::Zero();
        constexpr double kStep = 1e-7;
        for (int a = 0; a < 6; ++a) {
          Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
          d[a] = kStep;
          J.col(a) = (blockResiduals(updated(cams[fi], d), tag, t) - r0) / kStep;
          if (tagFree) J.col(6 + a) = (blockResiduals(cams[fi], updated(tag, d), t) - r0) / kStep;
        }
        const int cf = 6 * (nT + fi), ct = tagFree ? 6 * tagIndex.at(t.id) : -1;
        H.block<6, 6>(cf, cf) += J.leftCols<6>().transpose() * J.leftCols<6>();
        g.segment<6>(cf) += J.leftCols<6>().transpose() * r0;
        if (tagFree) {
          H.block<6, 6>(ct, ct) += J.rightCols<6>().transpose() * J.rightCols<6>();
          H.block<6, 6>(cf, ct) += J.leftCols<6>().transpose() * J.rightCols<6>();
          H.block<6, 6>(ct, cf) += J.rightCols<6>().transpose() * J.leftCols<6>();
          g.segment<6>(ct) += J.rightCols<6>().transpose() * r0;
        }
      }
    H.diagonal().array() += 1e-9;  // a tiny damping keeps weakly seen tags solvable
    const Eigen::VectorXd step = -H.ldlt().solve(g);
    for (const auto& [id, b] : tagIndex) layout.X_board_tag[id] = updated(layout.X_board_tag[id], step.segment<6>(6 * b));
    for (int fi = 0; fi < nF; ++fi) cams[fi] = updated(cams[fi], step.segment<6>(6 * (nT + fi)));
    if (step.norm() < 1e-9) break;
  }
  const auto [s, n] = sse();
  rmsAfter_px = std::sqrt(s / n);
  return layout;
}

/// Least-squares board pose for any (not necessarily planar) layout:
/// SOLVEPNP_ITERATIVE (Levenberg-Marquardt) from `start`.
inline core::Pose3 refitFrom(const Correspondences& c, const Intrinsics& k, const core::Pose3& start) {
  cv::Vec3d rvec, tvec;
  toRvecTvec(start, rvec, tvec);
  cv::solvePnP(c.p_board_m, c.uv_px, k.K(), cv::noArray(), rvec, tvec, true, cv::SOLVEPNP_ITERATIVE);
  return fromRvecTvec(rvec, tvec);
}

}  // namespace srp::notebook::board

namespace srp::notebook::board {

/// Leave-one-tag-out spread: the largest distance [m] between the point
/// p_board placed by the all-tag least-squares pose and by each pose fitted
/// without one of the tags (an empirical, tag-level sensitivity that the
/// first-order covariance, which assumes independent corner noise, misses).
inline double leaveOneTagOut_m(const Correspondences& c, const Intrinsics& k, const core::Pose3& X_all,
                               const Eigen::Vector3d& p_board) {
  double worst = 0;
  for (int skip = 0; skip < c.tags; ++skip) {
    Correspondences s;
    for (size_t i = 0; i < c.uv_px.size(); ++i)
      if (static_cast<int>(i / 4) != skip) {
        s.p_board_m.push_back(c.p_board_m[i]);
        s.uv_px.push_back(c.uv_px[i]);
      }
    s.tags = c.tags - 1;
    worst = std::max(worst, (refitFrom(s, k, X_all) * p_board - X_all * p_board).norm());
  }
  return worst;
}

/// A threshold rule "trusted when indicator <= threshold", chosen on the
/// given frames to maximise the balanced accuracy of predicting `good`.
struct ThresholdRule {
  double threshold = 0;
  double balancedAccuracy = 0;
};
inline ThresholdRule chooseThreshold(const std::vector<double>& indicator, const std::vector<bool>& good,
                                     const std::vector<int>& frames) {
  ThresholdRule best;
  for (int cand : frames) {
    const double t = indicator[cand];
    int tp = 0, tn = 0, pos = 0, neg = 0;
    for (int f : frames) {
      (good[f] ? pos : neg) += 1;
      tp += good[f] && indicator[f] <= t;
      tn += !good[f] && indicator[f] > t;
    }
    const double ba = 0.5 * ((pos ? double(tp) / pos : 1.0) + (neg ? double(tn) / neg : 1.0));
    if (ba > best.balancedAccuracy + 1e-12 || (std::abs(ba - best.balancedAccuracy) < 1e-12 && t < best.threshold)) best = {t, ba};
  }
  return best;
}

}  // namespace srp::notebook::board

namespace srp::notebook::board {

/// Rolling shutter: row v is read (v - rows/2) / rows * readout_frames frame
/// intervals after the middle row; the camera then stands at Delta^s X, with
/// Delta = X_camera_board(i) * inverse(X_camera_board(i-1)) the motion over one
/// frame interval (rotation scaled along its axis, translation linearly: small
/// motions). Residuals [px] of the board pose X for that model.
inline Eigen::VectorXd residualsRollingShutter(const Correspondences& c, const core::Pose3& X, const core::Pose3& delta,
                                               double readout_frames, double rows, const Intrinsics& k) {
  const Eigen::AngleAxisd aa(delta.linear());
  Eigen::VectorXd r(2 * c.uv_px.size());
  for (size_t i = 0; i < c.uv_px.size(); ++i) {
    const double s = (c.uv_px[i].y - rows / 2) / rows * readout_frames;
    core::Pose3 D = core::Pose3::Identity();
    D.linear() = Eigen::AngleAxisd(aa.angle() * s, aa.axis()).toRotationMatrix();
    D.translation() = delta.translation() * s;
    const Eigen::Vector2d q = k.project(D * X * Eigen::Vector3d(c.p_board_m[i].x, c.p_board_m[i].y, c.p_board_m[i].z));
    r[2 * i] = q.x() - c.uv_px[i].x;
    r[2 * i + 1] = q.y() - c.uv_px[i].y;
  }
  return r;
}

/// Least-squares board pose under that rolling-shutter model (Gauss-Newton from `start`).
inline core::Pose3 refitRollingShutter(const Correspondences& c, const Intrinsics& k, const core::Pose3& start,
                                       const core::Pose3& delta, double readout_frames, double rows) {
  core::Pose3 X = start;
  for (int it = 0; it < 10; ++it) {
    const Eigen::VectorXd r0 = residualsRollingShutter(c, X, delta, readout_frames, rows, k);
    Eigen::MatrixXd J(r0.size(), 6);
    constexpr double kStep = 1e-7;
    for (int a = 0; a < 6; ++a) {
      Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
      d[a] = kStep;
      J.col(a) = (residualsRollingShutter(c, updated(X, d), delta, readout_frames, rows, k) - r0) / kStep;
    }
    const Eigen::Matrix<double, 6, 1> step = -(J.transpose() * J).ldlt().solve(J.transpose() * r0);
    X = updated(X, step);
    if (step.norm() < 1e-10) break;
  }
  return X;
}

}  // namespace srp::notebook::board
