#include "scene/gltf_instancing.hpp"

#include <cmath>
#include <cstddef>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

#include "scene/scene_error.hpp"

namespace vkrt::gltf {
namespace {

[[noreturn]] void fail(const Origin& origin, const std::string& what) {
    throw SceneError(fmt::format("{}: {}: {}", origin.file, origin.element, what));
}

// The accessor index of attribute `name`, if the object lists it.
std::optional<int> attribute(const tinygltf::Value& attributes, const std::string& name, const Origin& origin) {
    if (!attributes.Has(name)) return std::nullopt;
    const tinygltf::Value& v = attributes.Get(name);
    if (!v.IsInt()) fail(origin, fmt::format("attributes.{} is not an accessor index", name));
    return v.GetNumberAsInt();
}

}  // namespace

std::optional<glm::dmat4> compose_trs(const glm::dvec3& t, const glm::dvec4& q, const glm::dvec3& s) {
    const glm::dquat rotation(q.w, q.x, q.y, q.z);
    const double length = glm::length(rotation);
    if (!(length > 0.0) || !std::isfinite(length)) return std::nullopt;
    glm::dmat4 translate(1.0);
    translate[3] = glm::dvec4(t, 1.0);
    return translate * glm::mat4_cast(rotation / length) * glm::scale(glm::dmat4(1.0), s);
}

std::vector<glm::dmat4> read_gpu_instances(const tinygltf::Model& model, const tinygltf::Value& extension,
                                           const Origin& origin, bool quantized) {
    if (!extension.IsObject() || !extension.Has("attributes") || !extension.Get("attributes").IsObject()) {
        fail(origin, "expected an object with an \"attributes\" object");
    }
    const tinygltf::Value& attributes = extension.Get("attributes");
    const auto at = [&](const char* name) { return Origin{origin.file, origin.element + ".attributes." + name}; };
    const Integers integers = quantized ? Integers::Quantized : Integers::Quantizable;
    std::vector<glm::dvec3> translations, scales;
    std::vector<glm::dvec4> rotations;
    std::optional<std::size_t> count;
    const auto check_count = [&](std::size_t n, const char* name) {
        if (count && *count != n) {
            fail(at(name), fmt::format("{} instances, where the attributes before it have {}", n, *count));
        }
        count = n;
    };
    if (const auto a = attribute(attributes, "TRANSLATION", origin)) {
        translations = read_vec3(model, *a, at("TRANSLATION"), integers);
        check_count(translations.size(), "TRANSLATION");
    }
    if (const auto a = attribute(attributes, "ROTATION", origin)) {
        rotations = read_vec4(model, *a, at("ROTATION"), Integers::Normalized);
        check_count(rotations.size(), "ROTATION");
    }
    if (const auto a = attribute(attributes, "SCALE", origin)) {
        scales = read_vec3(model, *a, at("SCALE"), integers);
        check_count(scales.size(), "SCALE");
    }
    if (!count) fail(origin, "no TRANSLATION, ROTATION or SCALE attribute");

    std::vector<glm::dmat4> instances(*count);
    for (std::size_t i = 0; i < *count; ++i) {
        const glm::dvec4 r = rotations.empty() ? glm::dvec4(0.0, 0.0, 0.0, 1.0) : rotations[i];
        const std::optional<glm::dmat4> m = compose_trs(translations.empty() ? glm::dvec3(0.0) : translations[i], r,
                                                        scales.empty() ? glm::dvec3(1.0) : scales[i]);
        if (!m) fail(at("ROTATION"), fmt::format("instance {} has a zero quaternion", i));
        instances[i] = *m;
    }
    return instances;
}

}  // namespace vkrt::gltf
