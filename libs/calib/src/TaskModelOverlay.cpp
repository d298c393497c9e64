#include "srp/calib/TaskModelOverlay.h"

#include <map>
#include <opencv2/imgproc.hpp>

#include "srp/core/Error.h"

namespace srp::calib {

namespace {

cv::Scalar classColour(int classId) {
  static const cv::Scalar palette[] = {{255, 128, 0}, {0, 200, 255}, {0, 0, 255},   {0, 200, 0},
                                       {255, 0, 255}, {255, 255, 0}, {128, 0, 255}, {0, 128, 255}};
  return palette[static_cast<size_t>(std::abs(classId)) % (sizeof palette / sizeof palette[0])];
}

}  // namespace

TaskModelOverlay::TaskModelOverlay(taskdb::TaskModel model, int firstTimeId)
    : model_(std::move(model)), firstTimeId_(firstTimeId) {
  const auto& info = model_.info;
  if (info.frame == "base") {
    if (!info.X_base_camera)
      throw core::InvalidInputError("task model '" + info.name +
                                    "' is in the base frame but has no X_base_camera to draw it in the camera");
    X_camera_model_ = info.X_base_camera->inverse();
  } else if (info.frame != "camera") {
    throw core::InvalidInputError("task model '" + info.name + "': frame '" + info.frame +
                                  "' cannot be drawn (camera or base)");
  }
}

Eigen::Vector3d TaskModelOverlay::toCamera(const Eigen::Vector3d& p) const { return X_camera_model_ * p; }

void TaskModelOverlay::draw(cv::Mat& img, const rawlog::RgbdFrame& frame) const {
  const int timeId = frame.index + firstTimeId_;
  const auto& K = frame.intrinsics;
  const auto pixel = [&](const Eigen::Vector3d& p_model) -> std::optional<cv::Point> {
    const auto uv = K.project(toCamera(p_model));
    if (!uv) return std::nullopt;
    return cv::Point(cvRound(uv->x()), cvRound(uv->y()));
  };
  const auto track = [&](const std::vector<cv::Point>& pts, const cv::Scalar& colour) {
    for (size_t i = 1; i < pts.size(); ++i) cv::line(img, pts[i - 1], pts[i], colour, 2, cv::LINE_AA);
  };

  // Object tracks and current positions.
  std::map<int, std::vector<cv::Point>> tracks;
  std::map<int, const taskdb::ProductPoseRow*> current;
  for (const auto& row : model_.productPoses) {
    if (row.timeId > timeId) continue;
    if (const auto p = pixel(row.p_m)) tracks[row.classId].push_back(*p);
    if (row.timeId == timeId) current[row.classId] = &row;
  }
  for (const auto& [classId, pts] : tracks) track(pts, classColour(classId));

  for (const auto& [classId, row] : current) {
    const auto p = pixel(row->p_m);
    if (!p) continue;
    const cv::Scalar colour = classColour(classId);
    cv::circle(img, *p, 7, colour, row->detected ? cv::FILLED : 2, cv::LINE_AA);
    std::string label;
    if (const auto* g = model_.findGrounded(classId)) label = g->objectName;
    else label = "class " + std::to_string(classId);
    for (const auto& s : model_.skills)
      if (s.classId == classId && s.startTimeId <= timeId && timeId <= s.endTimeId)
        label += ": " + core::toString(s.skill);
    cv::putText(img, label, *p + cv::Point(10, -8), cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
    cv::putText(img, label, *p + cv::Point(10, -8), cv::FONT_HERSHEY_SIMPLEX, 0.5, colour, 1, cv::LINE_AA);
  }

  // Hand track and current hand.
  std::vector<cv::Point> hand;
  std::optional<cv::Point> handNow;
  bool handDetected = false;
  for (const auto& row : model_.handPositions) {
    if (row.timeId > timeId) continue;
    const auto p = pixel(row.p_m);
    if (!p) continue;
    hand.push_back(*p);
    if (row.timeId == timeId) {
      handNow = *p;
      handDetected = row.detected;
    }
  }
  track(hand, cv::Scalar(255, 255, 255));
  if (handNow) cv::circle(img, *handNow, 6, cv::Scalar(255, 255, 255), handDetected ? cv::FILLED : 2, cv::LINE_AA);

  const std::string header = model_.info.name + " v" + std::to_string(model_.info.version) + "  frame " +
                             std::to_string(frame.index) + " (TimeId " + std::to_string(timeId) + ")";
  cv::putText(img, header, {8, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
  cv::putText(img, header, {8, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
}

}  // namespace srp::calib
