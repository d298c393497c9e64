#pragma once
/// \file CalibrationPattern.h
/// \brief Planar calibration targets: chessboard, symmetric and asymmetric
/// circle grids, and an AprilTag board; parsing of their command-line spec,
/// detection in an image, and drawing of the printable board.

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace srp::calib {

/// The 2D-3D correspondences found in one image.
struct PatternObservation {
  std::vector<cv::Point2f> imagePoints_px;   ///< detected points, image pixels
  std::vector<cv::Point3f> objectPoints_m;   ///< the same points in the board frame [m] (z = 0)
};

/// A planar target. Board frame: origin at the first point (chessboard: the
/// first inner corner; circles: the first centre; AprilTag board: the centre
/// of the first tag), x along a row, y along a column, z = 0 on the board, metres.
///
/// Spec strings (`--pattern`):
/// - `chessboard:COLSxROWS:SQUARE_m`      inner corners, e.g. chessboard:9x6:0.025
/// - `circles:COLSxROWS:SPACING_m`        symmetric grid of circle centres
/// - `acircles:COLSxROWS:SPACING_m`       asymmetric grid in OpenCV's layout: point
///   (row i, col j) at ((2 j + i mod 2) SPACING, i SPACING), so SPACING is half the
///   distance between neighbouring centres of a row
/// - `apriltag:COLSxROWS:TAG_m:GAP_m[:FIRST_ID]` tag36h11 tags, ids from FIRST_ID
///   (default 0) row by row, TAG_m the black square's side, GAP_m the white space
///   between neighbouring tags; tags drawn as renderBoard draws them (OpenCV's
///   aruco::drawMarker of DICT_APRILTAG_36h11), detected with ViSP's
///   vpDetectorAprilTag. Partly visible boards are used (>= 2 tags).
class CalibrationPattern {
 public:
  enum class Kind { Chessboard, Circles, AsymmetricCircles, AprilTagBoard };

  /// Parses a spec string; throws InvalidInputError naming it and the expected form.
  static CalibrationPattern parse(const std::string& spec);

  Kind kind() const { return kind_; }
  int cols() const { return cols_; }
  int rows() const { return rows_; }
  double spacing_m() const { return spacing_m_; }
  const std::string& spec() const { return spec_; }

  /// All points of the board in the board frame [m] (AprilTag board: 4 corners per tag).
  std::vector<cv::Point3f> objectPoints() const;

  /// Finds the pattern in an 8-bit grey image (sub-pixel corners); nullopt when
  /// it is not (fully, for grids) visible.
  std::optional<PatternObservation> detect(const cv::Mat& grey8) const;

  /// Draws the detection on a BGR image (OpenCV's coloured corner chain, or tag outlines).
  void draw(cv::Mat& bgr8, const PatternObservation& obs) const;

  /// A printable image of the board at `pixelsPerMetre`, with a white margin of
  /// `margin_m`. Board point (x, y) [m] is at pixel
  /// (origin_px.x + x * pixelsPerMetre, origin_px.y + y * pixelsPerMetre).
  struct BoardImage {
    cv::Mat grey8;
    cv::Point2d origin_px;
    double pixelsPerMetre = 0.0;
  };
  /// Throws InvalidInputError when the image would have more than kMaxBoardPixels.
  BoardImage renderBoard(double pixelsPerMetre, double margin_m) const;

  /// Bounds of a pattern spec (parse() refuses larger) and of a board image.
  static constexpr int kMaxSide = 200;               ///< points (or tags) per row and column
  static constexpr double kMaxSpacing_m = 1.0;       ///< square, spacing, tag and gap [m]
  static constexpr double kMaxBoardPixels = 200e6;   ///< renderBoard(): 200 MP (an A0 sheet at 600 dpi is 65 MP)

 private:
  Kind kind_ = Kind::Chessboard;
  int cols_ = 0, rows_ = 0;
  double spacing_m_ = 0.0;  ///< square / circle spacing / tag size
  double gap_m_ = 0.0;      ///< AprilTag board only
  int firstId_ = 0;         ///< AprilTag board only
  std::string spec_;
};

}  // namespace srp::calib
