#pragma once
// Private: the ridge coefficient that minimises the generalised cross-validation
// error of a forcing-term fit (Golub, Heath & Wahba 1979), found with NLopt.
#include "ForcingBasis.h"

namespace srp::motion::detail {

struct LambdaChoice {
  double lambda = 0.0;
  double gcv = 0.0;
};

LambdaChoice chooseLambdaByGcv(const RidgeSolver& solver, double lambdaMin, double lambdaMax);

}  // namespace srp::motion::detail
