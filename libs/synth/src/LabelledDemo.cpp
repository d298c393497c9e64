#include "srp/kb/KnowledgeBase.h"
#include "srp/synth/LabelledDemo.h"

#include "srp/core/DefaultScene.h"
#include "srp/core/Pose.h"
#include "srp/synth/DemoTimeline.h"
#include "srp/synth/HandModel.h"
#include "srp/synth/PickPlacePlan.h"

namespace srp::synth {

motion::LabelledDemo cleanLabelledDemo(std::uint32_t seed) {
  const auto scene = core::Scene::load(core::defaultScenePath());
  const auto catalogue = kb::loadCatalogue(scene.cataloguePath);
  const auto steps = groundPlan(synth::defaultPlanJson(), scene, catalogue);
  DemoOptions options;
  options.seed = seed;
  const auto timeline = planDemonstration(scene, catalogue, steps, HandModel{}, options);
  const core::Pose3 X_camera_world = timeline.scene.X_world_camera.inverse();
  motion::LabelledDemo demo;
  demo.hand = core::PositionTrajectory("camera");
  for (const auto& o : timeline.scene.objects) {
    motion::ObjectTrack t;
    t.name = o.id;
    t.positions = core::PositionTrajectory("camera");
    demo.objects.push_back(t);
  }
  for (const auto& f : timeline.frames) {
    const bool inView = f.phase != "idle";
    demo.hand.append({f.index, f.t_s, inView ? Eigen::Vector3d(X_camera_world * f.X_world_hand.translation())
                                             : Eigen::Vector3d::Zero(), inView});
    for (std::size_t j = 0; j < demo.objects.size(); ++j) {
      const core::Pose3 X_camera_object = X_camera_world * f.X_world_objects[j];
      demo.objects[j].positions.append({f.index, f.t_s, X_camera_object.translation(), true});
      demo.objects[j].yaw_rad.push_back(core::yawOf(X_camera_object.linear()));
    }
  }
  for (const auto& e : timeline.events) {
    demo.planOrder.push_back(e.objectId);
    demo.graspIndex.push_back(e.graspFrame);
    demo.releaseIndex.push_back(e.releaseFrame);
  }
  return demo;
}

}  // namespace srp::synth
