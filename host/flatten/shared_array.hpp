#pragma once
// An array of the flattened scene that is not copied from the scene but shared with
// it: the textures' texels, the largest data most assets have, which flattening
// does not change (Scene::texels, scene/texture_image.hpp). Read like a vector.
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace vkrt {

template <class T>
class SharedArray {
public:
    using value_type = T;

    SharedArray() = default;
    // Any vector of T, whatever its allocator; kept alive as long as this is.
    template <class Allocator>
    explicit SharedArray(std::shared_ptr<const std::vector<T, Allocator>> items)
        : owner_(items), items_(items ? std::span<const T>(*items) : std::span<const T>()) {}

    std::size_t size() const { return items_.size(); }
    bool empty() const { return items_.empty(); }
    const T* data() const { return items_.empty() ? nullptr : items_.data(); }
    const T& operator[](std::size_t i) const { return items_[i]; }
    operator std::span<const T>() const { return items_; }

private:
    std::shared_ptr<const void> owner_;
    std::span<const T> items_;
};

}  // namespace vkrt
