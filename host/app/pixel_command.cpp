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
    GpuSession session;
    gpu::GpuRenderStats stats;
    const PixelTrace gpu =
        session.tracerFor(o, out).tracePixel(scene, camera, settings, o.pixelX, o.pixelY, &stats);
    reportShader(stats, o, out);
    session.requireNoValidationMessages(o);
    const PixelTrace cpu = reference::tracePixel(scene, camera, settings, o.pixelX, o.pixelY);
    out << formatPixelReport(scene, settings, gpu, cpu);
    return 0;
}

}  // namespace vkray
