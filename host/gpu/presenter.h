// `vkray view`'s window on the device: the tracer's tiles (TileListener) are
// summed into the picture by shaders/present.comp, which also turns the
// picture, an AOV, the CPU reference or their difference into the 8-bit
// bytes a PNG of it would hold; those are copied into the window's swapchain
// image and presented. Nothing of the picture goes through the host on its
// way to the window; the host reads it back only to save or compare it.
#pragma once

#include "gpu/context.h"
#include "gpu/gpu_tracer.h"
#include "image/frame.h"
#include "image/image_io.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace vkray::gpu {

// Makes the window's surface for a Vulkan instance: takes the VkInstance and
// returns the VkSurfaceKHR (both as plain handles, so that the window system's
// side needs no Vulkan-Hpp). Throws Error when it cannot.
using SurfaceMaker = std::function<std::uint64_t(void* instance)>;

enum class View { Color, Depth, Normal, ObjectId, Difference };

// A pixel's verdict in the difference view (shaders/layout.h, VERDICT_*).
enum class ShownVerdict : std::uint32_t { None = 0, Same = 1, SetAside = 2, Unexplained = 3 };

struct ViewSettings {
    View view = View::Color;
    bool cpuReference = false;  // show the CPU reference (setCpuReference) instead of the GPU's
    float depthNear = 0, depthFar = 1;  // View::Depth: the range of the false colours
    float threshold = 0.02f;            // View::Difference: errors above it are red to yellow
};

class Presenter {
public:
    // The context must have been made with the window system's surface
    // extensions and the swapchain (ContextOptions). Throws Error when its
    // queue cannot present to the surface or the surface offers no 8-bit
    // RGBA or BGRA format that can be copied to.
    Presenter(Context& context, const std::string& shaderDirectory, const SurfaceMaker& makeSurface,
              int width, int height);
    ~Presenter();
    Presenter(const Presenter&) = delete;
    Presenter& operator=(const Presenter&) = delete;

    // How the tiles from now on join the picture: `fresh`, they replace
    // their pixels' sums (else they add a sample to them); `sampleZero`, they
    // hold sample 0 and so the AOVs (and the depth range starts afresh).
    void beginPass(bool fresh, bool sampleZero);
    // A tile the tracer has finished: the GpuTracer's TileListener.
    void absorb(const TracedTile& tile);

    void setCpuReference(const Frame& frame);
    // The margin rule's verdict of each pixel, for the difference view;
    // empty: none (the threshold's heat alone).
    void setVerdicts(const std::vector<ShownVerdict>& verdicts);

    // Composes the view and presents it. The window is left as it was when
    // it cannot show it now (minimised); the view is composed regardless.
    void show(const ViewSettings& settings);

    // The least and greatest finite depth of the tiles since the last
    // beginPass(.., true); {0, 0} when none was finite.
    std::pair<float, float> depthRange() const;
    // The view last composed by show(), as a 3-channel image of its bytes
    // over 255: what a PNG of it holds.
    Image shownImage() const;
    // The GPU's picture: each pixel's sum over its count of samples.
    Image pictureColor() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace vkray::gpu
