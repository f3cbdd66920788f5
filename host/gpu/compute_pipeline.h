// One compute shader made ready to dispatch: its descriptor-set layout,
// pipeline layout, module and pipeline, and the command buffer, fence and
// descriptor set a dispatch needs. The trace pass, the view's presenter and
// the benchmark's FMA peak all build theirs here.
#pragma once

#include "gpu/context_impl.h"
#include "gpu/vulkan_pch.h"

#include <cstdint>
#include <vector>

namespace vkray::gpu {

struct ComputeBinding {
    std::uint32_t binding;
    vk::DescriptorType type;
};

// Member order fixes destruction order: the pipeline goes before its layouts.
struct ComputePipeline {
    // pushConstantBytes: the size of the shader's push-constant block (0: none).
    // lavapipe compiles the SPIR-V to machine code here.
    ComputePipeline(Context::Impl& c, const std::vector<std::uint32_t>& spirv,
                    std::vector<ComputeBinding> bindings, std::uint32_t pushConstantBytes);

    std::vector<ComputeBinding> bindings;
    vk::raii::DescriptorSetLayout setLayout = nullptr;
    vk::raii::PipelineLayout layout = nullptr;
    vk::raii::ShaderModule module = nullptr;
    vk::raii::Pipeline pipeline = nullptr;
};

// One descriptor set of a pipeline's layout, from a pool of its own sized
// for exactly its bindings.
struct DescriptorSet {
    DescriptorSet(Context::Impl& c, const ComputePipeline& pipeline);

    vk::raii::DescriptorPool pool = nullptr;
    vk::raii::DescriptorSet set = nullptr;
};

vk::raii::CommandBuffer makeCommandBuffer(Context::Impl& c);

// Submits `submit` (its command buffers and semaphores), waits for it on
// `fence` and resets the fence; `what` names the work in the error if the
// wait fails.
void submitAndWait(Context::Impl& c, const vk::SubmitInfo& submit, const vk::raii::Fence& fence,
                   const char* what);

}  // namespace vkray::gpu
