// The one rule every GPU-vs-CPU-reference check applies (`render --check`,
// `vkray difftest`, the view's difference mode, tests/gpu): a pixel may
// differ only where the reference, with every ray of it moved by the GPU
// mode's error bound, can itself give the GPU's value (reference/margins.h).
// Those pixels are set aside and counted; every other differing pixel is a
// failure, whatever the image size, spp or block. Colours are compared
// unclamped; depth and normal where both hit the same object.
#pragma once

#include "gpu/precision.h"
#include "image/frame.h"
#include "image/image.h"
#include "reference/margins.h"
#include "render/camera.h"
#include "scene/scene.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace vkray {

// A GPU mode's error bound: 64 u of its geometry's arithmetic (the
// robust shader's own secondary-ray offset, 2^-18 of the distance from the
// eye, is sized the same: float's error, with room for its roundings), its
// directions' and its textures'; naive adds its fixed epsilon, 1e-4.
reference::ErrorBound errorBoundOf(Precision precision);

struct AgreementOptions {
    // A colour differs above this, relative where the reference's is above 1.
    double colorThreshold = 0.02;
    double allowedPercent = 0;  // of the pixels, differing unexplained
    int threads = 0;            // for the margins; 0: every core
};

enum class PixelVerdict : std::uint8_t { Same, SetAside, Unexplained };

struct Agreement {
    std::size_t pixels = 0, differing = 0, setAside = 0, unexplained = 0;
    // Among the differing pixels, what differs (a pixel may count in several).
    std::size_t colors = 0, ids = 0, depths = 0, normals = 0;
    double largest = 0;  // the largest colour difference, unclamped
    int largestX = 0, largestY = 0;
    std::vector<std::pair<int, int>> firstUnexplained;  // up to 5
    std::vector<PixelVerdict> verdicts;                 // per pixel
    bool passed = true;
};

// gpu and cpu: the same scene, camera and settings (settings.aovs for the
// depth and normal). Throws Error when their sizes differ.
Agreement judgeAgreement(const Scene& scene, const CameraBasis& camera,
                         const RenderSettings& settings, Precision precision, const Frame& gpu,
                         const Frame& cpu, const AgreementOptions& options);

// The lines `render --check` prints.
std::string formatAgreement(const Agreement& agreement, const AgreementOptions& options);

// --diff: each pixel's colour difference (x4, grey), set-aside pixels in
// blue, unexplained ones in red.
Image agreementImage(const Frame& gpu, const Frame& cpu, const Agreement& agreement);

}  // namespace vkray
