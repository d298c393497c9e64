#include "srp/synth/HandModel.h"

#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "srp/core/Error.h"
#include "srp/kb/ShapeMeshes.h"

namespace srp::synth {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Finger layout: lateral offset y of the knuckle [m], proximal and distal lengths [m].
struct FingerSpec {
  double y_m, proximal_m, distal_m;
};
constexpr std::array<FingerSpec, 4> kFingers = {{{0.030, 0.045, 0.034},    // index
                                                 {0.010, 0.050, 0.036},    // middle
                                                 {-0.010, 0.047, 0.034},   // ring
                                                 {-0.030, 0.038, 0.028}}};  // little
constexpr double kPalmHalfLength_m = 0.045, kPalmHalfWidth_m = 0.042, kPalmHalfThickness_m = HandModel::kPalmBackHeight_m;  // 2 mm below the tag plate (no depth fighting)
constexpr double kForearmPitch_rad = 15.0 * kDeg;  // forearm rises towards the elbow

srp::core::Pose3 translation(double x, double y, double z) {
  srp::core::Pose3 X = srp::core::Pose3::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}
srp::core::Pose3 rotY(double a) {
  srp::core::Pose3 X = srp::core::Pose3::Identity();
  X.linear() = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return X;
}
srp::core::Pose3 rotZ(double a) {
  srp::core::Pose3 X = srp::core::Pose3::Identity();
  X.linear() = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return X;
}

HandPart boxPart(const std::string& name, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                 const Eigen::Vector3d& rgb) {
  HandPart p;
  p.name = name;
  p.mesh_part = srp::kb::makeBoxMesh(lo, hi);
  p.triangleRgb.assign(p.mesh_part.size(), rgb);
  p.bounds_part = p.mesh_part.bounds();
  return p;
}

// A block [0, |to - from|] x [-width/2, width/2] x [z0, z0 + height] along `from` -> `to` in the
// part's xy plane, in one colour: a piece of wire or a patch of tape on a part's face.
void addBlock(HandPart& part, const Eigen::Vector2d& from, const Eigen::Vector2d& to, double width, double z0,
              double height, const Eigen::Vector3d& rgb) {
  const Eigen::Vector2d d = to - from;
  const double length = d.norm();
  if (length <= 0.0) return;
  const srp::kb::TriangleMesh block =
      srp::kb::makeBoxMesh({0.0, -0.5 * width, z0}, {length, 0.5 * width, z0 + height})
          .transformed(translation(from.x(), from.y(), 0.0) * rotZ(std::atan2(d.y(), d.x())));
  part.mesh_part.append(block);
  part.triangleRgb.insert(part.triangleRgb.end(), block.size(), rgb);
}

// A wire along a polyline on a face at height `back` of the part, in pieces of at most 4 mm; pieces
// whose middle lies inside `hidden` (the tag plate's footprint) are left out (the wire runs under it).
void addWire(HandPart& part, const std::vector<Eigen::Vector2d>& path, double back,
             const HandModel::SensorWires& w, const Eigen::AlignedBox2d& hidden = Eigen::AlignedBox2d()) {
  constexpr double kPiece_m = 0.004, kEmbed_m = 1e-4;  // sunk a little into the skin: no gap at an edge
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const int n = std::max(1, static_cast<int>(std::ceil((path[i + 1] - path[i]).norm() / kPiece_m)));
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector2d a = path[i] + (path[i + 1] - path[i]) * (static_cast<double>(k) / n);
      const Eigen::Vector2d b = path[i] + (path[i + 1] - path[i]) * (static_cast<double>(k + 1) / n);
      if (!hidden.isEmpty() && hidden.contains(0.5 * (a + b))) continue;
      addBlock(part, a, b, w.wireDiameter_m, back - kEmbed_m, w.wireDiameter_m + kEmbed_m, w.wireRgb);
    }
  }
}

// A square tape patch centred at `centre` on a face at height `back`, at most `maxWidth` across x.
void addTape(HandPart& part, const Eigen::Vector2d& centre, double back, double maxWidth,
             const HandModel::SensorWires& w) {
  const double half = 0.5 * w.tapeSize_m;
  addBlock(part, centre - Eigen::Vector2d(half, 0.0), centre + Eigen::Vector2d(half, 0.0),
           std::min(w.tapeSize_m, maxWidth), back - 1e-4, w.tapeThickness_m + 1e-4, w.tapeRgb);
}

std::vector<std::vector<bool>> tag36h11Cells(int id) {
  apriltag_family_t* family = tag36h11_create();
  if (id < 0 || id >= static_cast<int>(family->ncodes)) {
    const int n = static_cast<int>(family->ncodes);
    tag36h11_destroy(family);
    throw srp::core::InvalidInputError("HandModel: tag id " + std::to_string(id) + " is not a tag36h11 id (0.." +
                                       std::to_string(n - 1) + ")");
  }
  image_u8_t* image = apriltag_to_image(family, id);
  std::vector<std::vector<bool>> cells(image->height, std::vector<bool>(image->width));
  for (int r = 0; r < image->height; ++r)
    for (int c = 0; c < image->width; ++c) cells[r][c] = image->buf[r * image->stride + c] < 128;
  // image_u8_destroy is not exported by Debian's libapriltag; it frees exactly these two blocks.
  std::free(image->buf);
  std::free(image);
  tag36h11_destroy(family);
  return cells;
}

}  // namespace

HandModel::HandModel(const HandModel::Options& options) : options_(options) {
  srp::core::require(options.tagSize_m > 0.0 && options.tagSize_m <= 0.06,
                     "HandModel: tagSize_m must be in (0, 0.06] m to fit on the back of the hand");
  tagCells_ = tag36h11Cells(options.tagId);
  const Eigen::Vector3d skin = options.skinRgb;
  parts_.push_back(boxPart("palm", {-kPalmHalfLength_m, -kPalmHalfWidth_m, -kPalmHalfThickness_m},
                           {kPalmHalfLength_m, kPalmHalfWidth_m, kPalmHalfThickness_m}, skin));
  // The wrist is thinner than the palm and starts behind the tag plate, so that
  // it never rises over the plate (it is pitched up towards the elbow).
  parts_.push_back(boxPart("wrist", {-0.11, -0.031, -0.018}, {-0.012, 0.031, 0.018}, skin));
  parts_.push_back(boxPart("sleeve", {-0.45, -0.038, -0.03}, {-0.1, 0.038, 0.03}, options.sleeveRgb));
  for (std::size_t i = 0; i < kFingers.size(); ++i) {
    const auto& f = kFingers[i];
    parts_.push_back(boxPart("finger" + std::to_string(i) + "_proximal", {-0.004, -0.0085, -0.0075},
                             {f.proximal_m, 0.0085, 0.0075}, skin));
    parts_.push_back(boxPart("finger" + std::to_string(i) + "_distal", {-0.003, -0.008, -0.007},
                             {f.distal_m, 0.008, 0.007}, skin));
  }
  parts_.push_back(boxPart("thumb_proximal", {-0.005, -0.010, -0.009}, {0.042, 0.010, 0.009}, skin));
  parts_.push_back(boxPart("thumb_distal", {-0.003, -0.009, -0.008}, {0.032, 0.009, 0.008}, skin));

  // Tag plate: one quad per cell (white border included), in the hand frame's
  // xy plane seen from +z; tag row r grows along -y_hand, column c along +x_hand.
  HandPart tag;
  tag.name = "tag";
  const int n = static_cast<int>(tagCells_.size());
  const double cell = options.tagSize_m / (n - 2);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      const double x0 = (c - 0.5 * n) * cell, x1 = x0 + cell;
      const double yTag0 = (r - 0.5 * n) * cell, yTag1 = yTag0 + cell;
      const double y0 = -yTag1, y1 = -yTag0;
      tag.mesh_part.addQuad({x0, y0, 0.0}, {x1, y0, 0.0}, {x1, y1, 0.0}, {x0, y1, 0.0});
      const Eigen::Vector3d rgb = tagCells_[r][c] ? Eigen::Vector3d(0.02, 0.02, 0.02) : Eigen::Vector3d(0.97, 0.97, 0.97);
      tag.triangleRgb.push_back(rgb);
      tag.triangleRgb.push_back(rgb);
    }
  tag.bounds_part = tag.mesh_part.bounds();
  parts_.push_back(tag);
  if (options.sensorWires.enabled) dressWithSensorWires();
}

void HandModel::dressWithSensorWires() {
  const SensorWires& w = options_.sensorWires;
  srp::core::require(w.wireDiameter_m > 0.0 && w.wireDiameter_m <= 0.004,
                     "HandModel: sensorWires.wireDiameter_m must be in (0, 0.004] m");
  srp::core::require(w.tapeSize_m > 0.0 && w.tapeSize_m <= 0.016,
                     "HandModel: sensorWires.tapeSize_m must be in (0, 0.016] m to fit on a finger segment");
  srp::core::require(w.tapeThickness_m > 0.0 && w.tapeThickness_m <= 0.003,
                     "HandModel: sensorWires.tapeThickness_m must be in (0, 0.003] m");
  srp::core::require(w.wristBandWidth_m >= 0.0 && w.wristBandWidth_m <= 0.05,
                     "HandModel: sensorWires.wristBandWidth_m must be in [0, 0.05] m");
  auto part = [&](const std::string& name) -> HandPart& {
    for (auto& p : parts_)
      if (p.name == name) return p;
    throw srp::core::InvalidInputError("HandModel: no part '" + name + "'");
  };
  // One digit: a wire along the back of both segments (boxes from x = -start to the length, back
  // face at half the thickness), the sensor's tape near the tip of the distal one.
  struct Digit {
    std::string name;
    double proximalStart_m, proximal_m, proximalBack_m, distalStart_m, distal_m, distalBack_m, distalWidth_m;
  };
  std::vector<Digit> digits;
  for (std::size_t i = 0; i < kFingers.size(); ++i)
    digits.push_back({"finger" + std::to_string(i), 0.004, kFingers[i].proximal_m, 0.0075, 0.003,
                      kFingers[i].distal_m, 0.007, 0.016});
  digits.push_back({"thumb", 0.005, 0.042, 0.009, 0.003, 0.032, 0.008, 0.018});
  for (const auto& d : digits) {
    addWire(part(d.name + "_proximal"), {{-d.proximalStart_m, 0.0}, {d.proximal_m, 0.0}}, d.proximalBack_m, w);
    HandPart& distal = part(d.name + "_distal");
    const double tapeCentre_m = d.distal_m - 0.002 - 0.5 * w.tapeSize_m;  // its far edge 2 mm from the tip
    addWire(distal, {{-d.distalStart_m, 0.0}, {tapeCentre_m - 0.5 * w.tapeSize_m, 0.0}}, d.distalBack_m, w);
    addTape(distal, {tapeCentre_m, 0.0}, d.distalBack_m, d.distalWidth_m, w);
  }
  // The back of the hand: the five wires from the knuckles and the thumb's base converge on the
  // wrist end of the palm; a sixth sensor between the plate and the ring and little knuckles, its
  // wire down the little-finger edge. Pieces under the tag plate are left out.
  HandPart& palm = part("palm");
  const double plate = tagPlateHalfSize_m();
  const Eigen::AlignedBox2d underPlate(Eigen::Vector2d(-plate, -plate), Eigen::Vector2d(plate, plate));
  const double end = -kPalmHalfLength_m;
  constexpr std::array<double, 4> kWristY_m = {0.009, 0.003, -0.003, -0.009};
  for (std::size_t i = 0; i < kFingers.size(); ++i)
    addWire(palm, {{kPalmHalfLength_m, kFingers[i].y_m}, {end, kWristY_m[i]}}, kPalmBackHeight_m, w, underPlate);
  addWire(palm, {{0.0, kPalmHalfWidth_m - 0.002}, {end, 0.015}}, kPalmBackHeight_m, w, underPlate);
  const Eigen::Vector2d sensor(0.5 * (plate + kPalmHalfLength_m), -0.020);
  addTape(palm, sensor, kPalmBackHeight_m, w.tapeSize_m, w);
  const double edgeY_m = -(kPalmHalfWidth_m - 0.004);
  addWire(palm,
          {sensor - Eigen::Vector2d(0.0, 0.5 * w.tapeSize_m), {sensor.x() - 0.004, edgeY_m}, {end + 0.006, edgeY_m},
           {end, -0.015}},
          kPalmBackHeight_m, w, underPlate);
  // The band round the wrist right behind the palm (the wrist's box starts at x = -0.012 in its frame).
  if (w.wristBandWidth_m > 0.0) {
    HandPart& wrist = part("wrist");
    const double t = w.tapeThickness_m;
    const srp::kb::TriangleMesh band =
        srp::kb::makeBoxMesh({-0.013 - w.wristBandWidth_m, -0.031 - t, -0.018 - t}, {-0.013, 0.031 + t, 0.018 + t});
    wrist.mesh_part.append(band);
    wrist.triangleRgb.insert(wrist.triangleRgb.end(), band.size(), w.tapeRgb);
  }
  for (auto& p : parts_) p.bounds_part = p.mesh_part.bounds();
}

std::vector<srp::core::Pose3> HandModel::partPoses(double grip) const {
  const double g = std::clamp(grip, 0.0, 1.0);
  std::vector<srp::core::Pose3> poses;
  poses.reserve(parts_.size());
  poses.push_back(srp::core::Pose3::Identity());                                      // palm
  const srp::core::Pose3 X_hand_wrist = translation(-kPalmHalfLength_m + 0.01, 0, 0) * rotY(kForearmPitch_rad);
  poses.push_back(X_hand_wrist);                                                      // wrist
  poses.push_back(X_hand_wrist);                                                      // sleeve
  for (const auto& f : kFingers) {
    const srp::core::Pose3 X_hand_proximal = translation(kPalmHalfLength_m, f.y_m, -0.002) * rotY((12.0 + 38.0 * g) * kDeg);
    poses.push_back(X_hand_proximal);
    poses.push_back(X_hand_proximal * translation(f.proximal_m, 0, 0) * rotY((12.0 + 48.0 * g) * kDeg));
  }
  const srp::core::Pose3 X_hand_thumb =
      translation(-0.005, kPalmHalfWidth_m - 0.004, -0.006) * rotZ(50.0 * kDeg) * rotY((28.0 + 18.0 * g) * kDeg);
  poses.push_back(X_hand_thumb);
  poses.push_back(X_hand_thumb * translation(0.042, 0, 0) * rotZ(-25.0 * kDeg) * rotY((10.0 + 30.0 * g) * kDeg));
  poses.push_back(translation(0, 0, kTagHeight_m));                                    // tag plate
  return poses;
}

srp::core::Pose3 HandModel::X_hand_tag() const {
  srp::core::Pose3 X = translation(0, 0, kTagHeight_m);
  X.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
  return X;
}

std::array<Eigen::Vector3d, 4> HandModel::tagCorners_tag() const {
  const double h = 0.5 * options_.tagSize_m;
  return {Eigen::Vector3d(-h, -h, 0), Eigen::Vector3d(h, -h, 0), Eigen::Vector3d(h, h, 0), Eigen::Vector3d(-h, h, 0)};
}

}  // namespace srp::synth
