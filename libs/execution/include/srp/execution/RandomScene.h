#pragma once
/// \file RandomScene.h
/// \brief Seeded variations of a cell for the randomised acceptance runs: the
/// containers shifted (+-3 cm) and turned (+-0.2 rad), the parts placed at random
/// non-overlapping poses (any yaw, 1 cm apart) inside the source container.

#include <cstdint>

#include "srp/execution/CellDescription.h"

namespace srp::execution {

/// A randomised copy of `base` (same objects); `sourceContainer` names the
/// container the parts are scattered in. Deterministic for a given seed.
/// Throws InvalidInputError when the container is missing or the parts do not fit.
CellDescription randomizeCell(const CellDescription& base, const std::string& sourceContainer, std::uint32_t seed);

}  // namespace srp::execution
