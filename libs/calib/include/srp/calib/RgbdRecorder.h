#pragma once
/// \file RgbdRecorder.h
/// \brief Records an RGB-D camera (OpenNI2 devices: Asus Xtion, PrimeSense,
/// Orbbec Astra, Kinect v1 with the OpenNI2 driver) to a rawlog through MRPT's
/// mrpt::hwdrivers::COpenNI2Sensor and srp::rawlog::RawlogWriter.

#include <functional>
#include <string>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/Error.h"

namespace srp::calib {

/// No RGB-D camera is connected (or the requested one is not there). An
/// expected situation on machines without a camera: apps print the message
/// and suggest `srp import` instead.
class NoCameraError : public srp::core::Error {
 public:
  using Error::Error;
};

struct RecordOptions {
  int deviceIndex = 0;          ///< which OpenNI2 device, from 0
  int maxFrames = 0;            ///< stop after this many frames (0: no limit)
  double duration_s = 10.0;     ///< stop after this long (0: no limit; one limit is needed)
  double depthUnit_m = 1e-3;    ///< depth step stored in the rawlog (OpenNI2 gives millimetres)
  std::function<void(int frames, double elapsed_s)> progress;
};

struct RecordSummary {
  int frames = 0;
  double duration_s = 0.0;
  srp::core::CameraIntrinsics intrinsics;  ///< of the recorded (depth) camera
};

/// Number of OpenNI2 devices connected now (0 when the OpenNI2 runtime finds none).
int countOpenNI2Devices();

/// Records until a limit is reached. Frames are the depth camera's view:
/// depth = range image, colour = the RGB image (resized to the depth size when
/// the sizes differ), intrinsics = depth camera's (as RawlogReader reads
/// MRPT grabber logs). The output file is only created once the camera
/// delivers. Throws NoCameraError when no device is present, InvalidInputError
/// for bad options, core::Error on a hardware error during capture.
RecordSummary recordOpenNI2(const std::string& rawlogPath, const RecordOptions& options);

}  // namespace srp::calib
