#pragma once
// Estimator specs as `vkrt converge --estimator` takes them: which global-mode
// estimator, hemisphere sampling and next-event estimation to render with, in one
// word. paper[:H][@S], path[:H][@S] (next-event estimation off) and path+nee[:H][@S],
// where H is angles, uniform or cosine and S is sobol or hash; without :H the
// estimator's default (paper: angles, path: cosine), as the scene loader has it,
// without @S the default sampler, sobol.
#include <optional>
#include <string>
#include <string_view>

#include "scene/scene.hpp"

namespace vkrt {

struct EstimatorSpec {
    Estimator estimator = Estimator::Path;
    Hemisphere hemisphere = Hemisphere::Cosine;
    bool nee = false;
    Sampler sampler = Sampler::Sobol;

    // The full spelling, e.g. "path+nee:cosine@sobol": one name per setting, for CSV rows.
    std::string label() const;
    // Sets the scene's render.estimator, .hemisphere, .nee and .sampler.
    void apply(RenderSettings& render) const;
};

// render.sampler's names: "sobol", "hash".
const char* sampler_name(Sampler sampler);
std::optional<Sampler> parse_sampler(std::string_view name);

// Throws std::invalid_argument with a one-line message for anything else.
EstimatorSpec parse_estimator_spec(const std::string& text);

// The spec the scene's own settings amount to.
EstimatorSpec estimator_spec_of(const RenderSettings& render);

}  // namespace vkrt
