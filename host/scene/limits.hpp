#pragma once
// Bounds on user input, shared by the scene loader and the command line so both
// reject the same values with the same reasoning.
#include <cstdint>
#include <string>

namespace vkrt::limits {

// An image side beyond this is a typo, not a render. A pixel's sums and counters
// take 160 bytes (kernel::PIXEL_TEXELS = 10 texels of 16 bytes: PixelSum 6, Counters
// 4), so those of the largest allowed image take 5 GiB; a progressive render holds
// two such sets on the host from its second pass on, the total and the pass's own.
inline constexpr std::uint32_t kMaxImageSide = 32768;
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t(1) << 25;
// Why an image of width x height pixels is refused; empty when it is allowed.
// Each side is checked where it is read; this is the rule on their product, on the
// grid of rays the buffers hold: with `corners` (render.corners) the
// (width + 1) x (height + 1) pixel corners.
inline std::string image_size_problem(std::uint32_t width, std::uint32_t height, bool corners = false) {
    const std::uint64_t w = width + (corners ? 1u : 0u), h = height + (corners ? 1u : 0u);
    if (w * h <= kMaxImagePixels) return {};
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    if (corners) {
        return "image of " + size + " pixels traces " + std::to_string(w) + "x" + std::to_string(h) +
               " corner rays (render.corners), more than the limit of " + std::to_string(kMaxImagePixels);
    }
    return "image of " + size + " pixels is larger than the limit of " + std::to_string(kMaxImagePixels) + " pixels";
}

inline constexpr std::uint32_t kMaxAa = 64;
// Pixel sums are exact 96-bit fixed point (kernel/sums.glsl): 65,536 samples of the
// largest radiance a sample may carry still fit them. Also what --time alone stops at.
inline constexpr std::uint32_t kMaxSpp = 1u << 16;
inline constexpr std::uint32_t kMaxDepth = 64;
// Global mode's bounces; each is one loop iteration of a budget of 65,000 shared with
// the grid walk, so more than this could never finish (the stability tests render
// 1000).
inline constexpr std::uint32_t kMaxBounces = 1000;
// render.exposure and --exposure, in stops: 2^64 either way is far past any
// radiance a float image holds.
inline constexpr double kMaxExposureStops = 64.0;
inline constexpr std::uint32_t kMaxLoopBudget = 65000;  // below lavapipe's 65,535 cap
// Area-light shadow rays per hit. Each costs at least three loop iterations of the
// invocation's budget (the sample loop, the walk, a test), so more than this would
// truncate samples in all but the smallest scenes; more samples per pixel (spp)
// reduce noise just as well.
inline constexpr std::uint32_t kMaxLightSamples = 1024;
// Cells per axis a scene may ask of the grid; the total is further capped to what
// the device's buffers hold (host/accel/grid.cpp).
inline constexpr std::uint32_t kMaxGridAxisCells = 1u << 16;

// Instances (glTF's EXT_mesh_gpu_instancing, the scene format's "instance") are
// copies of their mesh's triangles: at most this many in one file or object, and
// at most 2^25 triangles in their copies. A scene's triangle takes about half a
// kilobyte on the host until it is flattened, so those take about 16 GiB.
inline constexpr std::uint64_t kMaxInstances = 1'000'000;
inline constexpr std::uint64_t kMaxInstancedTriangles = std::uint64_t(1) << 25;

}  // namespace vkrt::limits
