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
    explicit SharedArray(std::shared_ptr<const std::vector<T>> items) : items_(std::move(items)) {}

    std::size_t size() const { return items_ ? items_->size() : 0; }
    bool empty() const { return size() == 0; }
    const T* data() const { return items_ ? items_->data() : nullptr; }
    const T& operator[](std::size_t i) const { return (*items_)[i]; }
    operator std::span<const T>() const { return items_ ? std::span<const T>(*items_) : std::span<const T>(); }

private:
    std::shared_ptr<const std::vector<T>> items_;
};

}  // namespace vkrt
