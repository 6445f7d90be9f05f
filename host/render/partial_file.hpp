#pragma once
// Partial files: one render's exact per-pixel sums and counters over a set of
// sample ranges, so that renders of disjoint ranges (on other runs or machines) add
// up to the very render of their union (`vkrt render --samples`, `vkrt merge`).
//
// The format is OpenEXR (docs/cli.md, "Partial files"): R, G, B float channels hold
// each pixel's mean, so any viewer shows the image; 32-bit UINT channels hold the
// PixelSum words (vkrt.sum.*) and the counters (vkrt.rays.*, vkrt.work.*,
// vkrt.tree.*, vkrt.paths.*); header attributes say what was rendered (vkrt:*),
// by which build (vkrt:version, with a hash of the kernel's sources), and a checksum
// of the sums and counters (vkrt:checksum) that reading verifies.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "render/backend.hpp"

namespace vkrt {

// This build's version and kernel hash, as partial files record it: "0.1.0 kernel 1a2b3c4d5e6f".
std::string build_version();

struct PartialFile {
    RenderResult sums;                // width x height of the kernel's rays (with corners, one larger)
    std::vector<SampleRange> samples; // sorted, touching ranges joined
    std::string scene;                // the scene file's name, for messages
    std::uint32_t seed = 0;
    std::uint64_t fingerprint = 0;    // render/fingerprint.hpp
    std::string backend;              // "vulkan", "cpu", or both joined by '+' after a merge
    bool corners = false;             // SPD corner rays: each image pixel averages four of these
    std::string version = build_version();  // of the vkrt that rendered it
};

// Throws ImageError (image/image.hpp) naming the file when it cannot be written.
void write_partial(const PartialFile& partial, const std::filesystem::path& file);

// Throws ImageError naming the file when it cannot be read or is not a vkrt partial
// file (another EXR, a PNG, a partial missing a channel), or when its pixels do not
// match its checksum (a truncated or damaged file).
PartialFile read_partial(const std::filesystem::path& file);

// Reads a partial and adds its sums and counters into `total` (sized to it when
// empty), a block of rows at a time: memory for the total, not for the partial too.
// Returns the header (read_partial_header). Throws as read_partial, and ImageError
// when its size is not total's.
PartialFile add_partial(const std::filesystem::path& file, RenderResult& total);

// The header, after reading every pixel to verify the file as read_partial does,
// keeping none of them.
PartialFile check_partial(const std::filesystem::path& file);

// The header alone: everything but the sums (whose width and height are set).
// Cheap, for checking many partials before adding any.
PartialFile read_partial_header(const std::filesystem::path& file);

}  // namespace vkrt
