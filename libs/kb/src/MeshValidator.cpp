#include "srp/kb/MeshValidator.h"

#include <cmath>
#include <cstdio>

#include "srp/core/Error.h"

namespace srp::kb {
namespace {

std::string metres(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.4g m", v);
  return buffer;
}

}  // namespace

MeshValidator::MeshValidator(Options options) : options_(options) {
  const Options& o = options_;
  if (!(o.minSize_m > 0.0 && o.minSize_m < o.maxSize_m && std::isfinite(o.maxSize_m)) || !(o.minFillRatio >= 0.0))
    throw srp::core::InvalidInputError("MeshValidator: sizes must satisfy 0 < minSize_m < maxSize_m < inf, and "
                                       "minFillRatio >= 0");
}

std::vector<std::string> MeshValidator::check(const TriangleMesh& mesh, const std::string& what) const {
  const Options& o = options_;
  if (mesh.empty()) throw srp::core::InvalidInputError(what + ": the mesh has no triangles");
  for (std::size_t i = 0; i < mesh.size(); ++i)
    for (const auto& v : mesh.triangles()[i])
      if (!v.allFinite())
        throw srp::core::InvalidInputError(what + ": triangle " + std::to_string(i) +
                                           " has a non-finite vertex (NaN or Inf); repair the mesh");
  const Eigen::Vector3d size = mesh.bounds().sizes();
  const double largest = size.maxCoeff();
  if (!(largest <= o.maxSize_m))
    throw srp::core::InvalidInputError(
        what + ": the part is " + metres(largest) + " across, above the " + metres(o.maxSize_m) +
        " a robot cell handles; a file in millimetres needs --units mm (or --scale 0.001), in centimetres --units cm");
  if (!(largest >= o.minSize_m))
    throw srp::core::InvalidInputError(what + ": the part is " + metres(largest) + " across, below " +
                                       metres(o.minSize_m) + "; a file in other units needs --units or --scale");
  const double boxVolume = size.x() * size.y() * size.z();
  const double fill = boxVolume > 0.0 ? std::abs(mesh.volume()) / boxVolume : 0.0;
  if (!o.flat && !(fill >= o.minFillRatio))
    throw srp::core::InvalidInputError(
        what + ": the mesh encloses no volume (" + std::to_string(std::abs(mesh.volume())) + " m^3 in a " +
        metres(size.x()) + " x " + metres(size.y()) + " x " + metres(size.z()) +
        " box): an open or flat surface. Close the mesh, or declare a flat part with --flat");
  std::vector<std::string> warnings;
  if (largest > o.millimetreHint_m)
    warnings.push_back(what + ": the part is " + metres(largest) +
                       " across; if the file is in millimetres, add it again with --units mm");
  return warnings;
}

double unitScale(const std::string& unit) {
  if (unit == "m") return 1.0;
  if (unit == "cm") return 0.01;
  if (unit == "mm") return 0.001;
  if (unit == "in") return 0.0254;
  throw srp::core::InvalidInputError("unknown length unit '" + unit + "'; use m, cm, mm or in");
}

}  // namespace srp::kb
