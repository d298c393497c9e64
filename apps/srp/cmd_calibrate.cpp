// srp calibrate: camera intrinsics from pattern images (ViSP camera XML), and
// camera-to-robot extrinsics from AprilTags or hand-eye pose pairs.
#include <cmath>
#include <filesystem>
#include <optional>
#include <cstdio>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "CommandRegistry.h"
#include "CommonOptions.h"
#include "ProgressLine.h"
#include "srp/calib/CalibrationPattern.h"
#include "srp/calib/CameraExtrinsics.h"
#include "srp/calib/CameraFiles.h"
#include "srp/calib/ImageHeader.h"
#include "srp/calib/IntrinsicCalibrator.h"
#include "srp/core/DataPaths.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/OutputFile.h"
#include "srp/core/Scene.h"

namespace {

using srp::core::Pose3;

struct IntrinsicArgs {
  std::vector<std::string> images;
  std::string pattern;
  std::string out;  ///< empty: defaultCameraFileName(format) in the current folder
  std::string format = "visp";
  std::string name = "Camera";
  std::string drawDir;
  bool noDistortion = false;
  bool json = false;
  bool overwrite = false;
};

struct TagArgs {
  std::string image;
  std::string intrinsics;  ///< empty: the shipped calib/camera.xml
  double tagSize_m = 0.0;
  std::vector<std::string> tags;  // "ID:x,y,z,yaw,pitch,roll"
  std::string frame = "base";
  std::string scene;
  std::string out = "extrinsics.json";
  bool json = false;
  bool overwrite = false;
};

struct HandEyeArgs {
  std::string pairs;
  std::string out = "extrinsics.json";
  bool json = false;
  bool overwrite = false;
};

struct BoardArgs {
  std::string pattern;
  std::string out;
  double dpi = 300.0;
  bool overwrite = false;
};

void runIntrinsics(const IntrinsicArgs& a) {
  if (a.images.empty()) throw srp::core::InvalidInputError("give the calibration images with --images 'calib/*.png'");
  if (a.pattern.empty()) throw srp::core::InvalidInputError("give the pattern with --pattern, e.g. chessboard:9x6:0.025");
  const auto pattern = srp::calib::CalibrationPattern::parse(a.pattern);
  std::vector<std::string> files;
  for (const auto& g : a.images)
    for (const auto& f : srp::calib::expandImageGlob(g)) files.push_back(f);
  std::vector<srp::core::PathRole> inputs;
  for (const auto& f : files) inputs.push_back({"--images", f});
  srp::core::checkOutputPaths({{"--out", a.out}, {"--draw", a.drawDir}}, inputs, a.overwrite);
  std::optional<srp::core::AtomicOutputFolder> drawn;  // put in place when the calibration is done
  if (!a.drawDir.empty()) {
    std::vector<std::string> names;
    for (const auto& f : files) names.push_back(std::filesystem::path(f).stem().string() + ".png");
    srp::core::checkFolderHoldsOnly(a.drawDir, names, "--draw");
    drawn.emplace(std::filesystem::path(a.drawDir).lexically_normal());
  }
  srp::calib::IntrinsicCalibrationOptions options;
  options.estimateDistortion = !a.noDistortion;
  options.cameraName = a.name;
  if (drawn) options.drawDir = drawn->temporaryPath().string();
  auto line = std::make_shared<srp::app::ProgressLine>(srp::app::progressWanted(a.json));
  options.progress = [line](int i, int n, const std::string& name) {
    line->show("calibrate", static_cast<std::size_t>(i + 1), static_cast<std::size_t>(n), name);
    if (i + 1 == n) line->finish();
  };
  const auto format = srp::calib::cameraFileFormatFromName(a.format);
  const std::string out = a.out.empty() ? srp::calib::defaultCameraFileName(format) : a.out;
  const auto r = srp::calib::calibrateIntrinsicsFromFiles(files, pattern, options);
  srp::calib::saveCameraFile(out, r.camera, format,
                             "srp calibrate --pattern " + a.pattern + ": RMS reprojection " + std::to_string(r.rms_px) +
                                 " px over " + std::to_string(r.viewsUsed()) + " images",
                             r.rms_px);
  if (drawn) drawn->commit();
  // Read back what was written: every app reads this file.
  const auto back = format == srp::calib::CameraFileFormat::Visp ? srp::calib::loadCameraXml(out, a.name)
                                                                 : srp::calib::loadCameraFile(out).camera;
  const auto& K = back.intrinsics;
  const auto outliers = r.outlierNames();
  if (a.json) {
    nlohmann::json views = nlohmann::json::array();
    for (const auto& v : r.views)
      views.push_back({{"image", v.name}, {"found", v.found}, {"points", v.points},
                       {"rms_px", v.found ? nlohmann::json(v.rms_px) : nlohmann::json(nullptr)},
                       {"outlier", v.outlier}});
    std::cout << nlohmann::json{{"camera_file", out},
                                {"format", a.format},
                                {"intrinsics", K},
                                {"kud", back.kud},
                                {"kdu", back.kdu},
                                {"rms_px", r.rms_px},
                                {"median_view_rms_px", r.medianViewRms_px},
                                {"outlier_factor", srp::calib::kOutlierViewFactor},
                                {"outliers", outliers},
                                {"views", views}}
                     .dump(2)
              << "\n";
    return;
  }
  for (const auto& v : r.views) {
    if (!v.found) std::printf("  %-50s pattern NOT found (rejected)\n", v.name.c_str());
    else
      std::printf("  %-50s %4d points  RMS %.3f px%s\n", v.name.c_str(), v.points, v.rms_px,
                  v.outlier ? "  OUTLIER" : "");
  }
  std::printf("pattern found in %d of %zu images\n", r.viewsUsed(), r.views.size());
  if (!outliers.empty())
    std::printf("%zu outlier view(s), RMS at least %.0fx the median view's %.3f px: check them (blur, a bent board, a "
                "wrong detection); drop them and calibrate again if the board is not seen right\n",
                outliers.size(), srp::calib::kOutlierViewFactor, r.medianViewRms_px);
  std::printf("intrinsics: %dx%d  px %.3f  py %.3f  u0 %.3f  v0 %.3f  kud %.5f  kdu %.5f\n", K.width_px, K.height_px,
              K.fx_px, K.fy_px, K.cx_px, K.cy_px, back.kud, back.kdu);
  std::printf("total RMS reprojection error: %.3f px\n", r.rms_px);
  std::printf("written to %s (%s, camera '%s')%s\n", out.c_str(), a.format.c_str(), a.name.c_str(),
              a.drawDir.empty() ? "" : (", detections drawn in " + a.drawDir).c_str());
}

Pose3 parseTagPose(const std::string& spec, int& id) {
  const auto colon = spec.find(':');
  double v[6];
  if (colon == std::string::npos ||
      std::sscanf(spec.c_str() + colon + 1, "%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5]) != 6)
    throw srp::core::InvalidInputError("--tag '" + spec + "': expected ID:x,y,z,yaw,pitch,roll (metres, degrees)");
  id = std::stoi(spec.substr(0, colon));
  constexpr double kDeg = M_PI / 180.0;
  return srp::core::makePoseYPR({v[0], v[1], v[2]}, v[3] * kDeg, v[4] * kDeg, v[5] * kDeg);
}

void printExtrinsics(const srp::calib::CameraExtrinsics& e, const std::string& out, bool json) {
  if (json) {
    std::cout << e.toJson().dump(2) << "\n";
    return;
  }
  const Eigen::Vector3d t = e.X_base_camera.translation();
  const Eigen::Vector3d ypr = e.X_base_camera.linear().eulerAngles(2, 1, 0) * 180.0 / M_PI;
  std::printf("X_base_camera: translation [%.4f, %.4f, %.4f] m, yaw/pitch/roll [%.2f, %.2f, %.2f] deg\n", t.x(), t.y(),
              t.z(), ypr.x(), ypr.y(), ypr.z());
  std::printf("method %s, %d samples, residual %.4f %s\nwritten to %s\n", e.method.c_str(), e.samples, e.residual,
              e.residualUnit.c_str(), out.c_str());
}

void runTags(const TagArgs& a) {
  srp::core::checkOutputPaths({{"--out", a.out}},
                              {{"--image", a.image}, {"--intrinsics", a.intrinsics}, {"--scene", a.scene}}, a.overwrite);
  const std::string intrinsics =
      a.intrinsics.empty() ? srp::core::DataPaths::file("calib/camera.xml").string() : a.intrinsics;
  const auto camera = srp::calib::loadCameraFile(intrinsics).camera;
  srp::calib::checkImageFile(a.image);
  const cv::Mat image = cv::imread(a.image, cv::IMREAD_COLOR);
  if (image.empty()) throw srp::core::FileError(a.image, "cannot read this image");
  Pose3 X_base_frame = Pose3::Identity();
  if (a.frame == "world") {
    if (a.scene.empty()) throw srp::core::InvalidInputError("--frame world needs --scene FILE (for X_world_base)");
    X_base_frame = srp::core::Scene::load(a.scene).X_world_base.inverse();
  }
  std::map<int, Pose3> X_base_tag;
  for (const auto& spec : a.tags) {
    int id = 0;
    const Pose3 X_frame_tag = parseTagPose(spec, id);
    X_base_tag[id] = X_base_frame * X_frame_tag;
  }
  auto e = srp::calib::extrinsicsFromTags(image, camera, a.tagSize_m, X_base_tag);
  if (!e) throw srp::core::InvalidInputError("none of the given tags is visible in '" + a.image + "'");
  e->intrinsicsFile = intrinsics;
  e->save(a.out);
  printExtrinsics(*e, a.out, a.json);
}

void runHandEye(const HandEyeArgs& a) {
  srp::core::checkOutputPaths({{"--out", a.out}}, {{"--pairs", a.pairs}}, a.overwrite);
  const auto j = srp::core::readJsonFile(a.pairs);
  std::vector<Pose3> gripper, target;
  const std::string context = "hand-eye pairs '" + a.pairs + "'";
  for (const auto& p : srp::core::requireField(j, "pairs", context)) {
    gripper.push_back(srp::core::poseFromJson(srp::core::requireField(p, "X_base_gripper", context), context));
    target.push_back(srp::core::poseFromJson(srp::core::requireField(p, "X_camera_target", context), context));
  }
  const auto e = srp::calib::extrinsicsFromHandEye(gripper, target);
  e.save(a.out);
  printExtrinsics(e, a.out, a.json);
}

void runBoard(const BoardArgs& a) {
  const auto pattern = srp::calib::CalibrationPattern::parse(a.pattern);
  const double ppm = a.dpi / 0.0254;
  srp::core::checkOutputPaths({{"--out", a.out}}, {}, a.overwrite);
  const auto board = pattern.renderBoard(ppm, 0.01);
  srp::core::AtomicOutputFile out(a.out);
  if (!cv::imwrite(out.temporaryPath().string(), board.grey8))
    throw srp::core::FileError(a.out, "cannot write the board image (give a .png path)");
  out.commit();
  std::printf("board %s: %dx%d px at %.0f dpi (print at 100 %% scale) -> %s\n", a.pattern.c_str(), board.grey8.cols,
              board.grey8.rows, a.dpi, a.out.c_str());
}

void setupCalibrate(CLI::App& cmd) {
  auto intrinsic = std::make_shared<IntrinsicArgs>();
  cmd.footer(
      "Example: srp calibrate --images 'calib/*.png' --pattern chessboard:9x6:0.025 --out camera.xml --draw drawn\n"
      "A view whose RMS is 3x the median view's or more is flagged OUTLIER (JSON \"outlier\").\nPatterns: chessboard:COLSxROWS:SQUARE_m, circles:COLSxROWS:SPACING_m, "
      "acircles:COLSxROWS:SPACING_m, apriltag:COLSxROWS:TAG_m:GAP_m[:FIRST_ID] (see 'srp calibrate board').");
  cmd.add_option("--images", intrinsic->images, "image files or quoted patterns ('calib/*.png')");
  cmd.add_option("--pattern", intrinsic->pattern, "calibration target, e.g. chessboard:9x6:0.025");
  cmd.add_option("-o,--out", intrinsic->out,
                 "camera file to write (default: camera.xml, camera_info.yaml or camera_opencv.yaml in the current "
                 "folder, by --format)");
  cmd.add_option("--format", intrinsic->format,
                 "visp: ViSP camera XML (what srp reads by default); ros: ROS camera_info YAML (plumb_bob); opencv: "
                 "OpenCV FileStorage YAML (camera_matrix, distortion_coefficients). srp reads all three")
      ->check(CLI::IsMember({"visp", "ros", "opencv"}))
      ->capture_default_str();
  cmd.add_option("--name", intrinsic->name, "camera name in the XML")->capture_default_str();
  cmd.add_option("--draw", intrinsic->drawDir, "write one PNG per image with the detected pattern here");
  cmd.add_flag("--no-distortion", intrinsic->noDistortion, "estimate a pinhole model without distortion");
  cmd.add_flag("--json", intrinsic->json, "print the result as JSON");
  srp::app::addOverwriteFlag(cmd, intrinsic->overwrite);
  cmd.require_subcommand(0, 1);

  auto tags = std::make_shared<TagArgs>();
  auto* ext = cmd.add_subcommand("extrinsics", "camera pose in the robot base from AprilTags (tag36h11) at known poses");
  ext->add_option("--image", tags->image, "image showing the tags")->required();
  ext->add_option("--intrinsics", tags->intrinsics,
                  "camera file (ViSP XML, ROS/OpenCV YAML or JSON; default: the shipped calib/camera.xml of srp's data "
                  "folder, the synthetic camera of the default scene)");
  ext->add_option("--tag-size", tags->tagSize_m, "side of the tags' black square [m]")->required();
  ext->add_option("--tag", tags->tags, "ID:x,y,z,yaw,pitch,roll of a tag in --frame (m, deg); repeat for more tags")
      ->required();
  ext->add_option("--frame", tags->frame, "frame of the tag poses: base or world (world needs --scene)")
      ->check(CLI::IsMember({"base", "world"}))
      ->capture_default_str();
  ext->add_option("--scene", tags->scene, "scene file giving X_world_base (for --frame world)");
  ext->add_option("-o,--out", tags->out, "extrinsics JSON to write")->capture_default_str();
  ext->add_flag("--json", tags->json, "print the result as JSON");
  srp::app::addOverwriteFlag(*ext, tags->overwrite);
  ext->footer("Example: srp calibrate extrinsics --image tag.png --tag-size 0.1 --frame world --scene "
              "sim/scenes/default.json --tag 0:0.1,0.1,0,30,0,0");
  ext->callback([tags] { runTags(*tags); });

  auto handEye = std::make_shared<HandEyeArgs>();
  auto* he = cmd.add_subcommand("hand-eye", "camera pose in the robot base from (gripper, target) pose pairs");
  he->add_option("--pairs", handEye->pairs,
                 "JSON {\"pairs\": [{\"X_base_gripper\": pose, \"X_camera_target\": pose}, ...]}")
      ->required();
  he->add_option("-o,--out", handEye->out, "extrinsics JSON to write")->capture_default_str();
  he->add_flag("--json", handEye->json, "print the result as JSON");
  srp::app::addOverwriteFlag(*he, handEye->overwrite);
  he->callback([handEye] { runHandEye(*handEye); });

  auto boardArgs = std::make_shared<BoardArgs>();
  auto* board = cmd.add_subcommand("board", "write a printable image of a calibration pattern");
  board->add_option("--pattern", boardArgs->pattern, "e.g. apriltag:4x3:0.04:0.01 or chessboard:9x6:0.025")->required();
  board->add_option("-o,--out", boardArgs->out, "PNG to write")->required();
  board->add_option("--dpi", boardArgs->dpi, "printer resolution [dots per inch]")
      ->check(CLI::Range(30, 4800))
      ->capture_default_str();
  srp::app::addOverwriteFlag(*board, boardArgs->overwrite);
  board->callback([boardArgs] { runBoard(*boardArgs); });

  cmd.callback([&cmd, intrinsic] {
    if (!cmd.get_subcommands().empty()) return;  // a subcommand did the work
    runIntrinsics(*intrinsic);
  });
}

const srp::app::CommandRegistrar kReg{"calibrate", "Camera intrinsics from pattern images (ViSP XML, ROS or OpenCV YAML) and extrinsics",
                                      10, setupCalibrate};

}  // namespace
