#pragma once
// The metallic-roughness BSDF of shaders/kernel/bsdf.glsl and lobes/ written
// again in double, from the papers rather than from the kernel, for the tests to hold
// the kernel against: GGX's distribution (Walter et al. 2007), Smith's Lambda and
// height-correlated G2 (Heitz 2014), Schlick's Fresnel, and Kulla and Conty's
// multiple-scattering lobe and diffuse layering (2017). Those two read the albedo
// tables the kernel reads (host/flatten/ggx_albedo.hpp), interpolated here as
// lobes/ggx_albedo.glsl does; tests/kernel/microfacet_test.cpp holds the tables
// against quadrature.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "flatten/ggx_albedo.hpp"
#include "kernel/types.hpp"

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

// The tables' values: E (table 0) or E_s (table 1) at sqrt(mu), sqrt(alpha), bilinear
// between knots, and their means over mu.
inline double table_value(std::size_t i) { return double(std::bit_cast<float>(vkrt::ggx_albedo_table()[i])); }
inline std::size_t table_knot(double x, double& t) {
    const double n = double(vkrt::kernel::GGX_TABLE_SIZE);
    const double s = std::clamp(x, 0.0, 1.0) * (n - 1.0);
    const std::size_t k = std::min(std::size_t(s), std::size_t(n) - 2);
    t = s - double(k);
    return k;
}
inline double table_lookup(int table, double mu, double alpha) {
    const std::size_t n = vkrt::kernel::GGX_TABLE_SIZE, base = std::size_t(table) * (n * n + n);
    double tm = 0.0, tr = 0.0;
    const std::size_t i = table_knot(std::sqrt(std::max(mu, 0.0)), tm), j = table_knot(std::sqrt(alpha), tr);
    auto at = [&](std::size_t jj, std::size_t ii) { return table_value(base + jj * n + ii); };
    const double low = at(j, i) + (at(j, i + 1) - at(j, i)) * tm;
    const double high = at(j + 1, i) + (at(j + 1, i + 1) - at(j + 1, i)) * tm;
    return low + (high - low) * tr;
}
inline double table_mean(int table, double alpha) {
    const std::size_t n = vkrt::kernel::GGX_TABLE_SIZE, base = std::size_t(table) * (n * n + n) + n * n;
    double tr = 0.0;
    const std::size_t j = table_knot(std::sqrt(alpha), tr);
    return table_value(base + j) + (table_value(base + j + 1) - table_value(base + j)) * tr;
}

// F_ms: F_avg^2 E_avg / (1 - F_avg (1 - E_avg)), F_avg = f0 + (1 - f0) / 21.
inline double multiple_fresnel(double f0, double e_avg) {
    const double f_avg = f0 + (1.0 - f0) / 21.0;
    return f_avg * f_avg * e_avg / (1.0 - f_avg * (1.0 - e_avg));
}

// What the rough lobe reflects from cos(theta) = mu, single and multiple scattering.
inline double reflectance(double f0, double mu, double alpha) {
    const double e = table_lookup(0, mu, alpha);
    return f0 * e + (1.0 - f0) * table_lookup(1, mu, alpha) + multiple_fresnel(f0, table_mean(0, alpha)) * (1.0 - e);
}
inline double mean_reflectance(double f0, double alpha) {
    const double e_avg = table_mean(0, alpha);
    return f0 * e_avg + (1.0 - f0) * table_mean(1, alpha) + multiple_fresnel(f0, e_avg) * (1.0 - e_avg);
}

// The material as it was before its multiple scattering and layering (decision 0029:
// single scattering, and Shirley, Hu, Smits and Lafortune's diffuse coupling, 1997),
// for comparisons with models that are single-scattering too.
inline double metallic_roughness_single_scattering_bsdf(double base, double metallic, double roughness, glm::dvec3 n,
                                                        glm::dvec3 wo, glm::dvec3 wi) {
    const double co = glm::dot(n, wo), ci = glm::dot(n, wi);
    const double f0 = 0.04 + (base - 0.04) * metallic, alpha = roughness * roughness;
    const double diffuse =
        (1.0 - metallic) * base * (1.0 - f0) * 21.0 / (20.0 * kPi) * (1.0 - pow5(1.0 - ci)) * (1.0 - pow5(1.0 - co));
    const glm::dvec3 h = glm::normalize(wo + wi);
    const double fresnel = f0 + (1.0 - f0) * pow5(1.0 - glm::dot(wo, h));
    return diffuse + fresnel * d(glm::dot(n, h), alpha) * g2(co, ci, alpha) / (4.0 * co * ci);
}

// The whole material for one channel: base colour, metallic, roughness as the scene
// gives them; unit n, wo, wi both above the surface. Single scattering, its
// multiple-scattering complement, and the diffuse lobe under both.
inline double metallic_roughness_bsdf(double base, double metallic, double roughness, glm::dvec3 n, glm::dvec3 wo,
                                      glm::dvec3 wi) {
    const double co = glm::dot(n, wo), ci = glm::dot(n, wi);
    const double f0 = 0.04 + (base - 0.04) * metallic;
    const double alpha = std::max(roughness * roughness, double(vkrt::kernel::MIN_GGX_ALPHA));
    const glm::dvec3 h = glm::normalize(wo + wi);
    const double fresnel = f0 + (1.0 - f0) * pow5(1.0 - glm::dot(wo, h));
    const double single = fresnel * d(glm::dot(n, h), alpha) * g2(co, ci, alpha) / (4.0 * co * ci);
    const double e_avg = table_mean(0, alpha);
    const double multiple = multiple_fresnel(f0, e_avg) * (1.0 - table_lookup(0, co, alpha)) *
                            (1.0 - table_lookup(0, ci, alpha)) / (kPi * (1.0 - e_avg));
    const double diffuse = (1.0 - metallic) * base * (1.0 - reflectance(f0, co, alpha)) *
                           (1.0 - reflectance(f0, ci, alpha)) / (kPi * (1.0 - mean_reflectance(f0, alpha)));
    return single + multiple + diffuse;
}

}  // namespace vkrt::test::ggx
