#pragma once
// The metallic-roughness BSDF of shaders/kernel/bsdf.glsl and lobes/ written
// again in double, from the papers rather than from the kernel, for the tests to hold
// the kernel against: GGX's distribution (Walter et al. 2007), Smith's Lambda and
// height-correlated G2 (Heitz 2014), Schlick's Fresnel, and the diffuse coupling of
// Shirley, Hu, Smits and Lafortune (1997).
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace vkrt::test::ggx {

inline constexpr double kPi = 3.14159265358979323846;

inline double pow5(double x) { return x * x * x * x * x; }

// D(h) for cos(theta_h) = c.
inline double d(double c, double alpha) {
    const double a2 = alpha * alpha;
    const double k = (a2 - 1.0) * c * c + 1.0;
    return a2 / (kPi * k * k);
}

// Lambda for a direction at cos(theta) = c.
inline double lambda(double c, double alpha) {
    const double t2 = (1.0 - c * c) / (c * c);
    return 0.5 * (std::sqrt(1.0 + alpha * alpha * t2) - 1.0);
}

inline double g2(double cos_o, double cos_i, double alpha) {
    return 1.0 / (1.0 + lambda(cos_o, alpha) + lambda(cos_i, alpha));
}

// The whole material for one channel: base colour, metallic, roughness as the scene
// gives them; unit n, wo, wi both above the surface.
inline double metallic_roughness_bsdf(double base, double metallic, double roughness, glm::dvec3 n, glm::dvec3 wo,
                                      glm::dvec3 wi) {
    const double co = glm::dot(n, wo), ci = glm::dot(n, wi);
    const double f0 = 0.04 + (base - 0.04) * metallic, alpha = roughness * roughness;
    const double diffuse =
        (1.0 - metallic) * base * (1.0 - f0) * 21.0 / (20.0 * kPi) * (1.0 - pow5(1.0 - ci)) * (1.0 - pow5(1.0 - co));
    const glm::dvec3 h = glm::normalize(wo + wi);
    const double fresnel = f0 + (1.0 - f0) * pow5(1.0 - glm::dot(wo, h));
    return diffuse + fresnel * d(glm::dot(n, h), alpha) * g2(co, ci, alpha) / (4.0 * co * ci);
}

}  // namespace vkrt::test::ggx
