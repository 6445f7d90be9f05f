#pragma once
// A fingerprint of everything that decides a sample's value: the flattened scene
// (camera, image size, seed, settings, materials, lights, primitives) and the
// kernel features. Partial files carry it, so that `vkrt merge` can refuse to add
// up renders of different scenes, sizes, seeds or settings.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "flatten/flat_scene.hpp"

namespace vkrt {

// 64-bit FNV-1a: the fingerprint's hash, and partial files' checksum.
class Fnv1a {
public:
    void add(const void* data, std::size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < bytes; ++i) hash_ = (hash_ ^ p[i]) * 0x100000001b3ull;
    }
    // The length first, so that moving an element from one array to the next
    // changes the hash.
    template <class T>
    void add(const std::vector<T>& items) {
        const std::uint64_t n = items.size();
        add(&n, sizeof n);
        add(items.data(), items.size() * sizeof(T));
    }
    // The same steps over 64-bit words instead of bytes (bytes a multiple of 8): eight
    // times fewer, for checksums of large buffers.
    void add_words(const void* data, std::size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i + 8 <= bytes; i += 8) {
            std::uint64_t word = 0;
            std::memcpy(&word, p + i, sizeof word);
            hash_ = (hash_ ^ word) * 0x100000001b3ull;
        }
    }
    std::uint64_t value() const { return hash_; }

private:
    std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

// 64-bit FNV-1a over those bytes. The grid is left out: it decides how
// rays find what they hit, not what they hit (tests/accel/grid_image_test.cpp renders
// identical images with and without it), so partials rendered with --grid on, off,
// or on backends that choose differently still merge. So is DEFERRED_SPHERES, the
// order in which brute force tests spheres (tests/kernel/deferred_spheres_test.cpp).
std::uint64_t scene_fingerprint(const FlatScene& scene);

// Sixteen lower-case hex digits, as partial files store it.
std::string format_fingerprint(std::uint64_t fingerprint);

}  // namespace vkrt
