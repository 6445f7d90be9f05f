// The Vulkan backend: one compute pipeline specialised for the scene's feature set,
// one dispatch per sample index, submitted in batches sized to the device's speed.
#include "gpu/vulkan_backend.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "gpu/vulkan_buffer.hpp"
#include "gpu/vulkan_context.hpp"
#include "render_comp_spv.h"

namespace vkrt {

namespace {

using namespace gpu;
using Clock = std::chrono::steady_clock;

// Binding numbers of shaders/render.comp.
enum Binding : std::uint32_t {
    kParams, kMaterials, kSpheres, kTriangles, kLights, kAccum, kCounters, kBindingCount
};
constexpr std::uint32_t kLocalSize = 8;     // local_size_x and _y of render.comp

// Every binding but the params is a texel buffer of 16-byte texels (see render.comp
// for why): read-only scene arrays as uniform texel buffers, the sums as storage ones.
VkDescriptorType descriptor_type(std::uint32_t binding) {
    switch (binding) {
    case kParams: return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case kAccum:
    case kCounters: return VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
    default: return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    }
}
VkFormat texel_format(std::uint32_t binding) {
    return binding == kAccum ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R32G32B32A32_UINT;
}
constexpr VkBufferUsageFlags kSceneUsage = VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
constexpr VkBufferUsageFlags kSumsUsage = VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT;
constexpr std::uint32_t kPushBytes = 16;    // uvec4 pass
constexpr double kTargetSubmitSeconds = 0.25;
constexpr std::uint32_t kMaxBatch = 256;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// Short submissions keep a GPU's watchdog away and the progress callback lively;
// long ones amortise the per-submission cost. Aim between: about kTargetSubmitSeconds.
// Growth and shrinkage are limited to 4x per step because the first, tiny batches
// are dominated by fixed costs and would suggest far too large a jump.
std::uint32_t next_batch(std::uint32_t batch, double seconds) {
    const double scale = seconds > 0.0 ? std::clamp(kTargetSubmitSeconds / seconds, 0.25, 4.0) : 4.0;
    const double next = std::round(batch * scale);
    return static_cast<std::uint32_t>(std::clamp(next, 1.0, double(kMaxBatch)));
}

void compute_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stage, VkAccessFlags src_access) {
    VkMemoryBarrier b{};
    b.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    b.srcAccessMask = src_access;
    b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, src_stage, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &b, 0, nullptr,
                         0, nullptr);
}

// The pipeline and its descriptor set. Members are destroyed in reverse order.
struct Pipeline {
    DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout> set_layout;
    DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout> layout;
    DeviceHandle<VkPipeline, vkDestroyPipeline> pipeline;
    DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool> pool;
    VkDescriptorSet set = VK_NULL_HANDLE;  // freed with the pool
};

Pipeline make_pipeline(const VulkanContext& context, const FeatureSet& features) {
    const VkDevice device = context.device();
    Pipeline p;

    std::array<VkDescriptorSetLayoutBinding, kBindingCount> bindings{};
    for (std::uint32_t i = 0; i < kBindingCount; ++i) {
        bindings[i].binding = i;
        bindings[i].descriptorType = descriptor_type(i);
        bindings[i].descriptorCount = 1;
        bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    VkDescriptorSetLayoutCreateInfo set_info{};
    set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    set_info.bindingCount = kBindingCount;
    set_info.pBindings = bindings.data();
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    check(vkCreateDescriptorSetLayout(device, &set_info, nullptr, &set_layout), "vkCreateDescriptorSetLayout");
    p.set_layout = {device, set_layout};

    const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, kPushBytes};
    VkPipelineLayoutCreateInfo layout_info{};
    layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout;
    layout_info.pushConstantRangeCount = 1;
    layout_info.pPushConstantRanges = &push;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    check(vkCreatePipelineLayout(device, &layout_info, nullptr, &layout), "vkCreatePipelineLayout");
    p.layout = {device, layout};

    VkShaderModuleCreateInfo module_info{};
    module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    module_info.codeSize = sizeof(render_comp_spv);
    module_info.pCode = render_comp_spv;
    VkShaderModule raw_module = VK_NULL_HANDLE;
    check(vkCreateShaderModule(device, &module_info, nullptr, &raw_module), "vkCreateShaderModule");
    const DeviceHandle<VkShaderModule, vkDestroyShaderModule> module(device, raw_module);

    // One VkBool32 per feature, constant_id = feature id: a feature that is off is
    // compiled out by the driver.
    std::array<VkBool32, kFeatureCount> values{};
    std::array<VkSpecializationMapEntry, kFeatureCount> entries{};
    for (std::uint32_t id = 0; id < kFeatureCount; ++id) {
        values[id] = features.has(id) ? VK_TRUE : VK_FALSE;
        entries[id] = {id, std::uint32_t(id * sizeof(VkBool32)), sizeof(VkBool32)};
    }
    VkSpecializationInfo specialization{};
    specialization.mapEntryCount = kFeatureCount;
    specialization.pMapEntries = entries.data();
    specialization.dataSize = sizeof(values);
    specialization.pData = values.data();

    VkComputePipelineCreateInfo pipeline_info{};
    pipeline_info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    pipeline_info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_info.stage.module = raw_module;
    pipeline_info.stage.pName = "main";
    pipeline_info.stage.pSpecializationInfo = &specialization;
    pipeline_info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    check(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &pipeline),
          "vkCreateComputePipelines");
    p.pipeline = {device, pipeline};

    const std::array<VkDescriptorPoolSize, 3> sizes{{
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
        {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, kBindingCount - 3},
        {VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, 2},
    }};
    VkDescriptorPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = sizes.size();
    pool_info.pPoolSizes = sizes.data();
    VkDescriptorPool pool = VK_NULL_HANDLE;
    check(vkCreateDescriptorPool(device, &pool_info, nullptr, &pool), "vkCreateDescriptorPool");
    p.pool = {device, pool};

    VkDescriptorSetAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    alloc.descriptorPool = pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &set_layout;
    check(vkAllocateDescriptorSets(device, &alloc, &p.set), "vkAllocateDescriptorSets");
    return p;
}

using BufferView = DeviceHandle<VkBufferView, vkDestroyBufferView>;

// Writes the set; returns the texel-buffer views, which must outlive its use.
std::vector<BufferView> write_descriptors(VkDevice device, VkDescriptorSet set,
                                          const std::array<const VulkanBuffer*, kBindingCount>& buffers) {
    std::vector<BufferView> views;
    std::array<VkDescriptorBufferInfo, kBindingCount> infos{};
    std::array<VkBufferView, kBindingCount> raw_views{};
    std::array<VkWriteDescriptorSet, kBindingCount> writes{};
    for (std::uint32_t i = 0; i < kBindingCount; ++i) {
        writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        writes[i].dstSet = set;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = descriptor_type(i);
        if (i == kParams) {
            infos[i] = {buffers[i]->get(), 0, VK_WHOLE_SIZE};
            writes[i].pBufferInfo = &infos[i];
            continue;
        }
        VkBufferViewCreateInfo view_info{};
        view_info.sType = VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO;
        view_info.buffer = buffers[i]->get();
        view_info.format = texel_format(i);
        view_info.range = VK_WHOLE_SIZE;
        check(vkCreateBufferView(device, &view_info, nullptr, &raw_views[i]), "vkCreateBufferView");
        views.emplace_back(device, raw_views[i]);
        writes[i].pTexelBufferView = &raw_views[i];
    }
    vkUpdateDescriptorSets(device, kBindingCount, writes.data(), 0, nullptr);
    return views;
}

// A scene array as a buffer, or nothing when the scene leaves it out.
template <typename T>
std::optional<VulkanBuffer> array_buffer(const VulkanContext& context, const char* name,
                                         const std::vector<T>& items) {
    if (items.empty()) {
        return std::nullopt;
    }
    std::optional<VulkanBuffer> buffer;
    buffer.emplace(context, name, items.size() * sizeof(T), kSceneUsage);
    buffer->upload(items.data(), buffer->size());
    return buffer;
}

// The kernel trusts the counts in Params; an index past a buffer's end would be an
// out-of-bounds read on the device, so the counts are checked here, once.
void check_counts(const SceneGpu& scene) {
    const kernel::Params& p = scene.params;
    auto fail = [](const char* what, std::size_t count, std::size_t size) {
        throw GpuError(std::string("scene: params count of ") + what + " (" + std::to_string(count) +
                       ") exceeds its buffer (" + std::to_string(size) + ")");
    };
    if (scene.features.has(Feature::HAS_SPHERES) && p.counts.x > scene.spheres.size()) {
        fail("spheres", p.counts.x, scene.spheres.size());
    }
    if (scene.features.has(Feature::HAS_TRIANGLES) && p.counts.y > scene.triangles.size()) {
        fail("triangles", p.counts.y, scene.triangles.size());
    }
    if (scene.features.has(Feature::HAS_POINT_LIGHTS) && p.counts.z > scene.lights.size()) {
        fail("point lights", p.counts.z, scene.lights.size());
    }
    if (p.counts.w > scene.materials.size()) {
        fail("materials", p.counts.w, scene.materials.size());
    }
}

// The whole-render timer: GPU timestamps around each batch where the queue has them.
class BatchTimer {
public:
    explicit BatchTimer(const VulkanContext& context) : context_(context) {
        if (context.timestamp_valid_bits() == 0) {
            return;
        }
        VkQueryPoolCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
        info.queryType = VK_QUERY_TYPE_TIMESTAMP;
        info.queryCount = 2;
        VkQueryPool pool = VK_NULL_HANDLE;
        check(vkCreateQueryPool(context.device(), &info, nullptr, &pool), "vkCreateQueryPool");
        pool_ = {context.device(), pool};
    }
    bool on_gpu() const { return pool_.get() != VK_NULL_HANDLE; }

    void begin(VkCommandBuffer cmd) const {
        if (on_gpu()) {
            vkCmdResetQueryPool(cmd, pool_.get(), 0, 2);
            vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, pool_.get(), 0);
        }
    }
    void end(VkCommandBuffer cmd) const {
        if (on_gpu()) {
            vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_.get(), 1);
        }
    }
    // After the batch's fence: its GPU time, in seconds.
    double batch_seconds() const {
        std::array<std::uint64_t, 2> ticks{};
        check(vkGetQueryPoolResults(context_.device(), pool_.get(), 0, 2, sizeof(ticks), ticks.data(),
                                    sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              "vkGetQueryPoolResults");
        const std::uint32_t bits = context_.timestamp_valid_bits();
        const std::uint64_t mask = bits >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << bits) - 1;
        const std::uint64_t elapsed = (ticks[1] - ticks[0]) & mask;  // survives one wrap-around
        return double(elapsed) * context_.properties().limits.timestampPeriod * 1e-9;
    }

private:
    const VulkanContext& context_;
    DeviceHandle<VkQueryPool, vkDestroyQueryPool> pool_;
};

class VulkanBackend final : public Backend {
public:
    explicit VulkanBackend(const VulkanOptions& options) : context_(options) {}

    std::string name() const override { return "vulkan"; }
    std::string device_name() const override { return context_.properties().deviceName; }
    std::uint32_t validation_messages() const override { return context_.validation_messages(); }

    RenderResult render(const SceneGpu& scene, SampleRange samples,
                        const ProgressCallback& progress) override;

private:
    VulkanContext context_;
};

RenderResult VulkanBackend::render(const SceneGpu& scene, SampleRange samples,
                                   const ProgressCallback& progress) {
    const std::uint32_t width = scene.width();
    const std::uint32_t height = scene.height();
    const std::size_t pixels = scene.pixel_count();
    if (pixels == 0) {
        throw GpuError("scene: the image has no pixels (" + std::to_string(width) + "x" +
                       std::to_string(height) + ")");
    }
    const std::uint32_t groups_x = (width + kLocalSize - 1) / kLocalSize;
    const std::uint32_t groups_y = (height + kLocalSize - 1) / kLocalSize;
    const VkPhysicalDeviceLimits& limits = context_.properties().limits;
    if (groups_x > limits.maxComputeWorkGroupCount[0] || groups_y > limits.maxComputeWorkGroupCount[1]) {
        throw GpuError("image " + std::to_string(width) + "x" + std::to_string(height) +
                       " needs more workgroups than this device dispatches at once");
    }
    check_counts(scene);

    const Clock::time_point setup_start = Clock::now();
    const Pipeline pipeline = make_pipeline(context_, scene.features);

    VulkanBuffer params(context_, "params", sizeof(kernel::Params), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    params.upload(&scene.params, sizeof(kernel::Params));
    // Stands in for every array the scene leaves out: the shader still declares the
    // binding, but with the feature off nothing reads it.
    VulkanBuffer dummy(context_, "unused", 16, kSceneUsage);
    const std::optional<VulkanBuffer> materials = array_buffer(context_, "materials", scene.materials);
    const std::optional<VulkanBuffer> spheres = array_buffer(context_, "spheres", scene.spheres);
    const std::optional<VulkanBuffer> triangles = array_buffer(context_, "triangles", scene.triangles);
    const std::optional<VulkanBuffer> lights = array_buffer(context_, "lights", scene.lights);
    VulkanBuffer accum(context_, "accum", pixels * sizeof(glm::vec4), kSumsUsage);
    VulkanBuffer counters(context_, "counters", pixels * sizeof(glm::uvec4), kSumsUsage);

    auto or_dummy = [&](const std::optional<VulkanBuffer>& b) { return b ? &*b : &dummy; };
    const std::vector<BufferView> views = write_descriptors(context_.device(), pipeline.set,
                      {&params, or_dummy(materials), or_dummy(spheres), or_dummy(triangles),
                       or_dummy(lights), &accum, &counters});
    context_.submit_and_wait([&](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, accum.get(), 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cmd, counters.get(), 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cmd, dummy.get(), 0, VK_WHOLE_SIZE, 0);
        compute_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    });
    const BatchTimer timer(context_);

    RenderResult result;
    result.width = width;
    result.height = height;
    result.setup_seconds = seconds_since(setup_start);

    const Clock::time_point loop_start = Clock::now();
    double gpu_seconds = 0.0;
    std::uint32_t batch = 1;
    for (std::uint32_t done = 0; done < samples.count;) {
        const std::uint32_t n = std::min(batch, samples.count - done);
        const std::uint32_t begin = samples.first + done;
        const Clock::time_point submitted = Clock::now();
        context_.submit_and_wait([&](VkCommandBuffer cmd) {
            timer.begin(cmd);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline.get());
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout.get(), 0, 1,
                                    &pipeline.set, 0, nullptr);
            for (std::uint32_t s = begin; s < begin + n; ++s) {
                // Each dispatch adds to the sums the previous one wrote (also across
                // batches: a barrier's scope spans earlier submissions).
                if (s != samples.first) {
                    compute_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
                }
                const std::array<std::uint32_t, 4> pass{s, 0, 0, 0};
                vkCmdPushConstants(cmd, pipeline.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, kPushBytes,
                                   pass.data());
                vkCmdDispatch(cmd, groups_x, groups_y, 1);
            }
            timer.end(cmd);
        });
        const double wall = seconds_since(submitted);
        if (timer.on_gpu()) {
            gpu_seconds += timer.batch_seconds();
        }
        done += n;
        if (progress) {
            progress(done, samples.count);
        }
        batch = next_batch(n, wall);
    }
    result.render_seconds = timer.on_gpu() ? gpu_seconds : seconds_since(loop_start);

    result.accum.resize(pixels);
    result.counters.resize(pixels);
    accum.readback(result.accum.data(), accum.size());
    counters.readback(result.counters.data(), counters.size());
    return result;
}

}  // namespace

std::vector<DeviceInfo> list_vulkan_devices() {
    const VulkanInstance instance(false);
    std::vector<DeviceInfo> infos;
    for (const PhysicalDevice& d : instance.devices()) {
        infos.push_back(d.info);
    }
    return infos;
}

std::unique_ptr<Backend> make_vulkan_backend(const VulkanOptions& options) {
    return std::make_unique<VulkanBackend>(options);
}

}  // namespace vkrt
