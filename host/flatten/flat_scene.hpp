#pragma once
// A scene flattened into the kernel's buffer layouts (shaders/kernel/layout.glsl),
// the one form both backends consume. Buffers the feature set leaves out are empty:
// neither built here nor uploaded by a backend.
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "accel/accel_policy.hpp"
#include "accel/grid.hpp"
#include "kernel/types.hpp"
#include "flatten/features.hpp"
#include "flatten/shared_array.hpp"
#include "scene/scene.hpp"

namespace vkrt {

struct BufferSize {
    std::string name;
    std::size_t bytes;
};

// The arrays of kernel/arrays.glsl by name, for FlatArray.
enum class ArrayId {
#define SCENE_ARRAY(id, name, Element, load, format) name = id,
#include "kernel/arrays.glsl"
};

// Each array is built by flattening, but for the texels, which it shares.
template <class T, ArrayId id>
using FlatArray = std::conditional_t<id == ArrayId::texture_words, SharedArray<T>, std::vector<T>>;

struct FlatScene {
    kernel::Params params{};
    // Where the kernel's coordinates start, in the scene's (flatten_scene): every
    // position in params and the buffers is the scene's minus this, so a point the
    // kernel computes is at origin + that point in the scene.
    dvec3 origin{0.0};
    FeatureSet features;
    // One array per line of kernel/arrays.glsl (materials, spheres, ...,
    // grid_refs), uploaded as it is. An array only left-out features read stays
    // empty. The textures' texels are the scene's own (Scene::texels), shared.
#define SCENE_ARRAY(id, name, Element, load, format) FlatArray<kernel::Element, ArrayId::name> name;
#include "kernel/arrays.glsl"
    GridStats grid;
    InstanceCounts instances;  // Scene::instances, for the stats
    std::uint32_t samples_per_pixel = 1;
    // The SPD rule (render.corners): the kernel traces one ray through each pixel
    // corner, a (width + 1) x (height + 1) grid, and each output pixel averages its
    // four corners (resolve_image).
    bool corners = false;

    // The grid of rays the kernel traces: the image, or its corners.
    std::uint32_t width() const { return kernel::image_width(params); }
    std::uint32_t height() const { return kernel::image_height(params); }
    std::size_t pixel_count() const { return std::size_t(width()) * height(); }

    // The scene buffers that were built (non-empty), with their sizes.
    std::vector<BufferSize> built_buffers() const;
};

// `policy` comes from the backend that will render (Backend::accel_policy); the
// default builds the grid for any scene with primitives unless the scene says "off".
FlatScene flatten_scene(const Scene& scene, const AccelPolicy& policy = {});

}  // namespace vkrt
