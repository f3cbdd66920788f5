// Fuzzes the 2D outline reader of `extrude`. Any exception other than
// vkray::Error is a bug; an accepted outline has at least 3 finite points.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "scene/mesh_file.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const vkray::Outline outline = vkray::parseOutline(text, "fuzz.dat");
        if (outline.points.size() < 3) __builtin_trap();
        for (const auto& p : outline.points)
            if (!std::isfinite(p.x) || !std::isfinite(p.y)) __builtin_trap();
    } catch (const vkray::Error&) {
    }
    return 0;
}
