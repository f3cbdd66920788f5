#include "app/pixel_command.h"

#include "app/commands.h"
#include "app/pixel_report.h"
#include "reference/reference_tracer.h"
#include "render/camera.h"

#include <ostream>

namespace vkray {

int runPixel(const Options& o, std::ostream& out, std::ostream& err) {
    const Scene scene = loadSceneFor(o, err);
    RenderSettings settings{o.width, o.height, o.block, o.spp, o.seed};
    settings.firstSample = o.pixelSample;
    settings.sampleCount = 1;
    const CameraBasis camera = makeCameraBasis(chooseCamera(scene, o), o.width, o.height);
    // The mode `render` would trace in: auto chooses it from the scene, as there.
    Options run = o;
    run.precision = precisionInForce(scene, camera, o, out, err).precision;
    GpuSession session;
    gpu::GpuRenderStats stats;
    const PixelTrace gpu =
        session.tracerFor(run, out).tracePixel(scene, camera, settings, o.pixelX, o.pixelY, &stats);
    reportShader(stats, run, out);
    session.requireNoValidationMessages(run);
    const PixelTrace cpu = reference::tracePixel(scene, camera, settings, o.pixelX, o.pixelY);
    out << formatPixelReport(scene, settings, gpu, cpu);
    return 0;
}

}  // namespace vkray
