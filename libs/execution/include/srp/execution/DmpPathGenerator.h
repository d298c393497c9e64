#pragma once
/// \file DmpPathGenerator.h
/// \brief Reach and Move paths from the task model's learned DMPs (thesis fig. 7.11,
/// lines 14-25; srp::motion): Reach = the object's Reach DMP re-targeted from the
/// current tool position to the pre-grasp, Move = its Move DMP re-targeted from the
/// post-grasp to the pre-release.
///
/// The DMPs were learned in the demo's frame (the camera's): start and goal are
/// transformed into it with X_world_demo (= X_world_base * X_base_camera of the task
/// model, or the scene's camera), the DMP is rolled out there and the positions are
/// transformed back to the world (table) frame. The tool orientation turns from the
/// start's to the goal's along the same minimum-jerk time law as the fallback.
/// Duration: the longer of the demo's and the one the minimum-jerk generator would
/// give the chord (its mean speeds), so a long re-targeted path is not rushed.
/// The path starts and ends at rest (start and goal velocities 0).
///
/// Ends: the tool and a carried part must leave and enter a container vertically (the
/// demo's hand, and so its DMP, approaches diagonally, which would sweep the part or
/// the tool through a container wall): the tcp first rises straight to `endHeight_m`
/// (world z, 0.12 m by default: a part's bottom clears the 6 cm walls; `srp execute`
/// raises it so that the tallest part carried clears the tallest wall), the DMP runs
/// from there to above the goal (pre-grasp / pre-release), and a straight descent ends
/// the path (minimum-jerk segments). Both Reach and Move.
///
/// An object without a learned DMP for the skill gets the minimum-jerk fallback
/// (sourceFor() says which). The path is not clipped: the SafetyChecker refuses a
/// DMP path that leaves the workspace or comes near the table.

#include <map>
#include <optional>
#include <string>

#include "srp/execution/CartesianPathGenerator.h"
#include "srp/execution/MinimumJerkPathGenerator.h"
#include "srp/motion/Dmp.h"
#include "srp/taskdb/TaskModel.h"

namespace srp::execution {

/// The learned Reach and Move position DMPs of one object (either may be missing).
struct LearnedPathSkills {
  std::optional<srp::motion::Dmp> reach;
  std::optional<srp::motion::Dmp> move;
};

class DmpPathGenerator : public CartesianPathGenerator {
 public:
  /// Default tcp height [m, world z] of the DMP's ends (see the class comment).
  static constexpr double kDefaultEndHeight_m = 0.12;

  /// `skillsByObject`: learned DMPs by object (scene) name, in the frame `X_world_demo`.
  /// `endHeight_m`: the DMP runs between the start and the goal raised vertically
  /// to this tcp height (0: exactly between them). `moveEndHeight_m`: the same for
  /// Move, where the tool carries a part (default: `endHeight_m`).
  DmpPathGenerator(std::map<std::string, LearnedPathSkills> skillsByObject, const srp::core::Pose3& X_world_demo,
                   MinimumJerkPathGenerator::Options fallback = {}, double endHeight_m = kDefaultEndHeight_m,
                   std::optional<double> moveEndHeight_m = std::nullopt);

  /// The Reach and Move rows of the task model's Skills table (parameters "dmp",
  /// "frame"; object names from GroundedProducts). Without Skills rows every path
  /// is the fall-back's; a row that is there must be usable. Throws
  /// InvalidInputError naming the row, the object and the task model when a row
  /// has no DMP (`Parameters='{}'`, "dmp": null), a malformed one, a demonstrated
  /// segment longer than 600 s, or a frame other than "camera".
  /// `endHeight_m`, `moveEndHeight_m` as in the constructor.
  static DmpPathGenerator fromTaskModel(const srp::taskdb::TaskModel& model, const srp::core::Pose3& X_world_camera,
                                        MinimumJerkPathGenerator::Options fallback = {},
                                        double endHeight_m = kDefaultEndHeight_m,
                                        std::optional<double> moveEndHeight_m = std::nullopt);

  CartesianPath generate(srp::core::SkillType skill, const std::string& object,
                         const srp::core::Pose3& X_world_start, const srp::core::Pose3& X_world_goal,
                         double dt_s) const override;
  /// "dmp" when any object has a learned skill, else "minimum-jerk".
  std::string name() const override;
  std::string sourceFor(srp::core::SkillType skill, const std::string& object) const override;

  bool hasSkills() const { return !skills_.empty(); }

 private:
  CartesianPath rollout(const srp::motion::Dmp& learned, const std::string& object,
                        const srp::core::Pose3& X_world_start, const srp::core::Pose3& X_world_goal, double dt_s) const;
  const srp::motion::Dmp* find(srp::core::SkillType skill, const std::string& object) const;
  std::map<std::string, LearnedPathSkills> skills_;
  srp::core::Pose3 X_world_demo_;
  MinimumJerkPathGenerator fallback_;
  double endHeight_m_ = kDefaultEndHeight_m;
  double moveEndHeight_m_ = kDefaultEndHeight_m;
};

}  // namespace srp::execution
