#include "srp/taskdb/Rows.h"

#include "srp/core/Pose.h"

namespace srp::taskdb {

bool ProductRow::operator==(const ProductRow& o) const {
  return objectId == o.objectId && objectName == o.objectName && sourceLocationId == o.sourceLocationId &&
         targetLocationId == o.targetLocationId && colour == o.colour && tokenId == o.tokenId &&
         sentenceId == o.sentenceId && classId == o.classId && instanceId == o.instanceId;
}
bool SourceLocationRow::operator==(const SourceLocationRow& o) const {
  return locationId == o.locationId && trajectorObjectId == o.trajectorObjectId && description == o.description;
}
bool TargetLocationRow::operator==(const TargetLocationRow& o) const {
  return locationId == o.locationId && indicatorObjectId == o.indicatorObjectId && description == o.description;
}
bool GroundedProductRow::operator==(const GroundedProductRow& o) const {
  return classId == o.classId && objectName == o.objectName && sourceLocationId == o.sourceLocationId &&
         targetLocationId == o.targetLocationId && colour == o.colour && instanceId == o.instanceId;
}
double ProductPoseRow::yaw_rad() const { return core::yawOf(q.normalized().toRotationMatrix()); }
bool ProductPoseRow::operator==(const ProductPoseRow& o) const {
  return classId == o.classId && timeId == o.timeId && p_m == o.p_m && q.coeffs() == o.q.coeffs() &&
         reach == o.reach && grasp == o.grasp && move == o.move && release == o.release && detected == o.detected &&
         confidence == o.confidence && instanceId == o.instanceId;
}
bool HandPositionRow::operator==(const HandPositionRow& o) const {
  return timeId == o.timeId && p_m == o.p_m && detected == o.detected;
}
bool SkillRow::operator==(const SkillRow& o) const {
  return classId == o.classId && skill == o.skill && startTimeId == o.startTimeId && endTimeId == o.endTimeId &&
         parameters == o.parameters && instanceId == o.instanceId;
}

}  // namespace srp::taskdb
