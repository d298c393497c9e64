#include "srp/programming/PerceptionRows.h"

#include "srp/core/Error.h"

namespace srp::programming {

std::string perceptionKey(const taskdb::GroundedProductRow& row) {
  return row.instanceId.empty() ? row.objectName : row.instanceId;
}

PerceptionRows toTaskDbRows(const perception::PerceptionResult& result, const core::ObjectCatalogue& catalogue,
                            const std::map<std::string, std::string>& instanceColours) {
  PerceptionRows rows;
  const auto& samples = result.hand.samples();
  std::size_t first = 0;
  while (first < samples.size() && !samples[first].valid) ++first;
  if (first == samples.size())
    throw core::InvalidInputError("perception result has no detected hand sample: nothing to write to HandPositions");
  Eigen::Vector3d carried = samples[first].p_m;
  for (const auto& s : samples) {
    if (s.valid) carried = s.p_m;
    rows.handPositions.push_back({s.frame, carried, s.valid});
  }
  for (const auto& o : result.objects) {
    if (o.samples.empty()) continue;
    taskdb::GroundedProductRow g;
    g.classId = o.classId;
    g.objectName = o.className;
    g.instanceId = o.instanceId;
    if (const auto c = instanceColours.find(o.instanceId); !o.instanceId.empty() && c != instanceColours.end())
      g.colour = c->second;
    else if (const auto* cls = catalogue.find(o.className); cls && !cls->colourName.empty())
      g.colour = cls->colourName;
    rows.groundedProducts.push_back(g);
    for (const auto& s : o.samples) {
      taskdb::ProductPoseRow p;
      p.classId = o.classId;
      p.timeId = s.frame;
      p.p_m = s.X_camera_object.translation();
      p.q = Eigen::Quaterniond(s.X_camera_object.linear()).normalized();
      p.detected = s.detected;
      p.confidence = s.confidence;
      p.instanceId = o.instanceId;
      rows.productPoses.push_back(p);
    }
  }
  return rows;
}

}  // namespace srp::programming
