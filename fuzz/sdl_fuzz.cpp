// Fuzzes the SDL reader: tokens, def/use expansion (with small limits, so a
// pasting bomb stops quickly instead of running out of memory), strict and
// lenient parsing, then what the renderers check before drawing (supported
// shapes, the camera). Any exception other than vkray::Error is a bug.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "render/camera.h"
#include "scene/sdl_reader.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    for (const bool lenient : {false, true}) {
        vkray::SdlOptions options;
        options.lenient = lenient;
        options.maxExpandedTokens = 20'000;
        options.maxUseDepth = 16;
        std::vector<std::string> warnings;
        try {
            vkray::Scene scene = vkray::parseSdl(text, "fuzz.sdl", options, &warnings);
            const vkray::Camera camera = scene.camera.value_or(vkray::autoCamera(scene));
            vkray::makeCameraBasis(camera, 64, 48);
        } catch (const vkray::Error&) {
            // A refused input: what the reader is for.
        }
    }
    return 0;
}
