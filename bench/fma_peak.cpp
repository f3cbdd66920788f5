#include "bench/fma_peak.h"

#include "gpu/compute_pipeline.h"
#include "gpu/shader_compiler.h"
#include "util/stopwatch.h"

#include <algorithm>
#include <chrono>
#include <utility>

namespace vkray::bench {

namespace {

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

    const gpu::ComputePipeline pipeline(c, spirv, {{0, vk::DescriptorType::eStorageBuffer}},
                                        sizeof(Parameters));
    const gpu::DescriptorSet set(c, pipeline);
    const vk::DescriptorBufferInfo info(result.buffer(), 0, VK_WHOLE_SIZE);
    c.device.updateDescriptorSets(
        vk::WriteDescriptorSet(*set.set, 0, 0, 1, vk::DescriptorType::eStorageBuffer, nullptr,
                               &info),
        nullptr);
    vk::raii::CommandBuffer commands = gpu::makeCommandBuffer(c);
    vk::raii::Fence fence(c.device, vk::FenceCreateInfo{});

    const auto run = [&](std::uint32_t iterations) {
        commands.reset();
        commands.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
        commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline.pipeline);
        commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline.layout, 0, *set.set,
                                    nullptr);
        commands.pushConstants<Parameters>(*pipeline.layout, vk::ShaderStageFlagBits::eCompute, 0,
                                           Parameters{iterations, 0.999f, 1e-3f});
        commands.dispatch(kGroups, 1, 1);
        commands.end();
        const auto start = std::chrono::steady_clock::now();
        const double cpuStart = processCpuSeconds();
        gpu::submitAndWait(c, vk::SubmitInfo({}, {}, *commands), fence, "the FMA benchmark");
        return std::pair(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
            processCpuSeconds() - cpuStart);
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
