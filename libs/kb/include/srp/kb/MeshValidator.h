#pragma once
/// \file MeshValidator.h
/// \brief What a CAD mesh must be before srp treats it as a part or a
/// container: checked where a mesh enters (`srp kb add`, kb::loadCatalogue for a
/// class given by its mesh alone), so perception, programming and execution
/// only ever see a mesh that fits in a robot's hand.
///
/// Rules (metres, after the class' scale: a file in millimetres is read with
/// scale 0.001, `srp kb add --units mm`):
/// - every vertex finite (TriangleMesh::load refuses NaN and Inf already);
/// - the largest side of the bounding box within [minSize_m, maxSize_m]
///   (1 mm - 2 m: a UR5 reaches 0.85 m and lifts 5 kg);
/// - a volume: the enclosed volume at least minFillRatio of the bounding box's,
///   unless the part is declared flat (a sheet, a label: `--flat`);
/// - a part whose largest side exceeds millimetreHint_m is accepted with a
///   warning: it is probably drawn in millimetres.
///
/// \code
///   srp::kb::MeshValidator::Options rules;
///   rules.flat = entry.flat;
///   for (const std::string& w : srp::kb::MeshValidator(rules).check(mesh, "cube.obj")) std::cerr << w << "\n";
/// \endcode

#include <string>
#include <vector>

#include "srp/kb/TriangleMesh.h"

namespace srp::kb {

class MeshValidator {
 public:
  struct Options {
    double minSize_m = 0.001;       ///< smallest allowed largest side of the bounding box
    double maxSize_m = 2.0;         ///< largest allowed largest side of the bounding box
    double millimetreHint_m = 0.5;  ///< above this, warn that the file may be in millimetres
    double minFillRatio = 1e-3;     ///< |enclosed volume| / bounding-box volume below this: no volume
    bool flat = false;              ///< a flat part: no volume needed
  };

  explicit MeshValidator(Options options);
  MeshValidator() : MeshValidator(Options{}) {}

  /// Throws InvalidInputError naming `what` (the file or the class), the
  /// measured value, the limit and the fix (`--units mm`, `--scale`, `--flat`)
  /// when a rule is broken; returns the warnings (possibly none).
  std::vector<std::string> check(const TriangleMesh& mesh, const std::string& what) const;

  const Options& options() const { return options_; }

 private:
  Options options_;
};

/// The scale factor of a length unit name: "m" 1, "cm" 0.01, "mm" 0.001,
/// "in" 0.0254. Throws InvalidInputError naming the unit otherwise.
double unitScale(const std::string& unit);

}  // namespace srp::kb
