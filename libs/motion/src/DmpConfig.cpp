#include "srp/motion/DmpConfig.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "srp/core/Error.h"
#include "srp/core/Json.h"

namespace srp::motion {

void DmpConfig::validate() const {
  using core::require;
  require(basisCount >= 2, "DmpConfig.basisCount must be >= 2 (got " + std::to_string(basisCount) + ")");
  require(alpha_y > 0 && beta_y > 0 && std::isfinite(alpha_y) && std::isfinite(beta_y),
          "DmpConfig.alpha_y and beta_y must be positive and finite");
  require(alpha_z > 0 && std::isfinite(alpha_z), "DmpConfig.alpha_z must be positive");
  require(overlap > 0 && overlap < 1, "DmpConfig.overlap must be in (0, 1)");
  if (lambda)
    require(*lambda >= 0 && std::isfinite(*lambda), "DmpConfig.lambda must be >= 0 and finite");
  require(mode == Mode::Default || lambda.has_value(),
          "DmpConfig: Reference mode needs a lambda (the thesis used 0.1)");
  require(mode == Mode::Default || scaling == ForcingScaling::None,
          "DmpConfig: Reference mode has no forcing scaling; use Mode::Default for scaling");
  require(lambdaSearchMin > 0 && lambdaSearchMax > lambdaSearchMin,
          "DmpConfig: need 0 < lambdaSearchMin < lambdaSearchMax");
  require(referenceDt_s > 0, "DmpConfig.referenceDt_s must be positive");
  require(maxStepFraction > 0 && maxStepFraction <= 1, "DmpConfig.maxStepFraction must be in (0, 1]");
}

std::string toString(ForcingScaling s) {
  switch (s) {
    case ForcingScaling::None: return "none";
    case ForcingScaling::PerDimension: return "per_dimension";
    case ForcingScaling::Spatial: return "spatial";
  }
  return "none";
}

ForcingScaling forcingScalingFromString(const std::string& text) {
  if (text == "none") return ForcingScaling::None;
  if (text == "per_dimension") return ForcingScaling::PerDimension;
  if (text == "spatial") return ForcingScaling::Spatial;
  throw core::InvalidInputError("unknown forcing scaling '" + text +
                                "'; use none, per_dimension or spatial");
}

void to_json(nlohmann::json& j, const DmpConfig& c) {
  j = nlohmann::json{{"mode", c.mode == DmpConfig::Mode::Reference ? "reference" : "default"},
                     {"basis_count", c.basisCount},
                     {"alpha_y", c.alpha_y},
                     {"beta_y", c.beta_y},
                     {"alpha_z", c.alpha_z},
                     {"overlap", c.overlap},
                     {"scaling", toString(c.scaling)},
                     {"lambda", c.lambda ? nlohmann::json(*c.lambda) : nlohmann::json(nullptr)},
                     {"lambda_search_min", c.lambdaSearchMin},
                     {"lambda_search_max", c.lambdaSearchMax},
                     {"reference_dt_s", c.referenceDt_s},
                     {"max_step_fraction", c.maxStepFraction}};
}

void from_json(const nlohmann::json& j, DmpConfig& c) {
  const std::string ctx = "DMP config";
  const std::string mode = core::requireField(j, "mode", ctx).get<std::string>();
  if (mode == "reference") c.mode = DmpConfig::Mode::Reference;
  else if (mode == "default") c.mode = DmpConfig::Mode::Default;
  else throw core::InvalidInputError(ctx + ": unknown mode '" + mode + "' (reference or default)");
  c.basisCount = core::requireField(j, "basis_count", ctx).get<int>();
  c.alpha_y = core::requireField(j, "alpha_y", ctx).get<double>();
  c.beta_y = core::requireField(j, "beta_y", ctx).get<double>();
  c.alpha_z = core::requireField(j, "alpha_z", ctx).get<double>();
  c.overlap = core::requireField(j, "overlap", ctx).get<double>();
  c.scaling = forcingScalingFromString(core::requireField(j, "scaling", ctx).get<std::string>());
  const auto& lam = core::requireField(j, "lambda", ctx);
  c.lambda = lam.is_null() ? std::nullopt : std::optional<double>(lam.get<double>());
  c.lambdaSearchMin = core::requireField(j, "lambda_search_min", ctx).get<double>();
  c.lambdaSearchMax = core::requireField(j, "lambda_search_max", ctx).get<double>();
  c.referenceDt_s = core::requireField(j, "reference_dt_s", ctx).get<double>();
  c.maxStepFraction = core::requireField(j, "max_step_fraction", ctx).get<double>();
  c.validate();
}

}  // namespace srp::motion
