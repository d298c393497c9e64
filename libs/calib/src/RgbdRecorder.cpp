#include "srp/calib/RgbdRecorder.h"

#include <mrpt/hwdrivers/COpenNI2Generic.h>
#include <mrpt/hwdrivers/COpenNI2Sensor.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <chrono>
#include <memory>
#include <thread>

#include "srp/rawlog/ObservationToFrame.h"
#include "srp/rawlog/RawlogWriter.h"

namespace srp::calib {

namespace {
const char* const kNoCameraHelp =
    "plug in an OpenNI2 RGB-D camera (Asus Xtion, PrimeSense, Orbbec Astra), check it shows in 'lsusb' and that "
    "you may access it (udev rules), or convert recorded images with 'srp import FOLDER OUT.rawlog'";
}

int countOpenNI2Devices() {
  // COpenNI2Generic, not COpenNI2Sensor: the sensor's destructor throws (and
  // terminates the program) when no device was opened.
  try {
    mrpt::hwdrivers::COpenNI2Generic openni;
    return std::max(0, openni.getConnectedDevices());
  } catch (const std::exception&) {
    return 0;  // the OpenNI2 runtime failed to start: no usable device either
  }
}

RecordSummary recordOpenNI2(const std::string& rawlogPath, const RecordOptions& options) {
  if (options.maxFrames <= 0 && options.duration_s <= 0.0)
    throw core::InvalidInputError("record: give a frame limit or a duration (or both)");
  if (options.deviceIndex < 0) throw core::InvalidInputError("record: device index must be >= 0");
  const int devices = countOpenNI2Devices();
  if (devices <= 0) throw NoCameraError(std::string("no RGB-D camera found (OpenNI2 sees no device); ") + kNoCameraHelp);
  if (options.deviceIndex >= devices)
    throw NoCameraError("no RGB-D camera number " + std::to_string(options.deviceIndex) + ": OpenNI2 sees " +
                        std::to_string(devices) + " device(s), numbered from 0");
  auto sensor = std::make_unique<mrpt::hwdrivers::COpenNI2Sensor>();
  sensor->setSensorIDToOpen(static_cast<unsigned>(options.deviceIndex));
  sensor->enableGrabRGB(true);
  sensor->enableGrabDepth(true);
  sensor->enableGrab3DPoints(false);
  try {
    sensor->initialize();
  } catch (const std::exception& e) {
    // Leaked on purpose: ~COpenNI2Sensor throws when its device is not open.
    (void)sensor.release();
    throw NoCameraError(std::string("the RGB-D camera could not be opened: ") + e.what());
  }

  RecordSummary summary;
  std::unique_ptr<rawlog::RawlogWriter> writer;
  const auto start = std::chrono::steady_clock::now();
  double firstTime_s = 0.0;
  int idleLoops = 0;
  while (true) {
    const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if ((options.duration_s > 0.0 && elapsed_s >= options.duration_s) ||
        (options.maxFrames > 0 && summary.frames >= options.maxFrames))
      break;
    mrpt::obs::CObservation3DRangeScan obs;
    bool haveObs = false, hardwareError = false;
    sensor->getNextObservation(obs, haveObs, hardwareError);
    if (hardwareError) throw core::Error("RGB-D camera: hardware error after " + std::to_string(summary.frames) + " frames");
    if (!haveObs || !obs.hasRangeImage) {
      if (++idleLoops > 5000 && summary.frames == 0)
        throw NoCameraError("the RGB-D camera delivers no frames (is it used by another program?)");
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    rawlog::RgbdFrame frame = rawlog::frameFromObservation(obs, summary.frames);
    if (frame.colour_bgr8.empty())  // depth-only device: keep a grey image so frames stay valid
      frame.colour_bgr8 = cv::Mat(frame.depth_m.size(), CV_8UC3, cv::Scalar::all(0));
    if (!writer) {
      writer = std::make_unique<rawlog::RawlogWriter>(rawlogPath, options.depthUnit_m);
      summary.intrinsics = frame.intrinsics;
      firstTime_s = frame.t_s;
    }
    writer->write(frame);
    ++summary.frames;
    summary.duration_s = frame.t_s - firstTime_s;
    if (options.progress) options.progress(summary.frames, elapsed_s);
  }
  if (writer) writer->close();
  return summary;
}

}  // namespace srp::calib
