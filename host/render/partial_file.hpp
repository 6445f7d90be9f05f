#pragma once
// Partial files: one render's exact per-pixel sums and counters over a set of
// sample ranges, so that renders of disjoint ranges (on other runs or machines) add
// up to the very render of their union (`vkrt render --samples`, `vkrt merge`).
//
// The format is OpenEXR (docs/cli.md, "Partial files"): R, G, B float channels hold
// each pixel's mean, so any viewer shows the image; 32-bit UINT channels hold the
// PixelSum words (vkrt.sum.*) and the counters (vkrt.rays.*, vkrt.work.*,
// vkrt.tree.*, vkrt.paths.*); header attributes say what was rendered (vkrt:*).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "render/backend.hpp"

namespace vkrt {

struct PartialFile {
    RenderResult sums;                // width x height of the kernel's rays (with corners, one larger)
    std::vector<SampleRange> samples; // sorted, touching ranges joined
    std::string scene;                // the scene file's name, for messages
    std::uint32_t seed = 0;
    std::uint64_t fingerprint = 0;    // render/fingerprint.hpp
    std::string backend;              // "vulkan", "cpu", or both joined by '+' after a merge
    bool corners = false;             // SPD corner rays: each image pixel averages four of these
};

// Throws ImageError (image/image.hpp) naming the file when it cannot be written.
void write_partial(const PartialFile& partial, const std::filesystem::path& file);

// Throws ImageError naming the file when it cannot be read or is not a vkrt partial
// file (another EXR, a PNG, a partial missing a channel).
PartialFile read_partial(const std::filesystem::path& file);

}  // namespace vkrt
