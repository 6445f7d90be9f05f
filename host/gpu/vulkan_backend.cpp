// The Vulkan backend: one compute pipeline specialised for the scene's feature set,
// one dispatch per sample index and band of rows, submitted in batches sized to the
// device's speed; a session keeps all of it for pass after pass.
#include "gpu/vulkan_backend.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "gpu/band_batcher.hpp"
#include "gpu/batch_timer.hpp"
#include "gpu/vulkan_buffer.hpp"
#include "gpu/vulkan_context.hpp"
#include "gpu/vulkan_pipeline.hpp"

namespace vkrt {

namespace {

using namespace gpu;
using Clock = std::chrono::steady_clock;

// Short submissions keep a GPU's watchdog away (Windows' TDR fires at 2 s) and the
// progress callback lively; long ones amortise the per-submission cost. Aim between.
constexpr double kTargetSubmitSeconds = 0.25;

// Scenes with fewer primitives render faster by brute force than through the grid, as
// measured on lavapipe and unmeasured elsewhere (docs/decisions/0002-grid-threshold.md;
// `vkrt bench --threshold` measures a device).
constexpr std::uint32_t kBruteForceBelow = 32;
constexpr std::uint32_t kMaxBatch = 256;
// Each sample is dispatched in bands of this many workgroup rows (64 pixel rows), so
// that one dispatch of a slow scene stays short and progress moves within a sample.
constexpr std::uint32_t kBandGroups = 8;
// The dispatches read the sums and write them back: what each barrier before one covers.
constexpr VkAccessFlags kShaderAccess = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// A scene array as a buffer, or nothing when the scene leaves it out.
template <typename T>
std::optional<VulkanBuffer> array_buffer(const VulkanContext& context, std::uint32_t binding, const char* name,
                                         const std::vector<T>& items) {
    if (items.empty()) {
        return std::nullopt;
    }
    std::optional<VulkanBuffer> buffer;
    buffer.emplace(context, name, items.size() * sizeof(T), kBindingUsage, Placement::Device, texel_bytes(binding));
    buffer->upload(items.data(), buffer->size());
    return buffer;
}

// The scene's arrays, one buffer per SCENE_BUFFER line of kernel/bindings.glsl.
std::array<std::optional<VulkanBuffer>, kBindingCount> upload_scene_buffers(const VulkanContext& context,
                                                                            const FlatScene& scene) {
    std::array<std::optional<VulkanBuffer>, kBindingCount> buffers;
#define SCENE_BUFFER(binding, name, Element, load, format) \
    buffers[binding] = array_buffer(context, binding, #name, scene.name);
#include "kernel/bindings.glsl"
    return buffers;
}

// The kernel trusts the counts in Params; an index past a buffer's end would be an
// out-of-bounds read on the device, so the counts are checked here, once.
void check_counts(const FlatScene& scene) {
    const kernel::Params& p = scene.params;
    auto check = [](const char* what, std::size_t count, std::size_t size) {
        if (count > size) {
            throw GpuError(std::string("scene: params count of ") + what + " (" + std::to_string(count) +
                           ") exceeds its buffer (" + std::to_string(size) + ")");
        }
    };
    const FeatureSet& f = scene.features;
    if (f.has(Feature::HAS_SPHERES)) check("spheres", kernel::sphere_count(p), scene.spheres.size());
    if (f.has(Feature::HAS_TRIANGLES)) check("triangles", kernel::triangle_count(p), scene.triangles.size());
    if (f.has(Feature::HAS_POINT_LIGHTS)) check("point lights", kernel::light_count(p), scene.lights.size());
    if (f.has(Feature::HAS_RINGS)) check("rings", kernel::ring_count(p), scene.rings.size());
    if (f.has(Feature::HAS_CYLINDERS)) check("cylinders", kernel::cylinder_count(p), scene.cylinders.size());
    if (f.has(Feature::HAS_AREA_LIGHTS)) {
        check("emitters", kernel::emitter_count(p), scene.emitters.size());
        if (kernel::emitter_count(p) == 0) throw GpuError("scene: area lights on, but params count no emitters");
    }
    check("materials", kernel::material_count(p), scene.materials.size());
    if (f.has(Feature::HAS_GRID)) {
        const glm::uvec3 res = kernel::grid_resolution(p);
        const std::uint64_t cells = std::uint64_t(res.x) * res.y * res.z;
        if (scene.grid_cell_starts.size() != cells + 1 || scene.grid_cell_starts.back() != scene.grid_refs.size()) {
            throw GpuError("scene: the grid's cell starts do not match its resolution and references");
        }
    }
}

// Refuses, before anything is created, a scene this device cannot dispatch.
void check_dispatchable(const VulkanContext& context, const FlatScene& scene) {
    const std::uint32_t width = scene.width();
    const std::uint32_t height = scene.height();
    if (scene.pixel_count() == 0) {
        throw GpuError("scene: the image has no pixels (" + std::to_string(width) + "x" +
                       std::to_string(height) + ")");
    }
    const VkPhysicalDeviceLimits& limits = context.properties().limits;
    if ((width + kLocalSize - 1) / kLocalSize > limits.maxComputeWorkGroupCount[0] ||
        (height + kLocalSize - 1) / kLocalSize > limits.maxComputeWorkGroupCount[1]) {
        throw GpuError("image " + std::to_string(width) + "x" + std::to_string(height) +
                       " needs more workgroups than this device dispatches at once");
    }
    check_counts(scene);
}

// The pipeline, the uploaded scene and the sums buffers of one scene, kept for as
// many passes as the caller renders: creating the pipeline can take longer than a
// pass of a small image (docs/decisions/0014-progressive-passes-one-session.md).
class VulkanSession final : public RenderSession {
public:
    VulkanSession(const VulkanContext& context, const FlatScene& scene)
        : context_(context),
          width_(scene.width()),
          height_(scene.height()),
          groups_x_((width_ + kLocalSize - 1) / kLocalSize),
          groups_y_((height_ + kLocalSize - 1) / kLocalSize),
          setup_start_(Clock::now()),
          pipeline_(make_pipeline(context, scene.features)),
          params_(context, "params", sizeof(kernel::Params), kBindingUsage),
          // Stands in for every array the scene leaves out: the shader still declares
          // the binding, but with the feature off nothing reads it.
          dummy_(context, "unused", 16, kBindingUsage),
          sums_(context, "sums", scene.pixel_count() * sizeof(kernel::PixelSum), kBindingUsage),
          counters_(context, "counters", scene.pixel_count() * sizeof(kernel::Counters), kBindingUsage),
          scene_buffers_(upload_scene_buffers(context, scene)),
          views_(write_descriptors(context.device(), pipeline_.set, bound_buffers())),
          timer_(context),
          batcher_(((groups_y_ + kBandGroups - 1) / kBandGroups), kTargetSubmitSeconds, kMaxBatch) {
        params_.upload(&scene.params, sizeof(kernel::Params));
        context_.submit_and_wait([&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, dummy_.get(), 0, VK_WHOLE_SIZE, 0); });
        setup_seconds_ = seconds_since(setup_start_);
    }

    double setup_seconds() const override { return setup_seconds_; }
    RenderResult render(SampleRange samples, const ProgressCallback& progress) override;

private:
    // The buffer of each binding (kernel/bindings.glsl), the dummy for an empty array.
    std::array<const VulkanBuffer*, kBindingCount> bound_buffers() const {
        std::array<const VulkanBuffer*, kBindingCount> buffers{};
        for (std::uint32_t i = 0; i < kBindingCount; ++i) {
            buffers[i] = scene_buffers_[i] ? &*scene_buffers_[i] : &dummy_;
        }
        buffers[index(Binding::params)] = &params_;
        buffers[index(Binding::sums)] = &sums_;
        buffers[index(Binding::counters)] = &counters_;
        return buffers;
    }

    const VulkanContext& context_;
    std::uint32_t width_, height_, groups_x_, groups_y_;
    Clock::time_point setup_start_;
    Pipeline pipeline_;
    VulkanBuffer params_;
    VulkanBuffer dummy_;
    VulkanBuffer sums_;
    VulkanBuffer counters_;
    std::array<std::optional<VulkanBuffer>, kBindingCount> scene_buffers_;  // by binding; empty: none
    std::vector<BufferView> views_;
    BatchTimer timer_;
    // Dispatches per submission, from the bands' measured costs; kept from pass to
    // pass so that a later pass need not measure them again.
    BandBatcher batcher_;
    double setup_seconds_ = 0.0;
};

RenderResult VulkanSession::render(SampleRange samples, const ProgressCallback& progress) {
    // Each pass starts from zero sums; the barrier orders the fill after the previous
    // pass's shader writes (also across submissions: a barrier's scope spans them).
    context_.submit_and_wait([&](VkCommandBuffer cmd) {
        memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, kShaderAccess, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_ACCESS_TRANSFER_WRITE_BIT);
        vkCmdFillBuffer(cmd, sums_.get(), 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cmd, counters_.get(), 0, VK_WHOLE_SIZE, 0);
        memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, kShaderAccess);
    });

    RenderResult result;
    result.width = width_;
    result.height = height_;

    // The work, in order: sample by sample, each in bands of rows. The sums are
    // exact integers, so neither banding nor batching changes a bit of the image.
    const std::uint32_t bands = (groups_y_ + kBandGroups - 1) / kBandGroups;
    // At most 65,536 samples (limits.hpp) of at most 512 bands (32,768 rows): the
    // count fits the progress callback's 32 bits.
    const std::uint32_t items = samples.count * bands;
    const Clock::time_point loop_start = Clock::now();
    double gpu_seconds = 0.0;
    for (std::uint32_t done = 0; done < items;) {
        const std::uint32_t n = batcher_.next(done, items - done);
        const Clock::time_point submitted = Clock::now();
        context_.submit_and_wait([&](VkCommandBuffer cmd) {
            timer_.begin(cmd);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.pipeline.get());
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.layout.get(), 0, 1,
                                    &pipeline_.set, 0, nullptr);
            for (std::uint32_t item = done; item < done + n; ++item) {
                const std::uint32_t sample = samples.first + item / bands;
                const std::uint32_t band = item % bands;
                // A sample adds to the sums the previous sample wrote: one barrier
                // where a sample starts orders all of the previous one before all of
                // it, across batches too (a barrier's scope spans earlier
                // submissions). The bands of one sample write disjoint rows and may
                // overlap on a GPU.
                if (item != 0 && band == 0) {
                    memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, kShaderAccess);
                }
                const std::uint32_t first_group = band * kBandGroups;
                const std::array<std::uint32_t, 4> pass{sample, first_group * kLocalSize, 0, 0};
                vkCmdPushConstants(cmd, pipeline_.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, kPushBytes,
                                   pass.data());
                vkCmdDispatch(cmd, groups_x_, std::min(kBandGroups, groups_y_ - first_group), 1);
            }
            timer_.end(cmd);
        });
        const double wall = seconds_since(submitted);
        result.longest_submit_seconds = std::max(result.longest_submit_seconds, wall);
        if (timer_.on_gpu()) {
            gpu_seconds += timer_.batch_seconds();
        }
        done += n;
        if (progress) {
            progress(done, items);
        }
        batcher_.measured(done - n, n, wall);
    }
    result.render_seconds = timer_.on_gpu() ? gpu_seconds : seconds_since(loop_start);

    result.sums.resize(std::size_t(width_) * height_);
    result.counters.resize(result.sums.size());
    sums_.readback(result.sums.data(), sums_.size());
    counters_.readback(result.counters.data(), counters_.size());
    return result;
}

class VulkanBackend final : public Backend {
public:
    explicit VulkanBackend(const VulkanOptions& options) : context_(options) {}

    std::string name() const override { return "vulkan"; }
    AccelPolicy accel_policy() const override {
        // The grid arrays are uint texel buffers: bounded by the texel count a view
        // may have and,
        // for a device that would need them as storage buffers, by
        // maxStorageBufferRange.
        const VkPhysicalDeviceLimits& l = context_.properties().limits;
        return {kBruteForceBelow, std::min<std::uint64_t>(l.maxTexelBufferElements, l.maxStorageBufferRange / 4)};
    }
    std::string device_name() const override { return context_.properties().deviceName; }
    std::uint32_t validation_messages() const override { return context_.validation_messages(); }

    std::unique_ptr<RenderSession> begin(const FlatScene& scene) override {
        check_dispatchable(context_, scene);
        return std::make_unique<VulkanSession>(context_, scene);
    }

private:
    VulkanContext context_;
};

}  // namespace

std::unique_ptr<Backend> make_vulkan_backend(const VulkanOptions& options) {
    return std::make_unique<VulkanBackend>(options);
}

}  // namespace vkrt
