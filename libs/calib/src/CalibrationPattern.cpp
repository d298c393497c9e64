#include "srp/calib/CalibrationPattern.h"

#include <visp3/core/vpImageConvert.h>
#include <visp3/detection/vpDetectorAprilTag.h>

#include <map>
#include <opencv2/aruco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <regex>

#include "srp/core/Error.h"

namespace srp::calib {

namespace {

/// Offsets of ViSP's four AprilTag corners (getTagsCorners order) from the tag
/// centre, in board coordinates (x right, y down on the printed board) for a
/// tag drawn upright by aruco::drawMarker. Found by detecting drawn tags:
/// corner 0 is top-right, then counter-clockwise on the print.
const cv::Point2f kTagCornerSign[4] = {{+0.5f, -0.5f}, {-0.5f, -0.5f}, {-0.5f, +0.5f}, {+0.5f, +0.5f}};

}  // namespace

CalibrationPattern CalibrationPattern::parse(const std::string& spec) {
  static const std::regex re(R"(^(chessboard|circles|acircles|apriltag):(\d+)x(\d+):([0-9.eE+-]+)(?::([0-9.eE+-]+))?(?::(\d+))?$)");
  std::smatch m;
  const std::string usage =
      "pattern '" + spec +
      "' not understood; expected chessboard:COLSxROWS:SQUARE_m (e.g. chessboard:9x6:0.025), "
      "circles:COLSxROWS:SPACING_m, acircles:COLSxROWS:SPACING_m or apriltag:COLSxROWS:TAG_m:GAP_m[:FIRST_ID]";
  if (!std::regex_match(spec, m, re)) throw core::InvalidInputError(usage);
  CalibrationPattern p;
  p.spec_ = spec;
  const std::string kind = m[1];
  p.kind_ = kind == "chessboard" ? Kind::Chessboard
            : kind == "circles"  ? Kind::Circles
            : kind == "acircles" ? Kind::AsymmetricCircles
                                 : Kind::AprilTagBoard;
  try {
    if (m[2].length() > 4 || m[3].length() > 4 || (m[6].matched && m[6].length() > 6)) throw std::out_of_range("count");
    p.cols_ = std::stoi(m[2]);
    p.rows_ = std::stoi(m[3]);
    p.spacing_m_ = std::stod(m[4]);
    if (m[5].matched) p.gap_m_ = std::stod(m[5]);
    if (m[6].matched) p.firstId_ = std::stoi(m[6]);
  } catch (const std::exception&) {
    throw core::InvalidInputError(usage);
  }
  if (p.kind_ == Kind::AprilTagBoard && !m[5].matched)
    throw core::InvalidInputError("pattern '" + spec + "': an AprilTag board needs TAG_m and GAP_m (apriltag:4x3:0.04:0.01)");
  if (p.kind_ != Kind::AprilTagBoard && (m[5].matched || m[6].matched)) throw core::InvalidInputError(usage);
  const int minSide = p.kind_ == Kind::AprilTagBoard ? 1 : 2;
  if (p.cols_ < minSide || p.rows_ < minSide || !(p.spacing_m_ > 0.0) || p.gap_m_ < 0.0)
    throw core::InvalidInputError("pattern '" + spec + "': sizes must be positive (at least 2x2 points for grids)");
  if (p.cols_ > kMaxSide || p.rows_ > kMaxSide || !(p.spacing_m_ <= kMaxSpacing_m) || !(p.gap_m_ <= kMaxSpacing_m))
    throw core::InvalidInputError("pattern '" + spec + "': at most " + std::to_string(kMaxSide) + " x " +
                                  std::to_string(kMaxSide) + " points, squares and gaps at most " +
                                  std::to_string(kMaxSpacing_m) + " m");
  return p;
}

std::vector<cv::Point3f> CalibrationPattern::objectPoints() const {
  std::vector<cv::Point3f> pts;
  const float s = static_cast<float>(spacing_m_);
  for (int i = 0; i < rows_; ++i)
    for (int j = 0; j < cols_; ++j) {
      switch (kind_) {
        case Kind::Chessboard:
        case Kind::Circles:
          pts.emplace_back(j * s, i * s, 0.0f);
          break;
        case Kind::AsymmetricCircles:
          pts.emplace_back((2 * j + i % 2) * s, i * s, 0.0f);
          break;
        case Kind::AprilTagBoard: {
          const float pitch = static_cast<float>(spacing_m_ + gap_m_);
          for (const auto& c : kTagCornerSign) pts.emplace_back(j * pitch + c.x * s, i * pitch + c.y * s, 0.0f);
          break;
        }
      }
    }
  return pts;
}

std::optional<PatternObservation> CalibrationPattern::detect(const cv::Mat& grey8) const {
  // Not CV_Assert: its __FILE__ would put the build's source path into the installed binary.
  if (grey8.type() != CV_8UC1)
    throw core::InvalidInputError("CalibrationPattern::detect needs an 8-bit single-channel image (CV_8UC1), got type " +
                                  std::to_string(grey8.type()) + "; convert with cv::cvtColor first");
  PatternObservation obs;
  const cv::Size size(cols_, rows_);
  switch (kind_) {
    case Kind::Chessboard: {
      if (!cv::findChessboardCorners(grey8, size, obs.imagePoints_px,
                                     cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
        return std::nullopt;
      cv::cornerSubPix(grey8, obs.imagePoints_px, cv::Size(11, 11), cv::Size(-1, -1),
                       cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-3));
      obs.objectPoints_m = objectPoints();
      return obs;
    }
    case Kind::Circles:
    case Kind::AsymmetricCircles: {
      const int flags = kind_ == Kind::Circles ? cv::CALIB_CB_SYMMETRIC_GRID : cv::CALIB_CB_ASYMMETRIC_GRID;
      if (!cv::findCirclesGrid(grey8, size, obs.imagePoints_px, flags)) return std::nullopt;
      obs.objectPoints_m = objectPoints();
      return obs;
    }
    case Kind::AprilTagBoard: {
      vpImage<unsigned char> I;
      vpImageConvert::convert(grey8, I);
      vpDetectorAprilTag detector(vpDetectorAprilTag::TAG_36h11);
      detector.setAprilTagQuadDecimate(1.0f);
      detector.detect(I);
      const auto ids = detector.getTagsId();
      const auto corners = detector.getTagsCorners();
      const auto all = objectPoints();
      std::map<int, size_t> seen;  // id -> detection (skip ids seen twice: ambiguous)
      for (size_t k = 0; k < ids.size(); ++k) {
        const int index = ids[k] - firstId_;
        if (index < 0 || index >= cols_ * rows_ || corners[k].size() != 4) continue;
        if (seen.count(index)) {
          seen[index] = SIZE_MAX;
          continue;
        }
        seen[index] = k;
      }
      for (const auto& [index, k] : seen) {
        if (k == SIZE_MAX) continue;
        for (int c = 0; c < 4; ++c) {
          obs.imagePoints_px.emplace_back(static_cast<float>(corners[k][c].get_u()),
                                          static_cast<float>(corners[k][c].get_v()));
          obs.objectPoints_m.push_back(all[4 * index + c]);
        }
      }
      if (obs.imagePoints_px.size() < 8) return std::nullopt;
      return obs;
    }
  }
  return std::nullopt;
}

void CalibrationPattern::draw(cv::Mat& bgr8, const PatternObservation& obs) const {
  if (kind_ != Kind::AprilTagBoard) {
    cv::drawChessboardCorners(bgr8, cv::Size(cols_, rows_), obs.imagePoints_px, true);
    return;
  }
  for (size_t k = 0; k + 3 < obs.imagePoints_px.size(); k += 4) {
    for (int c = 0; c < 4; ++c)
      cv::line(bgr8, obs.imagePoints_px[k + c], obs.imagePoints_px[k + (c + 1) % 4], cv::Scalar(0, 255, 0), 1,
               cv::LINE_AA);
    cv::circle(bgr8, obs.imagePoints_px[k], 3, cv::Scalar(0, 0, 255), -1, cv::LINE_AA);
  }
}

CalibrationPattern::BoardImage CalibrationPattern::renderBoard(double ppm, double margin_m) const {
  BoardImage b;
  b.pixelsPerMetre = ppm;
  const double s = spacing_m_;
  // Extent of the board in board coordinates [m].
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  switch (kind_) {
    case Kind::Chessboard:
      x0 = -s, y0 = -s, x1 = cols_ * s, y1 = rows_ * s;
      break;
    case Kind::Circles:
      x0 = -s / 2, y0 = -s / 2, x1 = (cols_ - 0.5) * s, y1 = (rows_ - 0.5) * s;
      break;
    case Kind::AsymmetricCircles:
      x0 = -s / 2, y0 = -s / 2, x1 = (2 * cols_ - 0.5) * s, y1 = (rows_ - 0.5) * s;
      break;
    case Kind::AprilTagBoard: {
      const double pitch = s + gap_m_;
      x0 = -s / 2, y0 = -s / 2, x1 = (cols_ - 1) * pitch + s / 2, y1 = (rows_ - 1) * pitch + s / 2;
      break;
    }
  }
  x0 -= margin_m, y0 -= margin_m, x1 += margin_m, y1 += margin_m;
  const double width_px = std::ceil((x1 - x0) * ppm), height_px = std::ceil((y1 - y0) * ppm);
  if (!(width_px >= 1.0 && height_px >= 1.0 && width_px * height_px <= kMaxBoardPixels))
    throw core::InvalidInputError("the board image would be " + std::to_string(static_cast<long long>(width_px)) +
                                  " x " + std::to_string(static_cast<long long>(height_px)) + " px, above the limit of " +
                                  std::to_string(static_cast<long long>(kMaxBoardPixels / 1e6)) +
                                  " MP; lower --dpi or print a smaller pattern");
  b.origin_px = cv::Point2d(-x0 * ppm, -y0 * ppm);
  b.grey8 = cv::Mat(static_cast<int>(std::ceil((y1 - y0) * ppm)), static_cast<int>(std::ceil((x1 - x0) * ppm)), CV_8UC1,
                    cv::Scalar(255));
  const auto px = [&](double x, double y) { return cv::Point2d(b.origin_px.x + x * ppm, b.origin_px.y + y * ppm); };
  switch (kind_) {
    case Kind::Chessboard:
      // Squares (i, j) for i in [-1, rows), j in [-1, cols); the corner grid lies between them.
      for (int i = -1; i < rows_; ++i)
        for (int j = -1; j < cols_; ++j)
          if (((i + j) & 1) == 0) {
            const cv::Point2d a = px(j * s, i * s), c = px((j + 1) * s, (i + 1) * s);
            cv::rectangle(b.grey8, cv::Rect(cv::Point(cvRound(a.x), cvRound(a.y)), cv::Point(cvRound(c.x), cvRound(c.y))),
                          cv::Scalar(0), cv::FILLED);
          }
      break;
    case Kind::Circles:
    case Kind::AsymmetricCircles: {
      const double radius_m = (kind_ == Kind::Circles ? 0.3 : 0.35) * s;
      constexpr int kShift = 4;  // sub-pixel drawing
      for (const auto& p : objectPoints()) {
        const cv::Point2d c = px(p.x, p.y);
        cv::circle(b.grey8, cv::Point(cvRound(c.x * (1 << kShift)), cvRound(c.y * (1 << kShift))),
                   cvRound(radius_m * ppm * (1 << kShift)), cv::Scalar(0), cv::FILLED, cv::LINE_AA, kShift);
      }
      break;
    }
    case Kind::AprilTagBoard: {
      const auto dict = cv::aruco::getPredefinedDictionary(cv::aruco::DICT_APRILTAG_36h11);
      const int side = cvRound(s * ppm);
      for (int i = 0; i < rows_; ++i)
        for (int j = 0; j < cols_; ++j) {
          cv::Mat tag;
          cv::aruco::drawMarker(dict, firstId_ + i * cols_ + j, side, tag, 1);
          const cv::Point2d tl = px(j * (s + gap_m_) - s / 2, i * (s + gap_m_) - s / 2);
          tag.copyTo(b.grey8(cv::Rect(cvRound(tl.x), cvRound(tl.y), side, side)));
        }
      break;
    }
  }
  return b;
}

}  // namespace srp::calib
