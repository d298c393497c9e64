#pragma once
/// \file SceneGrounder.h
/// \brief Resolves a noun phrase of an instruction ("the second red cuboid", "the
/// leftmost star", "the cuboid behind the yellow star", "the star closest to the
/// blue box", "the cuboid in the gray box") to exactly one instance of the
/// perceived scene, or throws GroundingError naming the candidates or the reason:
/// `two red cuboids match 'the red cuboid': 'cuboid_a' at (0.040, -0.100) and
/// 'cuboid_b' at (-0.140, -0.060) (world x, y in m); say which`.
///
/// Rules, applied in this order to the scene's instances:
/// 1. Name: the phrase's name is the instance's noun ("box"), class ("blue box"),
///    id ("cuboid_red", '_' read as ' '), or a plural of the noun ("stars");
///    `kind` restricts to parts or containers.
/// 2. Colour: the instance's colour word (its scene "color", else its class'
///    `color_name`, else the basic colour nearest its rgb: the catalogue's red
///    cuboid is "red"); "grey" = "gray".
/// 3. Relations (the phrase's own, e.g. "that is behind the star", and `where`,
///    the step's source locations, e.g. "from the blue box"): each must hold with
///    at least one instance its landmark phrase fits (the landmark is grounded by
///    these same rules, itself excluded). Relations read where the object is now:
///    - in / inside / into / within / at / to / from / out of / off / from inside:
///      a container landmark holds the object's footprint centre inside its walls;
///      a part landmark: as "on";
///    - on / onto / on top of / atop / above / over: the object's footprint centre is
///      over the landmark's footprint and its bottom at least at the landmark's top
///      (minus `onTolerance_m`); under / below / underneath / beneath: the converse;
///    - left of / right of / in front of / behind: the offset of the footprint centres
///      on the table points within 45 degrees of that direction of the view frame
///      (srp/core/ViewFrame.h: by default the demonstrator's view = the camera's image
///      axes on the table; SceneGrounder::Options::viewpoint = Robot for the robot's);
///    - next to / beside / near / adjacent to / close to / alongside / by: the gap
///      between the footprints is at most `nearGap_m`.
///    - closest to / nearest to / farthest from: a superlative, see 4.
/// 4. Superlative: "closest to X" / "farthest from X" take the extreme distance of
///    footprint centres to X (the nearest X if several fit); "leftmost"/"rightmost"
///    along the view's right axis, "frontmost"/"backmost" along its front axis,
///    "closest"/"farthest" alone = frontmost/backmost (nearest to the viewer),
///    "biggest"/"smallest" by bounding-box volume, "highest"/"lowest" by the top
///    of the bounding box. Instances within `tieTolerance_m` (or 10 % of the volume)
///    of the extreme all stay: an ambiguity.
/// 5. Ordinal: "the first/second/.../last" counts left to right in the view frame
///    (the view's right axis; first = leftmost, last = rightmost); two instances
///    level within `tieTolerance_m` at the counted place are an ambiguity.
/// Frames: world = table frame, z up, metres; positions in messages are world x, y.

#include <optional>
#include <string>
#include <vector>

#include "srp/core/Error.h"
#include "srp/core/ViewFrame.h"
#include "srp/execution/CellDescription.h"
#include "srp/execution/ExecutionPlan.h"

namespace srp::execution {

/// A noun phrase fits no instance or several; `candidates` are the ids of the
/// instances it could mean (empty when none fits).
class GroundingError : public srp::core::InvalidInputError {
 public:
  GroundingError(const std::string& message, std::vector<std::string> candidates)
      : InvalidInputError(message), candidates_(std::move(candidates)) {}
  const std::vector<std::string>& candidates() const { return candidates_; }

 private:
  std::vector<std::string> candidates_;
};

class SceneGrounder {
 public:
  struct Options {
    /// Frame of left/right/front/behind and of ordinals. Demonstrator: the scene
    /// camera (CellDescription::X_world_camera; the robot's view when there is none).
    srp::core::Viewpoint viewpoint = srp::core::Viewpoint::Demonstrator;
    double tieTolerance_m = 0.01;  ///< instances closer than this along an ordering are level
    double nearGap_m = 0.05;       ///< "next to"/"near": largest gap between footprints
    double onTolerance_m = 0.01;   ///< "on": how far the bottom may sit below the landmark's top
  };

  /// Keeps a reference to `scene`: it must outlive the grounder.
  SceneGrounder(const CellDescription& scene, Options options);
  explicit SceneGrounder(const CellDescription& scene) : SceneGrounder(scene, Options{}) {}

  const srp::core::ViewFrame& view() const { return view_; }

  /// The instance `ref` (with the step's source locations `where`) means; throws
  /// GroundingError listing the candidates when none or several fit.
  const CellObject& ground(const ObjectReference& ref, const std::vector<SpatialRelation>& where = {},
                           std::optional<CellObjectKind> kind = std::nullopt) const;

  /// Every instance fitting the whole description (rules 1-5), in scene order;
  /// empty when none fits. For plural landmarks ("between the stars").
  std::vector<const CellObject*> candidates(const ObjectReference& ref, const std::vector<SpatialRelation>& where = {},
                                            std::optional<CellObjectKind> kind = std::nullopt) const;

  /// True when the locative `relation` (rule 3 words) holds between `object` and
  /// `landmark` now; throws InvalidInputError for a relation word it does not know.
  bool holds(const std::string& relation, const CellObject& object, const CellObject& landmark) const;

  /// "'cuboid_red' at (0.040, -0.100)": how messages name an instance.
  static std::string describeInstance(const CellObject& object);

 private:
  struct Selection {
    std::vector<const CellObject*> objects;
    std::string whyNone;  ///< set when `objects` is empty
  };
  Selection select(const ObjectReference& ref, const std::vector<SpatialRelation>& where,
                   std::optional<CellObjectKind> kind) const;

  const CellDescription& scene_;
  Options options_;
  srp::core::ViewFrame view_;
};

/// Grounds every step of `plan` in `scene` before anything moves (`srp execute
/// --instruction`): the object (with its source locations) and each target
/// landmark ("between A and B": each exactly one; a plural "between the stars" at least one; the rest exactly one,
/// of any kind). Returns one message per failing step,
/// "step 2 ('the cuboid'): two cuboids match ...". A later step whose phrase may
/// name an instance an earlier step moves (same name) is left to the executor,
/// which grounds it again in the scene as it is then.
std::vector<std::string> groundingProblems(const ExecutionPlan& plan, const CellDescription& scene,
                                           const SceneGrounder::Options& options = {});

}  // namespace srp::execution
