#include "app/features_command.h"

#include "app/commands.h"
#include "app/features_report.h"
#include "gpu/shader_variant.h"
#include "gpu/spirv_cache.h"

#include <ostream>

namespace vkray {

int runFeatures(const Options& o, std::ostream& out, std::ostream& err) {
    const Scene scene = loadSceneFor(o, err);
    RenderSettings settings;
    settings.spp = o.spp;
    settings.aovs = false;  // as `render` without --aov
    const gpu::ShaderFeatures features = gpu::variantFeatures(
        scene, settings, o.allFeatures, o.precision, chooseCamera(scene, o).eye,
        std::numeric_limits<std::uint64_t>::max());  // no device here
    const gpu::ShaderSource source =
        gpu::variantSource(shaderDirectoryFor(o), features, o.precision, o.defines);
    out << formatFeatureReport(scene, settings, features, o.precision, source.defines,
                               gpu::spirvCacheKey(source));
    return 0;
}

}  // namespace vkray
