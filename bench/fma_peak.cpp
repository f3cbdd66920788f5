#include "bench/fma_peak.h"

#include "gpu/context_impl.h"
#include "gpu/shader_compiler.h"
#include "util/error.h"

#include <time.h>
#include <algorithm>
#include <chrono>
#include <utility>

namespace vkray::bench {

namespace {

double cpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Parameters {
    std::uint32_t iterations;
    float m, c;
};

}  // namespace

FmaPeak measureFmaPeak(gpu::Context& context, const std::string& shaderDirectory, int chains,
                       int runs, double targetSeconds) {
    gpu::Context::Impl& c = context.impl();
    const std::vector<std::uint32_t> spirv = gpu::compileComputeShader(
        {shaderDirectory, "fma_peak.comp", {{"CHAINS", std::to_string(chains)}}});

    constexpr std::uint32_t kLocalSize = 64, kGroups = 2048;
    constexpr std::uint32_t kInvocations = kLocalSize * kGroups;
    gpu::HostBuffer result(c, kInvocations * 16, vk::BufferUsageFlagBits::eStorageBuffer);

    const vk::DescriptorSetLayoutBinding binding(0, vk::DescriptorType::eStorageBuffer, 1,
                                                 vk::ShaderStageFlagBits::eCompute);
    vk::raii::DescriptorSetLayout setLayout(c.device, {{}, binding});
    const vk::PushConstantRange push(vk::ShaderStageFlagBits::eCompute, 0, sizeof(Parameters));
    vk::raii::PipelineLayout layout(c.device, {{}, *setLayout, push});
    vk::raii::ShaderModule module(c.device, {{}, spirv});
    vk::raii::Pipeline pipeline(
        c.device, nullptr,
        vk::ComputePipelineCreateInfo({}, {{}, vk::ShaderStageFlagBits::eCompute, *module, "main"},
                                      *layout));
    const vk::DescriptorPoolSize poolSize(vk::DescriptorType::eStorageBuffer, 1);
    vk::raii::DescriptorPool pool(
        c.device, {vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, 1, poolSize});
    vk::raii::DescriptorSet set =
        std::move(vk::raii::DescriptorSets(c.device, {*pool, *setLayout}).front());
    const vk::DescriptorBufferInfo info(result.buffer(), 0, VK_WHOLE_SIZE);
    c.device.updateDescriptorSets(
        vk::WriteDescriptorSet(*set, 0, 0, 1, vk::DescriptorType::eStorageBuffer, nullptr, &info),
        nullptr);
    vk::raii::CommandBuffer commands = std::move(
        vk::raii::CommandBuffers(c.device, {*c.commandPool, vk::CommandBufferLevel::ePrimary, 1})
            .front());
    vk::raii::Fence fence(c.device, vk::FenceCreateInfo{});

    const auto run = [&](std::uint32_t iterations) {
        commands.reset();
        commands.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
        commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline);
        commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *layout, 0, *set, nullptr);
        commands.pushConstants<Parameters>(*layout, vk::ShaderStageFlagBits::eCompute, 0,
                                           Parameters{iterations, 0.999f, 1e-3f});
        commands.dispatch(kGroups, 1, 1);
        commands.end();
        const auto start = std::chrono::steady_clock::now();
        const double cpuStart = cpuSeconds();
        c.queue.submit(vk::SubmitInfo({}, {}, *commands), *fence);
        if (c.device.waitForFences(*fence, VK_TRUE, UINT64_MAX) != vk::Result::eSuccess)
            throw Error("the FMA benchmark did not finish");
        c.device.resetFences(*fence);
        return std::pair(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
            cpuSeconds() - cpuStart);
    };

    // Size the loop from a short run (after one that JIT-compiles), then measure.
    std::uint32_t iterations = 256;
    run(iterations);
    const double probe = std::max(run(iterations).second, 1e-4);
    iterations = std::uint32_t(std::clamp(iterations * targetSeconds / probe, 256.0, 1e7));
    FmaPeak best;
    best.chains = chains;
    best.flops = 2.0 * 4.0 * chains * double(iterations) * kInvocations;
    for (int r = 0; r < runs; ++r) {
        const auto [wall, cpu] = run(iterations);
        if (best.seconds == 0 || wall < best.seconds) best.seconds = wall;
        if (best.cpuSeconds == 0 || cpu < best.cpuSeconds) best.cpuSeconds = cpu;
    }
    best.gflops = best.flops / best.seconds * 1e-9;
    return best;
}

}  // namespace vkray::bench
