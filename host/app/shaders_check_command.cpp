#include "app/shaders_check_command.h"

#include "app/commands.h"
#include "gpu/shader_variant.h"
#include "gpu/spirv_cache.h"
#include "util/error.h"
#include "util/stopwatch.h"

#include <ostream>

namespace vkray {

int runShadersCheck(const Options& o, std::ostream& out, std::ostream& err) {
    const std::string directory = shaderDirectoryFor(o);
    int failures = 0;
    const std::vector<gpu::ShaderFeatures> variants = gpu::allVariants(o.everyVariant);
    for (const gpu::ShaderFeatures& features : variants) {
        const Stopwatch stopwatch;
        try {
            gpu::compileComputeShader({directory, "trace.comp",
                                       gpu::definesFor(features, precisionDefines(o.precision))});
            out << "ok    " << gpu::describe(features) << " ("
                << fixedDigits(stopwatch.seconds(), 2) << " s)\n";
        } catch (const Error& e) {
            ++failures;
            out << "FAIL  " << gpu::describe(features) << "\n";
            err << e.what() << "\n";
        }
    }
    out << variants.size() - failures << " of " << variants.size() << " variants compiled ("
        << precisionName(o.precision) << ")"
        << (failures ? ", " + std::to_string(failures) + " failed" : std::string()) << "\n";
    return failures ? 1 : 0;
}

}  // namespace vkray
