#include "scene/gltf_instancing.hpp"

#include <cmath>
#include <cstddef>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/matrix_transform.hpp>
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

    std::vector<glm::dmat4> instances(*count, glm::dmat4(1.0));
    for (std::size_t i = 0; i < *count; ++i) {
        glm::dmat4 m(1.0);
        if (!translations.empty()) m = glm::translate(m, translations[i]);
        if (!rotations.empty()) {
            const glm::dvec4 r = rotations[i];
            const glm::dquat q(r.w, r.x, r.y, r.z);
            const double length = glm::length(q);
            if (!(length > 0.0)) fail(at("ROTATION"), fmt::format("instance {} has a zero quaternion", i));
            m = m * glm::mat4_cast(q / length);
        }
        if (!scales.empty()) {
            const glm::dvec3 s = scales[i];
            if (s.x == 0.0 || s.y == 0.0 || s.z == 0.0) {
                fail(at("SCALE"), fmt::format("instance {} has a scale of zero, which flattens its mesh", i));
            }
            m = glm::scale(m, s);
        }
        instances[i] = m;
    }
    return instances;
}

}  // namespace vkrt::gltf
