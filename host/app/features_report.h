// `vkray features SCENE`: what the renderer will leave in and out for a
// scene, as host/gpu/shader_variant.h computes it (the same functions the
// tracer calls), and the buffers that variant binds and uploads.
#pragma once

#include "gpu/precision.h"
#include "gpu/shader_variant.h"
#include "scene/scene.h"

#include <string>

namespace vkray {

// The report, given the scene, the render settings (--spp), its variant's features and defines (the
// variant's own and the user's -D) and the variant's SPIR-V cache key.
std::string formatFeatureReport(const Scene& scene, const RenderSettings& settings,
                                const gpu::ShaderFeatures& features, Precision precision,
                                const gpu::Defines& defines, const std::string& key);

}  // namespace vkray
