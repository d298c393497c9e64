#pragma once
/// \file ObservationToFrame.h
/// \brief Conversion of one MRPT RGB-D observation to an srp RgbdFrame, shared
/// by RawlogReader and live grabbers (srp record). The MRPT type is only
/// declared here; callers that have one include its MRPT header themselves.

#include "srp/rawlog/RgbdFrame.h"

namespace mrpt::obs {
class CObservation3DRangeScan;
}

namespace srp::rawlog {

/// Depth = rangeImage x rangeUnits [m]; colour = the intensity image (grey
/// converted to BGR, resized to the depth size when the sizes differ; empty
/// when there is none); intrinsics of the depth camera. The observation must
/// be loaded (obs.load()) and have a range image.
RgbdFrame frameFromObservation(const mrpt::obs::CObservation3DRangeScan& obs, int index);

}  // namespace srp::rawlog
