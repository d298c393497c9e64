#include "srp/rawlog/ObservationToFrame.h"

#include <mrpt/obs/CObservation3DRangeScan.h>

#include <opencv2/imgproc.hpp>

namespace srp::rawlog {

RgbdFrame frameFromObservation(const mrpt::obs::CObservation3DRangeScan& obs, int index) {
  RgbdFrame f;
  f.index = index;
  f.t_s = mrpt::Clock::toDouble(obs.timestamp);
  const auto& cam = obs.cameraParams;
  f.intrinsics = {cam.fx(), cam.fy(), cam.cx(), cam.cy(), static_cast<int>(cam.ncols), static_cast<int>(cam.nrows)};
  const int rows = static_cast<int>(obs.rangeImage.rows());
  const int cols = static_cast<int>(obs.rangeImage.cols());
  if (f.intrinsics.width_px != cols || f.intrinsics.height_px != rows) {
    // Some grabbers leave ncols/nrows unset: trust the image size.
    f.intrinsics.width_px = cols;
    f.intrinsics.height_px = rows;
  }
  f.depth_m = cv::Mat(rows, cols, CV_32FC1);
  const float units = obs.rangeUnits;
  for (int r = 0; r < rows; ++r) {
    float* d = f.depth_m.ptr<float>(r);
    for (int c = 0; c < cols; ++c) d[c] = static_cast<float>(obs.rangeImage(r, c)) * units;
  }
  if (obs.hasIntensityImage && !obs.intensityImage.isEmpty()) {
    cv::Mat img = obs.intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
    cv::Mat bgr;
    if (img.channels() == 1) cv::cvtColor(img, bgr, cv::COLOR_GRAY2BGR);
    else bgr = img.clone();
    if (bgr.cols != cols || bgr.rows != rows) cv::resize(bgr, bgr, cv::Size(cols, rows), 0, 0, cv::INTER_LINEAR);
    f.colour_bgr8 = bgr;
  }
  return f;
}

}  // namespace srp::rawlog
