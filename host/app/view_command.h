// `vkray view SCENE`: a window that renders the scene progressively (blocks
// of 16, 8, 4, 2 and 1 pixels, then one more sample a pass up to --spp),
// lets the mouse move the camera, shows AOVs, the CPU reference and the
// difference, and reloads when the scene, a file it reads or a shader
// changes (docs/usage.md, "vkray view").
#pragma once

#include "app/options.h"
#include "render/camera.h"

#include <iosfwd>
#include <string>
#include <vector>

namespace vkray {

// One step of the progression: what the tracer renders, and how its tiles
// join the picture (fresh: they replace it; else they add a sample).
struct ViewPass {
    RenderSettings settings;
    bool fresh = true;
    std::string name;  // "block 16", "block 1, sample 3 of 16"
};

// Blocks 16, 8, 4 and 2 (one sample at the block's centre, as `render
// --block B`), then the spp samples of `render --spp N` one a pass: after
// the last, the picture is that render's.
std::vector<ViewPass> viewProgression(int width, int height, int spp, std::uint32_t seed);

// Exit status 0, or 1 when an error stands at the end (it is printed).
int runView(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace vkray
