#include "app/features_command.h"

#include "app/commands.h"
#include "app/features_report.h"
#include "gpu/context.h"
#include "gpu/shader_variant.h"
#include "gpu/spirv_cache.h"
#include "gpu/traversal.h"

#include <ostream>
#include <sstream>

namespace vkray {

int runFeatures(const Options& o, std::ostream& out, std::ostream& err) {
    const Scene scene = loadSceneFor(o, err);
    RenderSettings settings;
    settings.spp = o.spp;
    settings.aovs = false;  // as `render` without --aov
    const Camera camera = chooseCamera(scene, o);
    // The precision `render` would run in, and why; its line goes after the report's.
    std::ostringstream choice;
    const Precision precision =
        precisionInForce(scene, makeCameraBasis(camera, o.width, o.height), o, choice, err)
            .precision;
    gpu::ShaderFeatures features =
        gpu::variantFeatures(scene, settings, o.allFeatures, precision, camera.eye,
                             std::numeric_limits<std::uint64_t>::max());
    // The walk `render` would take on the device it would pick; with no
    // Vulkan device at all, the own walk (`render` would refuse).
    gpu::DeviceInfo device;
    device.name = "no Vulkan device";
    try {
        device = gpu::Context({.deviceIndex = o.device}).device();
    } catch (const Error&) {
        if (o.traversal == gpu::Traversal::RayQuery) throw;
    }
    const std::string traversal = gpu::chooseTraversal(o.traversal, device, scene, features);
    const gpu::ShaderSource source =
        gpu::variantSource(shaderDirectoryFor(o), features, precision, o.defines);
    out << formatFeatureReport(scene, settings, features, precision, source.defines,
                               gpu::spirvCacheKey(source))
        << "traversal: " << traversal << "\n"
        << choice.str();
    return 0;
}

}  // namespace vkray
