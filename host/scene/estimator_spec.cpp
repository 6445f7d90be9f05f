#include "scene/estimator_spec.hpp"

#include <stdexcept>

#include <fmt/format.h>

namespace vkrt {
namespace {

const char* hemisphere_name(Hemisphere h) {
    switch (h) {
    case Hemisphere::Angles: return "angles";
    case Hemisphere::Uniform: return "uniform";
    case Hemisphere::Cosine: return "cosine";
    }
    return "?";
}

// The spec before its @sampler.
EstimatorSpec parse_estimator_without_sampler(const std::string& text) {
    const std::size_t colon = text.find(':');
    const std::string base = text.substr(0, colon);
    EstimatorSpec spec;
    if (base == "paper") {
        spec = {Estimator::Paper, Hemisphere::Angles, false};
    } else if (base == "path") {
        spec = {Estimator::Path, Hemisphere::Cosine, false};
    } else if (base == "path+nee") {
        spec = {Estimator::Path, Hemisphere::Cosine, true};
    } else if (base == "paper+nee") {
        throw std::invalid_argument(fmt::format(
            "'{}': the paper estimator has no next-event estimation (use path+nee)", text));
    } else {
        throw std::invalid_argument(fmt::format(
            "unknown estimator '{}' (expected paper, path or path+nee, each optionally with :angles, :uniform or "
            ":cosine and @sobol or @hash, e.g. path:uniform@hash)",
            text));
    }
    if (colon != std::string::npos) {
        const std::string h = text.substr(colon + 1);
        if (h == "angles") spec.hemisphere = Hemisphere::Angles;
        else if (h == "uniform") spec.hemisphere = Hemisphere::Uniform;
        else if (h == "cosine") spec.hemisphere = Hemisphere::Cosine;
        else {
            throw std::invalid_argument(fmt::format(
                "'{}': unknown hemisphere sampling '{}' (expected angles, uniform or cosine)", text, h));
        }
    }
    return spec;
}

}  // namespace

const char* sampler_name(Sampler sampler) {
    return sampler == Sampler::Sobol ? "sobol" : "hash";
}

std::optional<Sampler> parse_sampler(std::string_view name) {
    if (name == "sobol") return Sampler::Sobol;
    if (name == "hash") return Sampler::Hash;
    return std::nullopt;
}

std::string EstimatorSpec::label() const {
    const char* base = estimator == Estimator::Paper ? "paper" : nee ? "path+nee" : "path";
    return fmt::format("{}:{}@{}", base, hemisphere_name(hemisphere), sampler_name(sampler));
}

void EstimatorSpec::apply(RenderSettings& render) const {
    render.estimator = estimator;
    render.hemisphere = hemisphere;
    render.nee = nee;
    render.sampler = sampler;
}

EstimatorSpec parse_estimator_spec(const std::string& spelled) {
    const std::size_t at = spelled.find('@');
    const std::string text = spelled.substr(0, at);
    std::optional<Sampler> sampler = Sampler::Sobol;
    if (at != std::string::npos) {
        sampler = parse_sampler(std::string_view(spelled).substr(at + 1));
        if (!sampler) {
            throw std::invalid_argument(fmt::format("'{}': unknown sampler '{}' (expected sobol or hash)", spelled,
                                                    spelled.substr(at + 1)));
        }
    }
    EstimatorSpec spec = parse_estimator_without_sampler(text);
    spec.sampler = *sampler;
    return spec;
}

EstimatorSpec estimator_spec_of(const RenderSettings& render) {
    return {render.estimator, render.hemisphere, render.estimator == Estimator::Path && render.nee, render.sampler};
}

}  // namespace vkrt
