#pragma once
/// \file PerceptionRows.h
/// \brief The Environment module's output (libs/perception) as task-database
/// rows (HandPositions, GroundedProducts, ProductPose; libs/taskdb Rows.h),
/// made by the programming module's store stage: perception itself knows
/// nothing of the database.

#include <map>
#include <string>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/perception/DemoPerception.h"
#include "srp/taskdb/Rows.h"

namespace srp::programming {

struct PerceptionRows {
  std::vector<taskdb::HandPositionRow> handPositions;
  std::vector<taskdb::GroundedProductRow> groundedProducts;
  std::vector<taskdb::ProductPoseRow> productPoses;
};

/// The perception key (perception::PlanObject::key) of a GroundedProducts
/// row: its InstanceId, else its ObjectName (the class's one instance).
std::string perceptionKey(const taskdb::GroundedProductRow& row);

/// One HandPositions row per frame (TimeId = frame index; frames without a
/// detection carry the previous position forward, before the first one the
/// first, with detected = false); one GroundedProducts row per object seen
/// (colour from the catalogue; source/target locations are the programming
/// module's to fill); one ProductPose row per object and frame (skill flags
/// false: the motion module sets them). Camera frame, metres. Rows of an
/// object tracked per instance carry its InstanceId (ObjectTrajectory::
/// instanceId) and the colour word `instanceColours` gives it (instance id ->
/// word), else the catalogue's. Throws InvalidInputError when the hand has no
/// valid sample.
PerceptionRows toTaskDbRows(const perception::PerceptionResult& result, const core::ObjectCatalogue& catalogue,
                            const std::map<std::string, std::string>& instanceColours = {});

}  // namespace srp::programming
