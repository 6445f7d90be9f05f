#pragma once
// Estimator specs as `vkrt converge --estimator` takes them: which global-mode
// estimator, hemisphere sampling and next-event estimation to render with, in one
// word. paper[:H], path[:H] (next-event estimation off) and path+nee[:H], where H is
// angles, uniform or cosine; without :H the estimator's default (paper: angles,
// path: cosine), as the scene loader has it.
#include <string>

#include "scene/scene.hpp"

namespace vkrt {

struct EstimatorSpec {
    Estimator estimator = Estimator::Path;
    Hemisphere hemisphere = Hemisphere::Cosine;
    bool nee = false;

    // The full spelling, e.g. "path+nee:cosine": one name per setting, for CSV rows.
    std::string label() const;
    // Sets the scene's render.estimator, .hemisphere and .nee.
    void apply(RenderSettings& render) const;
};

// Throws std::invalid_argument with a one-line message for anything else.
EstimatorSpec parse_estimator_spec(const std::string& text);

// The spec the scene's own settings amount to.
EstimatorSpec estimator_spec_of(const RenderSettings& render);

}  // namespace vkrt
