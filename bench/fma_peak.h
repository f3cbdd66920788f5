// A microbenchmark of the Vulkan device's peak fused multiply-add rate
// (bench/shaders/fma_peak.comp), to put the tracer's arithmetic in proportion.
#pragma once

#include "gpu/context.h"

#include <string>

namespace vkray::bench {

struct FmaPeak {
    double gflops = 0;      // best of the runs: 2 flops per FMA per component
    double seconds = 0;     // wall clock of the fastest run
    double cpuSeconds = 0;  // CPU time (all threads) of the run with the least
    double flops = 0;       // per run
    int chains = 0;         // independent vec4 chains per invocation
};

// Runs the shader (from shaderDirectory) `runs` times, sized to take about
// `targetSeconds` each, and keeps the fastest.
FmaPeak measureFmaPeak(gpu::Context& context, const std::string& shaderDirectory, int chains,
                       int runs = 3, double targetSeconds = 0.4);

}  // namespace vkray::bench
