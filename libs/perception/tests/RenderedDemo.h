#pragma once
// The default synthetic demo (srp::synth: default scene, thesis instruction 1,
// default sensor noise) rendered into the build folder with its ground truth,
// for the tests that check perception against the truth.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "srp/core/Scene.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/perception/DemoPerception.h"
#include "srp/synth/DemoGenerator.h"
#include "srp/synth/PickPlacePlan.h"

namespace srp::perception::testing {

struct RenderedDemo {
  std::string rawlog;
  synth::DemoGroundTruth gt;
  core::ObjectCatalogue catalogue;
};

/// Renders `options` (seed: the scene's) to SRP_BINARY_DIR/<test name>_<fileName>, or,
/// when `existingRawlog` is given, loads that demo and its `.gt.json`. The running
/// test's name is part of the file name because CTest runs the tests of one program in
/// parallel processes: a shared name would have one test read a file another is writing.
inline RenderedDemo renderDefaultDemo(const std::string& fileName, synth::SynthDemoOptions options,
                                      const char* existingRawlog = nullptr) {
  const auto scene = core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  RenderedDemo out;
  out.catalogue = kb::loadCatalogue(scene.cataloguePath);
  if (existingRawlog) {
    out.rawlog = existingRawlog;
    out.gt = synth::DemoGroundTruth::load(std::filesystem::path(existingRawlog).replace_extension(".gt.json").string());
    return out;
  }
  options.demo.seed = static_cast<std::uint32_t>(scene.seed);
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string prefix = test ? std::string(test->test_suite_name()) + "." + test->name() + "_" : std::string();
  out.rawlog = (std::filesystem::path(SRP_BINARY_DIR) / (prefix + fileName)).string();
  const auto r = synth::generateSyntheticDemo(scene, out.catalogue, synth::defaultPlanJson(), options, out.rawlog);
  out.gt = synth::DemoGroundTruth::load(r.groundTruthPath);
  return out;
}

/// Perception options for a rendered demo: its glove's tag, and the objects
/// `srp program` grounds for instruction 1 (four parts moving, two boxes static).
inline PerceptionOptions instruction1Options(const synth::DemoGroundTruth& gt) {
  PerceptionOptions o;
  o.marker.tagSize_m = gt.tagSize_m;
  o.marker.tagId = gt.tagId;
  o.marker.p_tag_palm_m = gt.X_hand_tag.inverse().translation();
  o.plan = {{"cuboid", false}, {"star", false}, {"parallelogram", false}, {"octagon", false},
            {"blue box", true}, {"gray box", true}};
  return o;
}

}  // namespace srp::perception::testing
