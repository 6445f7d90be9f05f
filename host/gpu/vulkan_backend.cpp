// The Vulkan backend: one compute pipeline specialised for the scene's feature set
// and the device's data paths, one dispatch per sample index and tile, submitted in
// batches planned to stay under a bound; a session keeps all of it for pass after
// pass, and makes it again on a new device when the device is lost.
#include "gpu/vulkan_backend.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <vector>

#include "gpu/batch_timer.hpp"
#include "gpu/data_paths.hpp"
#include "gpu/device_class.hpp"
#include "gpu/scene_pack.hpp"
#include "gpu/tile_batcher.hpp"
#include "gpu/vulkan_buffer.hpp"
#include "gpu/vulkan_context.hpp"
#include "gpu/vulkan_pipeline.hpp"

namespace vkrt {

namespace {

using namespace gpu;
using Clock = std::chrono::steady_clock;

// Tiles start this size; while one tile of one sample alone takes longer than the
// bound, they are halved at once, down to one 8x8 workgroup.
constexpr std::uint32_t kStartTileWidth = 256;
constexpr std::uint32_t kStartTileHeight = 64;
constexpr std::uint32_t kMaxBatch = 256;
// A pass is rendered again on a new device at most this many times.
constexpr std::uint32_t kDeviceResets = 2;
constexpr VkAccessFlags kShaderAccess = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
constexpr std::uint32_t kProgressUnits = 1u << 20;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// The kernel trusts the counts in Params; an index past an array's end would read
// another array or past the buffer, so the counts are checked here, once.
void check_counts(const FlatScene& scene) {
    const kernel::Params& p = scene.params;
    auto check = [](const char* what, std::size_t count, std::size_t size) {
        if (count > size) {
            throw GpuError(std::string("scene: params count of ") + what + " (" + std::to_string(count) +
                           ") exceeds its array (" + std::to_string(size) + ")");
        }
    };
    const FeatureSet& f = scene.features;
#define PRIMITIVE_KIND(ID, name, Name, names, NAME, NAMES, PARTS) \
    if (f.has(Feature::HAS_##NAMES)) check(#names, kernel::name##_count(p), scene.names.size());
#include "kernel/shapes/kinds.glsl"
    if (f.has(Feature::HAS_POINT_LIGHTS)) check("lights", kernel::light_count(p), scene.lights.size());
    if (f.has(Feature::HAS_AREA_LIGHTS)) {
        check("emitters", kernel::emitter_count(p), scene.emitters.size());
        if (kernel::emitter_count(p) == 0) throw GpuError("scene: area lights on, but params count no emitters");
    }
    check("materials", kernel::material_count(p), scene.materials.size());
    if (f.has(Feature::HAS_GRID)) {
        const glm::uvec3 res = kernel::grid_resolution(p);
        const std::uint64_t cells = std::uint64_t(res.x) * res.y * res.z;
        if (scene.grid_nodes.size() < cells + 1 || scene.grid_nodes.back() != scene.grid_refs.size()) {
            throw GpuError("scene: the grid's nodes do not match its resolution and references");
        }
    }
}

std::string describe(const DataPaths& paths) {
    const char* scene = paths.scene_by_address ? "device address, pixels: storage"
                        : paths.scene_in_storage ? "storage"
                                                 : "texel";
    return std::string("scene: ") + scene + " buffers, params: " +
           (paths.params_in_uniform ? "uniform" : "texel") + " buffer";
}

// What the data paths are planned for: the packed scene, and the image's pixels of
// as many texels as the scene's features ask.
DataSizes data_sizes(const ScenePack& pack, const FlatScene& scene) {
    const std::uint32_t pixel_texels =
        kernel::PIXEL_TEXELS + (scene.features.has(Feature::HAS_PASSES) ? kernel::PASS_TEXELS : 0u);
    return {pack.texel_count, pack.words_start, pack.word_count, scene.width(), scene.height(), pixel_texels};
}

// Everything a session makes on one device: lost with the device, made again on a
// new one. It holds its context, so that replacing the backend's context after a
// lost device leaves another session's objects a device to be destroyed on.
struct DeviceState {
    DeviceState(std::shared_ptr<const VulkanContext> context_, const FlatScene& scene)
        : context(std::move(context_)),
          pack(pack_scene(scene, std::max(context->limits().texel_offset_alignment / 16, 1u))),
          paths(plan_data_paths(context->limits(), context->cpu_device(),
                                data_sizes(pack, scene),
                                context->options().scene_path, context->options().params_path)),
          pipeline(make_pipeline(*context, scene.features, paths)),
          params(*context, "params", sizeof(kernel::Params), kBindingUsage),
          // Stands in for every binding the data paths leave unread: the shader still
          // declares it, but nothing reads it.
          dummy(*context, "unused", 512, kBindingUsage),
          scene_buffer(*context, "scene", pack.bytes(),
                       paths.scene_by_address ? kBindingUsage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT
                                              : kBindingUsage),
          pixels(*context, "pixels", slab_bytes(scene), kBindingUsage),
          timer(*context) {
        params.upload(&scene.params, sizeof(kernel::Params));
        scene_buffer.write(pack.bytes(), [&](void* out) { write_scene(scene, pack, out); });
        // The CPU reads the sums through its caches: where the pixel buffer is not
        // such memory, each slab's last batch copies it into a buffer that is.
        if (!pixels.host_cached()) {
            readback.emplace(*context, "pixels (read-back)", pixels.size(), 0, Placement::Readback);
        }
        std::copy(pack.bases.begin(), pack.bases.end(), push.begin());
        if (paths.scene_by_address) {
            const std::uint64_t address = scene_buffer.address();
            push[kBaseLanes] = std::uint32_t(address);
            push[kBaseLanes + 1] = std::uint32_t(address >> 32);
        }
        views = write_descriptors(context->device(), pipeline.set, bound());
        context->submit_and_wait([&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, dummy.get(), 0, VK_WHOLE_SIZE, 0); });
    }

    VkDeviceSize slab_bytes(const FlatScene& scene) const {
        return VkDeviceSize(paths.slab_rows) * scene.width() * paths.pixel_texels * 16;
    }

    // What each binding of render_bindings.glsl is bound to.
    std::array<BoundRange, kBindingCount> bound() const {
        std::array<BoundRange, kBindingCount> b;
        b.fill({&dummy, 0, VK_WHOLE_SIZE});
        b[index(Binding::params_texels)] = {&params, 0, VK_WHOLE_SIZE};
        b[index(Binding::params_uniform)] = {&params, 0, VK_WHOLE_SIZE};
        if (paths.scene_in_storage) {
            // By address, the scene may be larger than one binding may be.
            if (!paths.scene_by_address) b[index(Binding::scene_storage)] = {&scene_buffer, 0, VK_WHOLE_SIZE};
            b[index(Binding::pixel_storage)] = {&pixels, 0, VK_WHOLE_SIZE};
        } else {
            b[index(Binding::scene_texels)] = {&scene_buffer, 0, std::max<VkDeviceSize>(pack.words_start, 1) * 16};
            if (pack.word_count != 0) {
                b[index(Binding::scene_words)] = {&scene_buffer, VkDeviceSize(pack.words_start) * 16,
                                                  VkDeviceSize(pack.word_count) * 4};
            }
            b[index(Binding::pixel_texels)] = {&pixels, 0, VK_WHOLE_SIZE};
        }
        return b;
    }

    std::shared_ptr<const VulkanContext> context;  // first: destroyed last
    ScenePack pack;
    DataPaths paths;
    Pipeline pipeline;
    VulkanBuffer params;
    VulkanBuffer dummy;
    VulkanBuffer scene_buffer;
    VulkanBuffer pixels;
    std::optional<VulkanBuffer> readback;
    std::vector<BufferView> views;
    // The push constants after `pass` (render_interface.hpp): the array bases, then
    // the scene's address when it is read by address.
    std::array<std::uint32_t, (kPushBytes - kPassBytes) / 4> push{};
    BatchTimer timer;
};

// A part of a slab's work: samples [first_sample, first_sample + samples) of a
// region of it, each tile by tile.
struct SlabWork {
    Region region;
    std::uint32_t first_sample, samples;
};

// What rendering one slab keeps from batch to batch.
struct SlabJob {
    std::uint32_t index = 0;      // which slab
    std::uint32_t rows = 0;
    std::uint32_t first_row = 0;  // of the image
    VkDeviceSize bytes = 0;       // of its sums in the pixel buffer
    Region whole;
    // The work, taken from the back: the whole slab, but for the rest of a sample
    // whose tiles were split part-way. The sums are exact integers, so neither
    // tiling, batching nor order changes a bit of the image.
    std::vector<SlabWork> work;
    std::optional<TileBatcher> rest_batcher;  // for the rest of a sample
    bool dispatched = false;                  // anything yet: the sums are cleared before the first
    double pixel_samples = 0.0;               // in all, for the progress
    double pixel_samples_done = 0.0;
    double gpu_seconds = 0.0;                 // the batches' time on the device, where it is measured
};

// One submission: items [first, first + count) of a work, item i being tile
// i % tiles of its sample first_sample + i / tiles.
struct Batch {
    const SlabWork& work;
    const Tiling& tiling;
    std::uint32_t tiles;
    std::uint32_t first, count;
    bool last;  // the slab's last: its sums are then made readable
};

// The slab starts from zero sums, after whatever last used the buffer.
void clear_sums(VkCommandBuffer cmd, const DeviceState& s, VkDeviceSize bytes) {
    memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                   kShaderAccess | VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                   VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdFillBuffer(cmd, s.pixels.get(), 0, bytes, 0);
    memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, kShaderAccess);
}

void bind_pipeline(VkCommandBuffer cmd, const DeviceState& s) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipeline.pipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipeline.layout.get(), 0, 1, &s.pipeline.set, 0,
                            nullptr);
    vkCmdPushConstants(cmd, s.pipeline.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, kPassBytes, kPushBytes - kPassBytes,
                       s.push.data());
}

// Dispatches item i of the batch's work: one tile of one sample.
void dispatch_item(VkCommandBuffer cmd, const DeviceState& s, const Batch& batch, std::uint32_t i, SlabJob& job) {
    const SlabWork& w = batch.work;
    const std::uint32_t tile = i % batch.tiles;
    // A sample adds to the sums an earlier one wrote: one barrier where the samples
    // of a region start orders all that came before (across batches too: a
    // barrier's scope spans earlier submissions). The tiles of one sample write
    // disjoint pixels and may overlap.
    if (tile == 0 && job.dispatched) {
        memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, kShaderAccess);
    }
    const Tiling& tiling = batch.tiling;
    const std::uint32_t x = tile % tiling.across() * tiling.tile_width;
    const std::uint32_t y = tile / tiling.across() * tiling.tile_height;
    const std::array<std::uint32_t, 4> pass{w.first_sample + i / batch.tiles, w.region.x + x,
                                            job.first_row + w.region.y + y, job.first_row};
    vkCmdPushConstants(cmd, s.pipeline.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, kPassBytes, pass.data());
    const std::uint32_t tw = std::min(tiling.tile_width, w.region.width - x);
    const std::uint32_t th = std::min(tiling.tile_height, w.region.rows - y);
    vkCmdDispatch(cmd, (tw + kWorkgroupSide - 1) / kWorkgroupSide, (th + kWorkgroupSide - 1) / kWorkgroupSide, 1);
    job.pixel_samples_done += double(tw) * th;
    job.dispatched = true;
}

// The slab's sums, to where the CPU reads them.
void make_sums_readable(VkCommandBuffer cmd, const DeviceState& s, VkDeviceSize bytes) {
    if (s.readback) {
        memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        const VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, s.pixels.get(), s.readback->get(), 1, &region);
        memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                       VK_ACCESS_HOST_READ_BIT);
    } else {
        memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                       VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    }
}

// Records and submits one batch and waits for it; returns its wall time.
double submit_batch(DeviceState& s, const Batch& batch, SlabJob& job) {
    const Clock::time_point submitted = Clock::now();
    s.context->submit_and_wait([&](VkCommandBuffer cmd) {
        if (!job.dispatched) clear_sums(cmd, s, job.bytes);
        s.timer.begin(cmd);
        bind_pipeline(cmd, s);
        for (std::uint32_t i = batch.first; i < batch.first + batch.count; ++i) dispatch_item(cmd, s, batch, i, job);
        s.timer.end(cmd);
        if (batch.last) make_sums_readable(cmd, s, job.bytes);
    });
    const double wall = seconds_since(submitted);
    if (s.timer.on_gpu()) job.gpu_seconds += s.timer.batch_seconds();
    return wall;
}

// After the tiles were split at item `item` of a work of `chunk` samples: the rest of
// that sample in the new tiles (rest_of_sample), then the samples after it.
void queue_rest_of_work(SlabJob& job, const SlabWork& w, const Tiling& tiling, std::uint32_t item,
                        std::uint32_t chunk) {
    const std::uint32_t tiles = tiling.count();
    const std::uint32_t sample = item / tiles;
    if (sample + 1 < chunk) job.work.push_back({w.region, w.first_sample + sample + 1, chunk - sample - 1});
    const std::vector<Region> rest = rest_of_sample(w.region, tiling, item % tiles);
    for (auto r = rest.rbegin(); r != rest.rend(); ++r) job.work.push_back({*r, w.first_sample + sample, 1});
}

// The slab's sums into the result. Each pixel's texels: its PixelSum, then its
// Counters, then where the result has them its PassSums (kernel/layout.glsl).
void read_sums(const DeviceState& s, const SlabJob& job, std::uint32_t width, RenderResult& result) {
    const auto* texels = static_cast<const unsigned char*>(s.readback ? s.readback->data() : s.pixels.data());
    const std::size_t first = std::size_t(job.first_row) * width;
    const std::size_t stride = std::size_t(s.paths.pixel_texels) * 16;
    const bool passes = !result.passes.empty();
    for (std::size_t p = 0; p < std::size_t(job.rows) * width; ++p) {
        const unsigned char* pixel = texels + p * stride;
        std::memcpy(&result.sums[first + p], pixel, sizeof(kernel::PixelSum));
        std::memcpy(&result.counters[first + p], pixel + sizeof(kernel::PixelSum), sizeof(kernel::Counters));
        if (passes) std::memcpy(&result.passes[first + p], pixel + kernel::PIXEL_TEXELS * 16, sizeof(kernel::PassSums));
    }
}

class VulkanBackend;

// The device state of one scene, kept for as many passes as the caller renders:
// creating the pipeline can take longer than a pass of a small image
// (docs/decisions/0014-progressive-passes-one-session.md).
class VulkanSession final : public RenderSession {
public:
    VulkanSession(VulkanBackend& backend, const FlatScene& scene);

    double setup_seconds() const override { return setup_seconds_; }
    RenderResult render(SampleRange samples, const ProgressCallback& progress) override;

private:
    RenderResult render_once(SampleRange samples, const ProgressCallback& progress);
    bool split_tiles(double costliest, const Tiling& tiling);
    void render_slab(SampleRange samples, std::uint32_t slab, std::uint32_t rows, RenderResult& result,
                     const std::function<void(double)>& progress);
    void render_work(SlabJob& job, const SlabWork& w, RenderResult& result,
                     const std::function<void(double)>& progress);
    TileBatcher& batcher_for(SlabJob& job, const Region& region, const Tiling& tiling);

    VulkanBackend& backend_;
    const FlatScene& scene_;
    std::uint32_t width_, height_;
    double bound_;
    std::unique_ptr<DeviceState> state_;
    // The largest tile wanted, and each slab's tiling and measured tile costs, kept
    // from pass to pass so that a later pass need not measure them again.
    std::uint32_t tile_width_ = kStartTileWidth, tile_height_ = kStartTileHeight;
    std::vector<Tiling> tilings_;
    std::vector<std::optional<TileBatcher>> batchers_;
    double setup_seconds_ = 0.0;
};

class VulkanBackend final : public Backend {
public:
    explicit VulkanBackend(const VulkanOptions& options)
        : options_(options), context_(std::make_shared<VulkanContext>(options)) {}

    std::string name() const override { return "vulkan"; }
    AccelPolicy accel_policy() const override {
        // The grid's arrays are part of the scene buffer: a texel buffer, a storage
        // buffer or one read by address, whichever holds most (data_paths.hpp).
        const DeviceLimits& l = context_->limits();
        AccelPolicy policy = heuristics_for(context_->cpu_device()).accel;
        policy.max_buffer_entries = std::max<std::uint64_t>(l.texel_elements, l.storage_range / 4);
        if (l.buffer_device_address) {
            policy.max_buffer_entries = std::max(policy.max_buffer_entries, max_addressed_bytes(l) / 4);
        }
        return policy;
    }
    std::string device_name() const override { return context_->properties().deviceName; }
    std::uint32_t validation_messages() const override {
        return lost_messages_ + context_->validation_messages();
    }

    std::unique_ptr<RenderSession> begin(const FlatScene& scene) override {
        if (scene.pixel_count() == 0) {
            throw GpuError("scene: the image has no pixels (" + std::to_string(scene.width()) + "x" +
                           std::to_string(scene.height()) + ")");
        }
        check_counts(scene);
        try {
            return std::make_unique<VulkanSession>(*this, scene);
        } catch (const SceneDoesNotFit& e) {
            // Unless the user named the device, one that can hold the scene is better.
            if (!options_.device.empty()) throw;
            // Aligned for any device: the largest alignment the specification allows.
            const ScenePack pack = pack_scene(scene, find_profile("minimum").limits.texel_offset_alignment / 16);
            const PhysicalDevice* other = device_for_scene(context_->devices(), data_sizes(pack, scene));
            if (!other || other->info.index == context_->device_index()) {
                throw SceneDoesNotFit(std::string(e.what()) + ", and no other Vulkan device can hold it either");
            }
            const std::uint32_t index = other->info.index;  // replace_context() frees the list
            std::fprintf(stderr, "note: %s; rendering on device %u (%s) instead\n", e.what(), index,
                         other->info.name.c_str());
            options_.device = std::to_string(index);
            replace_context();
            return std::make_unique<VulkanSession>(*this, scene);
        }
    }

    const VulkanContext& context() const { return *context_; }
    std::shared_ptr<const VulkanContext> shared_context() const { return context_; }

    // After a lost device: a new context on the same device (without the injected
    // fault of VulkanOptions::lose_device_at_submission). Should making it fail, the
    // old one stays, so the backend can still answer.
    void replace_context() {
        VulkanOptions options = options_;
        options.lose_device_at_submission = 0;
        std::shared_ptr<VulkanContext> fresh = std::make_shared<VulkanContext>(options);
        lost_messages_ += context_->validation_messages();
        context_ = std::move(fresh);
    }

private:
    VulkanOptions options_;
    std::shared_ptr<VulkanContext> context_;
    std::uint32_t lost_messages_ = 0;
};

VulkanSession::VulkanSession(VulkanBackend& backend, const FlatScene& scene)
    : backend_(backend),
      scene_(scene),
      width_(scene.width()),
      height_(scene.height()),
      bound_(backend.context().options().submit_bound_seconds > 0.0
                 ? backend.context().options().submit_bound_seconds
                 : heuristics_for(backend.context().cpu_device()).submit_bound_seconds) {
    const Clock::time_point start = Clock::now();
    state_ = std::make_unique<DeviceState>(backend_.shared_context(), scene_);
    setup_seconds_ = seconds_since(start);
}

RenderResult VulkanSession::render(SampleRange samples, const ProgressCallback& progress) {
    for (std::uint32_t resets = 0;; ++resets) {
        try {
            if (!state_) state_ = std::make_unique<DeviceState>(backend_.shared_context(), scene_);
            RenderResult result = render_once(samples, progress);
            result.device_resets = resets;
            return result;
        } catch (const DeviceLost& lost) {
            if (resets == kDeviceResets) {
                throw GpuError(std::string(lost.what()) + "; the pass failed on " + std::to_string(resets + 1) +
                               " devices in a row, giving up");
            }
            std::fprintf(stderr, "warning: %s; rendering samples %u to %u again on a new device\n", lost.what(),
                         samples.first, samples.end() - 1);
            state_.reset();
            backend_.replace_context();
        }
    }
}

RenderResult VulkanSession::render_once(SampleRange samples, const ProgressCallback& progress) {
    RenderResult result;
    result.width = width_;
    result.height = height_;
    result.sums.resize(std::size_t(width_) * height_);
    result.counters.resize(result.sums.size());
    if (scene_.features.has(Feature::HAS_PASSES)) result.passes.resize(result.sums.size());
    result.data_paths = describe(state_->paths);
    const std::uint32_t slab_rows = state_->paths.slab_rows;
    const std::uint32_t slabs = (height_ + slab_rows - 1) / slab_rows;
    result.slabs = slabs;
    if (samples.count == 0) return result;
    tilings_.resize(slabs);
    batchers_.resize(slabs);
    for (std::uint32_t slab = 0; slab < slabs; ++slab) {
        render_slab(samples, slab, std::min(slab_rows, height_ - slab * slab_rows), result, [&](double fraction) {
            if (progress) progress(std::uint32_t((slab + fraction) / slabs * kProgressUnits), kProgressUnits);
        });
    }
    const Tiling ended = tile_slab(width_, std::min(slab_rows, height_), tile_width_, tile_height_);
    result.tile_width = ended.tile_width;
    result.tile_height = ended.tile_height;
    return result;
}

// Halves the tiles until a tile of `tiling` that took `costliest` seconds, its cost
// taken as proportional to its area, would fit the bound; false when they cannot
// shrink. Every slab takes the new size; their costs are measured again.
bool VulkanSession::split_tiles(double costliest, const Tiling& tiling) {
    Tiling smaller = tiling;
    const double area = double(tiling.tile_width) * tiling.tile_height;
    bool split = false;
    while (costliest * (double(smaller.tile_width) * smaller.tile_height / area) > bound_ && smaller.split()) {
        split = true;
    }
    if (split) {
        tile_width_ = smaller.tile_width;
        tile_height_ = smaller.tile_height;
        for (std::optional<TileBatcher>& batcher : batchers_) batcher.reset();
    }
    return split;
}

void VulkanSession::render_slab(SampleRange samples, std::uint32_t slab, std::uint32_t rows, RenderResult& result,
                                const std::function<void(double)>& progress) {
    SlabJob job;
    job.index = slab;
    job.rows = rows;
    job.first_row = slab * state_->paths.slab_rows;
    job.bytes = VkDeviceSize(rows) * width_ * state_->paths.pixel_texels * 16;
    job.whole = Region{0, 0, width_, rows};
    job.work = {{job.whole, samples.first, samples.count}};
    job.pixel_samples = double(width_) * rows * samples.count;
    const Clock::time_point loop_start = Clock::now();
    while (!job.work.empty()) {
        const SlabWork w = job.work.back();
        job.work.pop_back();
        render_work(job, w, result, progress);
    }
    result.render_seconds += state_->timer.on_gpu() ? job.gpu_seconds : seconds_since(loop_start);
    read_sums(*state_, job, width_, result);
}

// Renders a work in batches; queues what is left of it when its tiles are split.
void VulkanSession::render_work(SlabJob& job, const SlabWork& w, RenderResult& result,
                                const std::function<void(double)>& progress) {
    const Tiling tiling = tile_slab(w.region.width, w.region.rows, tile_width_, tile_height_);
    TileBatcher& batcher = batcher_for(job, w.region, tiling);
    const std::uint32_t tiles = tiling.count();
    // Item numbers stay in 32 bits: a chunk of the samples, the rest later.
    const std::uint32_t chunk = std::min(w.samples, std::max(1u, (1u << 30) / tiles));
    if (chunk < w.samples) job.work.push_back({w.region, w.first_sample + chunk, w.samples - chunk});
    const std::uint32_t items = chunk * tiles;
    for (std::uint32_t item = 0; item < items;) {
        const std::uint32_t n = batcher.next(item, items - item);
        const bool last = item + n == items && job.work.empty();
        const double wall = submit_batch(*state_, {w, tiling, tiles, item, n, last}, job);
        result.longest_submit_seconds = std::max(result.longest_submit_seconds, wall);
        batcher.measured(item, n, wall);
        item += n;
        if (progress) progress(job.pixel_samples_done / job.pixel_samples);
        // A tile that alone overran the bound: smaller tiles at once, for the rest
        // of this sample, the samples after it and the next slabs.
        if (batcher.costliest() > bound_ && split_tiles(batcher.costliest(), tiling) && item < items) {
            queue_rest_of_work(job, w, tiling, item, chunk);
            return;
        }
    }
}

// The batcher of a work's tiles: for the whole slab the slab's own, whose tile costs
// are kept from pass to pass while its tiling holds; for the rest of a sample a new one.
TileBatcher& VulkanSession::batcher_for(SlabJob& job, const Region& region, const Tiling& tiling) {
    if (region != job.whole) return job.rest_batcher.emplace(tiling.count(), bound_, kMaxBatch);
    const Tiling& kept = tilings_[job.index];
    if (!batchers_[job.index] || kept.rows != job.rows || kept.tile_width != tiling.tile_width ||
        kept.tile_height != tiling.tile_height) {
        tilings_[job.index] = tiling;
        batchers_[job.index].emplace(tiling.count(), bound_, kMaxBatch);
    }
    return *batchers_[job.index];
}

}  // namespace

std::unique_ptr<Backend> make_vulkan_backend(const VulkanOptions& options) {
    return std::make_unique<VulkanBackend>(options);
}

}  // namespace vkrt
