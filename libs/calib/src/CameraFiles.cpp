#include "srp/calib/CameraFiles.h"

#include <unistd.h>
#include <visp3/core/vpXmlParserCamera.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <regex>
#include <sstream>

#include "srp/calib/CameraYaml.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/OutputFile.h"

namespace srp::calib {

namespace {

/// vpXmlParserCamera prints "Found camera with name ..." on std::cout: keep
/// the apps' output clean while it parses.
class SilenceStdout {
 public:
  SilenceStdout() : old_(std::cout.rdbuf(sink_.rdbuf())) {}
  ~SilenceStdout() { std::cout.rdbuf(old_); }

 private:
  std::ostringstream sink_;
  std::streambuf* old_;
};

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + ("'" + x + "'");
  return s;
}

}  // namespace

std::vector<std::string> cameraNamesInXml(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw core::FileError(path, "cannot open camera XML (does it exist? make one with 'srp calibrate')");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  std::vector<std::string> names;
  const std::regex cameraBlock(R"(<camera>[\s\S]*?<name>\s*([^<]*?)\s*</name>)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), cameraBlock); it != std::sregex_iterator(); ++it)
    names.push_back((*it)[1]);
  if (names.empty())
    throw core::FileError(path, "no <camera> with a <name> in this file (is it a ViSP camera XML file?)");
  return names;
}

CameraCalibration loadCameraXml(const std::string& path, const std::string& cameraName) {
  const auto names = cameraNamesInXml(path);
  const std::string name = cameraName.empty() ? names.front() : cameraName;
  if (std::find(names.begin(), names.end(), name) == names.end())
    throw core::FileError(path, "no camera named '" + name + "' (the file has " + joined(names) + ")");
  vpXmlParserCamera parser;
  vpCameraParameters cam;
  bool ok = false;
  try {
    SilenceStdout quiet;
    ok = parser.parse(cam, path, name, vpCameraParameters::perspectiveProjWithDistortion) ==
         vpXmlParserCamera::SEQUENCE_OK;
    if (!ok)
      ok = parser.parse(cam, path, name, vpCameraParameters::perspectiveProjWithoutDistortion) ==
           vpXmlParserCamera::SEQUENCE_OK;
  } catch (const vpException& e) {
    // ViSP refuses a px of 0 (also what it makes of "abc") with a bare "Camera parameter px = 0".
    throw core::FileError(path, "camera '" + name + "': px, py, u0, v0 must be numbers, px and py positive [px] (ViSP: " +
                                    e.getStringMessage() + ")");
  }
  if (!ok)
    throw core::FileError(path, "camera '" + name +
                                    "' has no perspective projection model ViSP can read (px, py, u0, v0 [, kud, kdu])");
  CameraCalibration c;
  c.name = name;
  c.intrinsics = {cam.get_px(), cam.get_py(), cam.get_u0(), cam.get_v0(), static_cast<int>(parser.getWidth()),
                  static_cast<int>(parser.getHeight())};
  if (cam.get_projModel() == vpCameraParameters::perspectiveProjWithDistortion) {
    c.kud = cam.get_kud();
    c.kdu = cam.get_kdu();
  }
  if (c.intrinsics.width_px <= 0 || c.intrinsics.height_px <= 0)
    throw core::FileError(path, "camera '" + name + "' has no image_width/image_height (add them to the XML)");
  c.intrinsics.validate("'" + path + "' camera '" + name + "'");
  return c;
}

void saveCameraXml(const std::string& path, const CameraCalibration& camera, const std::string& comment) {
  camera.intrinsics.validate("camera to save to '" + path + "'");
  const auto& K = camera.intrinsics;
  vpCameraParameters cam;
  if (camera.hasDistortion())
    cam.initPersProjWithDistortion(K.fx_px, K.fy_px, K.cx_px, K.cy_px, camera.kud, camera.kdu);
  else
    cam.initPersProjWithoutDistortion(K.fx_px, K.fy_px, K.cx_px, K.cy_px);
  // vpXmlParserCamera adds to an existing file: it writes a fresh scratch file,
  // whose bytes then replace the target atomically (core::writeFileAtomically).
  const std::string tmp = path + ".srp-xml-" + std::to_string(::getpid()) + ".xml";
  std::error_code ec;
  std::filesystem::remove(tmp, ec);
  vpXmlParserCamera parser;
  int status = vpXmlParserCamera::SEQUENCE_ERROR;
  {
    SilenceStdout quiet;
    status = parser.save(cam, tmp, camera.name, static_cast<unsigned>(K.width_px), static_cast<unsigned>(K.height_px),
                         comment);
  }
  if (status != vpXmlParserCamera::SEQUENCE_OK || !std::filesystem::exists(tmp)) {
    std::filesystem::remove(tmp, ec);
    throw core::FileError(path, "cannot write camera XML (is the folder there and writable?)");
  }
  std::string bytes;
  {
    std::ifstream in(tmp, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::filesystem::remove(tmp, ec);
  core::writeFileAtomically(path, bytes);
}

CameraFile loadCameraFile(const std::string& path) {
  CameraFile out;
  const auto extension = std::filesystem::path(path).extension();
  if (extension == ".xml") {
    out.camera = loadCameraXml(path);
    return out;
  }
  if (extension == ".yaml" || extension == ".yml") {
    out.camera = loadCameraYaml(path);
    return out;
  }
  const nlohmann::json root = core::readJsonFile(path);
  const nlohmann::json& j = root.contains("intrinsics") ? root.at("intrinsics") : root;
  const std::string context = "camera file '" + path + "'";
  try {
    if (j.contains("px")) {  // ViSP RGB-D recording layout (cam.json)
      out.camera.intrinsics = {core::requireField(j, "px", context).get<double>(),
                               core::requireField(j, "py", context).get<double>(),
                               core::requireField(j, "u0", context).get<double>(),
                               core::requireField(j, "v0", context).get<double>(),
                               core::requireField(j, "w", context).get<int>(),
                               core::requireField(j, "h", context).get<int>()};
      if (j.contains("model") && j.at("model").get<std::string>() != "perspectiveProjWithoutDistortion")
        throw core::InvalidInputError(context + ": model '" + j.at("model").get<std::string>() +
                                      "' is not supported here (use a ViSP XML for distortion)");
    } else {
      for (const char* key : {"fx", "fy", "cx", "cy", "width", "height"}) core::requireField(j, key, context);
      out.camera.intrinsics = j.get<core::CameraIntrinsics>();
      if (j.contains("kud")) out.camera.kud = j.at("kud").get<double>();
      if (j.contains("kdu")) out.camera.kdu = j.at("kdu").get<double>();
    }
    for (const auto* owner : {&root, &j})
      for (const char* key : {"depthScale", "depth_scale_m"})
        if (owner->contains(key)) out.depthScale_m = owner->at(key).get<double>();
  } catch (const nlohmann::json::exception& e) {
    throw core::FileError(path, std::string("bad camera JSON: ") + e.what());
  }
  out.camera.intrinsics.validate(context);
  if (out.depthScale_m && !(*out.depthScale_m > 0.0))
    throw core::FileError(path, "depth scale must be positive (metres per depth unit, e.g. 0.001)");
  return out;
}

CameraFileFormat cameraFileFormatFromName(const std::string& name) {
  if (name == "visp") return CameraFileFormat::Visp;
  if (name == "ros") return CameraFileFormat::Ros;
  if (name == "opencv") return CameraFileFormat::OpenCv;
  throw core::InvalidInputError("camera file format '" + name + "' is not one of visp, ros, opencv");
}

std::string defaultCameraFileName(CameraFileFormat format) {
  switch (format) {
    case CameraFileFormat::Visp:
      return "camera.xml";
    case CameraFileFormat::Ros:
      return "camera_info.yaml";
    case CameraFileFormat::OpenCv:
      return "camera_opencv.yaml";
  }
  return "camera.xml";
}

void saveCameraFile(const std::string& path, const CameraCalibration& camera, CameraFileFormat format,
                    const std::string& comment, double rms_px) {
  camera.intrinsics.validate("camera to save to '" + path + "'");
  switch (format) {
    case CameraFileFormat::Visp:
      saveCameraXml(path, camera, comment);
      return;
    case CameraFileFormat::Ros:
      core::writeFileAtomically(path, (comment.empty() ? "" : "# " + comment + "\n") + cameraInfoYaml(camera));
      return;
    case CameraFileFormat::OpenCv:
      core::writeFileAtomically(path, openCvYaml(camera, comment, rms_px));
      return;
  }
}

}  // namespace srp::calib
