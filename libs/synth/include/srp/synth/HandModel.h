#pragma once
/// \file HandModel.h
/// \brief The synthetic demonstrator: an articulated right hand and forearm
/// with an AprilTag (tag36h11) on the back of the glove.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "srp/core/Pose.h"
#include "srp/kb/TriangleMesh.h"

namespace srp::synth {

/// One rigid piece of the hand (palm, finger segment, forearm, tag), its mesh
/// in the part's own frame with one colour (linear RGB) per triangle.
struct HandPart {
  std::string name;
  srp::kb::TriangleMesh mesh_part;
  std::vector<Eigen::Vector3d> triangleRgb;
  Eigen::AlignedBox3d bounds_part;  ///< for image masks
};

/// A right hand, palm down, built from boxes: palm, four two-segment fingers,
/// a two-segment thumb, wrist and sleeve, and the tag plate; optionally dressed
/// with sensor wires and tape (Options::sensorWires).
///
/// Hand frame (`hand`): origin at the palm centre, x towards the fingers, z out
/// of the back of the hand (up when the palm faces the table), y = z × x
/// (towards the thumb). Metres.
///
/// Tag frame (`tag`, as AprilTag and ViSP): origin at the tag centre, x right
/// and y down as the tag is read, z into the palm; `X_hand_tag()` places it on
/// the back of the hand. Its corners are returned top-left, top-right,
/// bottom-right, bottom-left in tag coordinates (±size/2).
///
/// `grip` in [0, 1] flexes the fingers from relaxed (0) to closed (1).
class HandModel {
 public:
  /// Sensor wires and tape on the skin: the dressing of a glove-less hand-pose sensor rig (small
  /// tracking sensors taped to the fingertips and the back of the hand, each with its thin cable led
  /// along the back of the finger and the hand to a band of tape at the wrist, where the cables are
  /// bundled). Off by default: the hand is then exactly the clean one (same parts, triangles and
  /// colours). On, every digit carries one wire (a square section of wireDiameter_m) on the back of
  /// its proximal and distal segments, ending under a tape patch (tapeSize_m square, tapeThickness_m
  /// thick: a sensor under it) on the back of the distal segment; the palm's back carries the five
  /// wires from the knuckles and the thumb's base to the wrist end of the palm (they run under the
  /// tag plate where it covers them) and a sixth sensor's patch and wire near the wrist on the
  /// little-finger side; the wrist carries a band of tape wristBandWidth_m wide right behind the palm.
  /// Wires this thin (1.5-3 mm) are below a depth camera's resolution at arm's length; the tape lies
  /// flat on the skin. Linear RGB colours, metres; all of it part of the palm, finger, thumb and
  /// wrist parts' meshes (no new parts, same poses).
  struct SensorWires {
    bool enabled = false;
    double wireDiameter_m = 0.002;  ///< (0, 0.004]
    Eigen::Vector3d wireRgb = Eigen::Vector3d(0.05, 0.05, 0.06);  ///< dark insulation
    double tapeSize_m = 0.012;       ///< side of a sensor's patch, (0, 0.016] (a finger segment is 16-17 mm wide)
    double tapeThickness_m = 0.001;  ///< patches and the wrist band stand this far off the skin, (0, 0.003]
    Eigen::Vector3d tapeRgb = Eigen::Vector3d(0.92, 0.92, 0.88);  ///< white medical tape
    double wristBandWidth_m = 0.018;  ///< along the forearm, [0, 0.05]; 0: no band
  };

  /// The hand's tag and colours.
  struct Options {
    int tagId = 0;               ///< tag36h11 id reserved for the demonstrator's hand
    double tagSize_m = 0.05;     ///< side of the tag's black square (AprilTag convention)
    Eigen::Vector3d skinRgb = Eigen::Vector3d(0.87, 0.64, 0.52);
    Eigen::Vector3d sleeveRgb = Eigen::Vector3d(0.22, 0.27, 0.42);
    SensorWires sensorWires;     ///< off: the clean hand
  };

  HandModel() : HandModel(Options{}) {}
  explicit HandModel(const Options& options);

  const std::vector<HandPart>& parts() const { return parts_; }
  /// X_hand_part of every part (same order as parts()) for a grip in [0, 1].
  std::vector<srp::core::Pose3> partPoses(double grip) const;

  srp::core::Pose3 X_hand_tag() const;
  std::array<Eigen::Vector3d, 4> tagCorners_tag() const;
  /// Half side of the tag plate (black square plus its one-cell white margin) [m].
  double tagPlateHalfSize_m() const { return 0.5 * options_.tagSize_m * static_cast<double>(tagCells_.size()) / (tagCells_.size() - 2.0); }
  const Options& options() const { return options_; }
  /// The tag's cells (including the white border) as read: row-major,
  /// true = black. 10 x 10 for tag36h11.
  const std::vector<std::vector<bool>>& tagCells() const { return tagCells_; }

  /// Height of the tag plate above the palm centre [m].
  static constexpr double kTagHeight_m = 0.0136;
  /// Height of the back of the palm above the palm centre (the top of the palm's box) [m].
  static constexpr double kPalmBackHeight_m = 0.0115;

 private:
  /// Adds Options::sensorWires to the parts' meshes (throws InvalidInputError naming a bad size).
  void dressWithSensorWires();

  Options options_;
  std::vector<HandPart> parts_;
  std::vector<std::vector<bool>> tagCells_;
};

}  // namespace srp::synth
