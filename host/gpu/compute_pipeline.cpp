#include "gpu/compute_pipeline.h"

#include "util/error.h"

#include <map>
#include <string>
#include <utility>

namespace vkray::gpu {

ComputePipeline::ComputePipeline(Context::Impl& c, const std::vector<std::uint32_t>& spirv,
                                 std::vector<ComputeBinding> bindingList,
                                 std::uint32_t pushConstantBytes)
    : bindings(std::move(bindingList)) {
    std::vector<vk::DescriptorSetLayoutBinding> layoutBindings;
    for (const ComputeBinding& b : bindings)
        layoutBindings.emplace_back(b.binding, b.type, 1, vk::ShaderStageFlagBits::eCompute);
    setLayout = vk::raii::DescriptorSetLayout(c.device, {{}, layoutBindings});
    const vk::PushConstantRange pushRange(vk::ShaderStageFlagBits::eCompute, 0, pushConstantBytes);
    vk::PipelineLayoutCreateInfo layoutInfo({}, *setLayout);
    if (pushConstantBytes > 0) layoutInfo.setPushConstantRanges(pushRange);
    layout = vk::raii::PipelineLayout(c.device, layoutInfo);
    module = vk::raii::ShaderModule(c.device, {{}, spirv});
    pipeline = vk::raii::Pipeline(
        c.device, nullptr,
        vk::ComputePipelineCreateInfo({}, {{}, vk::ShaderStageFlagBits::eCompute, *module, "main"},
                                      *layout));
}

DescriptorSet::DescriptorSet(Context::Impl& c, const ComputePipeline& pipeline) {
    std::map<vk::DescriptorType, std::uint32_t> counts;
    for (const ComputeBinding& b : pipeline.bindings) ++counts[b.type];
    std::vector<vk::DescriptorPoolSize> sizes;
    for (const auto& [type, count] : counts) sizes.emplace_back(type, count);
    pool = vk::raii::DescriptorPool(
        c.device, {vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, 1, sizes});
    set = std::move(vk::raii::DescriptorSets(c.device, {*pool, *pipeline.setLayout}).front());
}

vk::raii::CommandBuffer makeCommandBuffer(Context::Impl& c) {
    return std::move(
        vk::raii::CommandBuffers(c.device, {*c.commandPool, vk::CommandBufferLevel::ePrimary, 1})
            .front());
}

void submitAndWait(Context::Impl& c, const vk::SubmitInfo& submit, const vk::raii::Fence& fence,
                   const char* what) {
    c.queue.submit(submit, *fence);
    if (c.device.waitForFences(*fence, VK_TRUE, UINT64_MAX) != vk::Result::eSuccess)
        throw Error(std::string("the GPU did not finish ") + what);
    c.device.resetFences(*fence);
}

}  // namespace vkray::gpu
