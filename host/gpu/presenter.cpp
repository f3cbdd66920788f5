#include "gpu/presenter.h"

#include "gpu/compute_pipeline.h"
#include "gpu/spirv_cache.h"
#include "image/stb_codecs.h"
#include "shaders/layout.h"
#include "util/error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

namespace vkray::gpu {

namespace {

// byteFrom[b]: the least float a PNG stores as byte b or more (pngByte is
// monotonic); byteFrom[0] = -inf. Found by bisection over the floats of
// [0, 1], whose bit patterns are ordered as their values.
std::vector<float> byteThresholds() {
    std::vector<float> from(256, -std::numeric_limits<float>::infinity());
    const auto bits = [](float f) {
        std::uint32_t u;
        std::memcpy(&u, &f, 4);
        return u;
    };
    const auto value = [](std::uint32_t u) {
        float f;
        std::memcpy(&f, &u, 4);
        return f;
    };
    for (int b = 1; b < 256; ++b) {
        std::uint32_t lo = bits(0.0f), hi = bits(1.0f);  // pngByte(lo) < b <= pngByte(hi)
        while (hi - lo > 1) {
            const std::uint32_t mid = lo + (hi - lo) / 2;
            (pngByte(value(mid)) >= b ? hi : lo) = mid;
        }
        from[size_t(b)] = value(hi);
    }
    return from;
}

GpuPixel toGpuPixel(const Frame& frame, size_t i) {
    GpuPixel p{};
    p.color = {frame.color[i].x, frame.color[i].y, frame.color[i].z, 0};
    std::memcpy(&p.color.w, &frame.id[i], sizeof(std::int32_t));
    p.normal = {frame.normal[i].x, frame.normal[i].y, frame.normal[i].z, frame.depth[i]};
    return p;
}

// The 8-bit formats the view's bytes copy into as they are (a copy does no
// conversion, so an sRGB format shows the same bytes as a UNORM one).
bool isBgra(vk::Format f) {
    return f == vk::Format::eB8G8R8A8Unorm || f == vk::Format::eB8G8R8A8Srgb;
}
bool isRgba(vk::Format f) {
    return f == vk::Format::eR8G8B8A8Unorm || f == vk::Format::eR8G8B8A8Srgb;
}

}  // namespace

struct Presenter::Impl {
    Context::Impl& c;
    int width, height;
    size_t pixels;
    vk::raii::SurfaceKHR surface = nullptr;
    vk::SurfaceFormatKHR format;
    vk::PresentModeKHR presentMode = vk::PresentModeKHR::eFifo;
    vk::raii::SwapchainKHR swapchain = nullptr;
    std::vector<vk::Image> images;
    std::vector<vk::raii::Semaphore> presentReady;  // one per swapchain image
    vk::Extent2D extent;
    bool recreate = false;

    HostBuffer sums, aovs, cpu, view, bytes, range, verdicts;
    std::optional<ComputePipeline> compose;
    std::optional<DescriptorSet> descriptors;
    vk::raii::CommandBuffer commands = nullptr;
    vk::raii::Fence fence = nullptr;
    vk::raii::Semaphore acquired = nullptr;

    bool fresh = true, sampleZero = true;
    bool bgra = false;

    Impl(Context::Impl& context, int w, int h)
        : c(context),
          width(w),
          height(h),
          pixels(size_t(w) * size_t(h)),
          sums(c, sizeof(vec4) * pixels, vk::BufferUsageFlagBits::eStorageBuffer),
          aovs(c, sizeof(GpuPixel) * pixels, vk::BufferUsageFlagBits::eStorageBuffer),
          cpu(c, sizeof(GpuPixel) * pixels, vk::BufferUsageFlagBits::eStorageBuffer),
          view(c, sizeof(uint) * pixels,
               vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferSrc),
          bytes(c, sizeof(float) * 256, vk::BufferUsageFlagBits::eStorageBuffer),
          range(c, sizeof(uvec4), vk::BufferUsageFlagBits::eStorageBuffer),
          verdicts(c, sizeof(uint) * pixels, vk::BufferUsageFlagBits::eStorageBuffer) {}

    void bindTile(vk::Buffer tile) {
        const vk::DescriptorBufferInfo info(tile, 0, VK_WHOLE_SIZE);
        c.device.updateDescriptorSets(
            vk::WriteDescriptorSet(*descriptors->set, PRESENT_BINDING_TILE, 0, 1,
                                   vk::DescriptorType::eStorageBuffer, nullptr, &info),
            nullptr);
    }

    // Records the dispatch of present.comp over rect (with its push constants).
    void recordDispatch(const PresentParams& params) {
        commands.bindPipeline(vk::PipelineBindPoint::eCompute, *compose->pipeline);
        commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *compose->layout, 0,
                                    *descriptors->set, nullptr);
        commands.pushConstants<PresentParams>(*compose->layout, vk::ShaderStageFlagBits::eCompute,
                                              0, params);
        commands.dispatch((params.rect.z + PRESENT_WORKGROUP - 1) / PRESENT_WORKGROUP,
                          (params.rect.w + PRESENT_WORKGROUP - 1) / PRESENT_WORKGROUP, 1);
    }

    void begin() {
        commands.reset();
        commands.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
        // The tracer's (and the last composition's) shader writes, before these reads.
        const vk::MemoryBarrier written(
            vk::AccessFlagBits::eShaderWrite,
            vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite);
        commands.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                                 vk::PipelineStageFlagBits::eComputeShader, {}, written, nullptr,
                                 nullptr);
    }

    void submitAndWait(vk::Semaphore wait = nullptr, vk::Semaphore signal = nullptr) {
        const vk::PipelineStageFlags stage = vk::PipelineStageFlagBits::eTransfer;
        vk::SubmitInfo submit({}, {}, *commands, {});
        if (wait) {
            submit.setWaitSemaphoreCount(1).setPWaitSemaphores(&wait).setPWaitDstStageMask(&stage);
        }
        if (signal) submit.setSignalSemaphoreCount(1).setPSignalSemaphores(&signal);
        gpu::submitAndWait(c, submit, fence, "presenting the view");
    }

    void makeSwapchain() {
        const vk::SurfaceCapabilitiesKHR caps =
            c.physicalDevice.getSurfaceCapabilitiesKHR(*surface);
        extent = caps.currentExtent;
        if (extent.width == std::numeric_limits<std::uint32_t>::max())
            extent = vk::Extent2D(std::clamp(std::uint32_t(width), caps.minImageExtent.width,
                                             caps.maxImageExtent.width),
                                  std::clamp(std::uint32_t(height), caps.minImageExtent.height,
                                             caps.maxImageExtent.height));
        c.queue.waitIdle();  // nothing presented still uses the old images
        swapchain = nullptr;
        images.clear();
        presentReady.clear();
        recreate = false;
        if (extent.width == 0 || extent.height == 0) return;  // minimised: nothing to show on
        if (!(caps.supportedUsageFlags & vk::ImageUsageFlagBits::eTransferDst))
            throw Error(
                "the window's surface cannot be copied to (no transfer-destination "
                "usage on " +
                c.info.name + "); use `vkray render --watch`");
        std::uint32_t count = caps.minImageCount + 1;
        if (caps.maxImageCount > 0) count = std::min(count, caps.maxImageCount);
        vk::CompositeAlphaFlagBitsKHR alpha = vk::CompositeAlphaFlagBitsKHR::eOpaque;
        for (const auto candidate :
             {vk::CompositeAlphaFlagBitsKHR::eOpaque, vk::CompositeAlphaFlagBitsKHR::eInherit,
              vk::CompositeAlphaFlagBitsKHR::ePreMultiplied,
              vk::CompositeAlphaFlagBitsKHR::ePostMultiplied})
            if (caps.supportedCompositeAlpha & candidate) {
                alpha = candidate;
                break;
            }
        vk::SwapchainCreateInfoKHR info({}, *surface, count, format.format, format.colorSpace,
                                        extent, 1, vk::ImageUsageFlagBits::eTransferDst,
                                        vk::SharingMode::eExclusive, {}, caps.currentTransform,
                                        alpha, presentMode, VK_TRUE);
        swapchain = vk::raii::SwapchainKHR(c.device, info);
        images = swapchain.getImages();
        for (size_t i = 0; i < images.size(); ++i)
            presentReady.emplace_back(c.device, vk::SemaphoreCreateInfo{});
    }
};

Presenter::Presenter(Context& context, const std::string& shaderDirectory,
                     const SurfaceMaker& makeSurface, int width, int height) try
    : impl_(std::make_unique<Impl>(context.impl(), width, height)) {
    Impl& s = *impl_;
    Context::Impl& c = s.c;
    const std::uint64_t handle =
        makeSurface(static_cast<void*>(static_cast<VkInstance>(*c.instance)));
    VkSurfaceKHR surface;
    static_assert(sizeof surface == sizeof handle);
    std::memcpy(&surface, &handle, sizeof surface);
    s.surface = vk::raii::SurfaceKHR(c.instance, surface);
    if (!c.physicalDevice.getSurfaceSupportKHR(c.queueFamily, *s.surface))
        throw Error("the Vulkan device " + std::to_string(c.info.index) + " (" + c.info.name +
                    ") cannot present to this window from its compute queue; choose another "
                    "with --device, or use `vkray render --watch`");
    const std::vector<vk::SurfaceFormatKHR> formats =
        c.physicalDevice.getSurfaceFormatsKHR(*s.surface);
    const auto found = std::find_if(
        formats.begin(), formats.end(),
        [](const vk::SurfaceFormatKHR& f) { return isBgra(f.format) || isRgba(f.format); });
    if (found == formats.end())
        throw Error(
            "the window offers no 8-bit RGBA or BGRA format to copy the view into; use "
            "`vkray render --watch`");
    // UNORM before sRGB, though both show the bytes as they are.
    s.format = *found;
    for (const vk::SurfaceFormatKHR& f : formats)
        if (f.format == vk::Format::eB8G8R8A8Unorm || f.format == vk::Format::eR8G8B8A8Unorm)
            s.format = f;
    s.bgra = isBgra(s.format.format);
    // Not tied to the display's refresh where the window system allows: the
    // render loop must not wait for it between tiles.
    const std::vector<vk::PresentModeKHR> modes =
        c.physicalDevice.getSurfacePresentModesKHR(*s.surface);
    for (const auto mode :
         {vk::PresentModeKHR::eFifo, vk::PresentModeKHR::eImmediate, vk::PresentModeKHR::eMailbox})
        if (std::find(modes.begin(), modes.end(), mode) != modes.end()) s.presentMode = mode;
    s.makeSwapchain();

    // The buffers start as an empty picture: no samples, every pixel a miss.
    std::vector<vec4> noSums(s.pixels, vec4{0, 0, 0, 0});
    s.sums.upload(noSums.data(), sizeof(vec4) * s.pixels);
    const Frame empty(width, height);
    std::vector<GpuPixel> misses(s.pixels);
    for (size_t i = 0; i < s.pixels; ++i) misses[i] = toGpuPixel(empty, i);
    for (GpuPixel& p : misses) p.normal.w = std::numeric_limits<float>::infinity();
    s.aovs.upload(misses.data(), sizeof(GpuPixel) * s.pixels);
    s.cpu.upload(misses.data(), sizeof(GpuPixel) * s.pixels);
    const std::vector<float> thresholds = byteThresholds();
    s.bytes.upload(thresholds.data(), sizeof(float) * 256);
    const uvec4 noRange{0x7f800000u, 0, 0, 0};
    s.range.upload(&noRange, sizeof noRange);
    const std::vector<uint> noVerdicts(s.pixels, VERDICT_NONE);
    s.verdicts.upload(noVerdicts.data(), sizeof(uint) * s.pixels);

    std::vector<ComputeBinding> bindings;
    for (uint b = PRESENT_BINDING_TILE; b <= PRESENT_BINDING_VERDICTS; ++b)
        bindings.push_back({b, vk::DescriptorType::eStorageBuffer});
    const CompiledShader shader = loadOrCompile({shaderDirectory, "present.comp", {}});
    s.compose.emplace(c, shader.spirv, std::move(bindings), uint(sizeof(PresentParams)));
    s.descriptors.emplace(c, *s.compose);
    const std::array<const HostBuffer*, 8> buffers{&s.aovs, &s.sums,  &s.aovs,  &s.cpu,
                                                   &s.view, &s.bytes, &s.range, &s.verdicts};
    std::vector<vk::DescriptorBufferInfo> infos;
    for (const HostBuffer* buffer : buffers) infos.emplace_back(buffer->buffer(), 0, VK_WHOLE_SIZE);
    std::vector<vk::WriteDescriptorSet> writes;
    for (uint b = 0; b < infos.size(); ++b)
        writes.emplace_back(*s.descriptors->set, b, 0, 1, vk::DescriptorType::eStorageBuffer,
                            nullptr, &infos[b]);
    c.device.updateDescriptorSets(writes, nullptr);
    s.commands = makeCommandBuffer(c);
    s.fence = vk::raii::Fence(c.device, vk::FenceCreateInfo{});
    s.acquired = vk::raii::Semaphore(c.device, vk::SemaphoreCreateInfo{});
} catch (const vk::SystemError& failure) {
    explainVulkanFailure(failure, context.device());
}

Presenter::~Presenter() {
    if (impl_) impl_->c.device.waitIdle();
}

void Presenter::beginPass(bool fresh, bool sampleZero) {
    Impl& s = *impl_;
    s.fresh = fresh;
    s.sampleZero = sampleZero;
    if (sampleZero) {
        const uvec4 noRange{0x7f800000u, 0, 0, 0};
        s.range.upload(&noRange, sizeof noRange);
    }
}

void Presenter::absorb(const TracedTile& tile) try {
    Impl& s = *impl_;
    VkBuffer pixels;
    static_assert(sizeof pixels == sizeof tile.pixelBuffer);
    std::memcpy(&pixels, &tile.pixelBuffer, sizeof pixels);
    s.bindTile(pixels);
    s.begin();
    const TileRect& r = tile.rect;
    s.recordDispatch({{uint(r.x), uint(r.y), uint(r.width), uint(r.height)},
                      {PRESENT_ABSORB, s.fresh ? 1u : 0u, s.sampleZero ? 1u : 0u, uint(s.width)},
                      {0, 0, 0, 0}});
    const vk::MemoryBarrier toHost(vk::AccessFlagBits::eShaderWrite, vk::AccessFlagBits::eHostRead);
    s.commands.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                               vk::PipelineStageFlagBits::eHost, {}, toHost, nullptr, nullptr);
    s.commands.end();
    s.submitAndWait();
    s.bindTile(s.aovs.buffer());  // the tracer's buffer is gone after its render
} catch (const vk::SystemError& failure) {
    explainVulkanFailure(failure, impl_->c.info);
}

void Presenter::setCpuReference(const Frame& frame) {
    Impl& s = *impl_;
    if (frame.width != s.width || frame.height != s.height)
        throw Error("internal: the CPU reference is not the window's size");
    std::vector<GpuPixel> packed(s.pixels);
    for (size_t i = 0; i < s.pixels; ++i) packed[i] = toGpuPixel(frame, i);
    s.cpu.upload(packed.data(), sizeof(GpuPixel) * s.pixels);
}

static_assert(std::uint32_t(ShownVerdict::None) == VERDICT_NONE &&
              std::uint32_t(ShownVerdict::Same) == VERDICT_SAME &&
              std::uint32_t(ShownVerdict::SetAside) == VERDICT_SET_ASIDE &&
              std::uint32_t(ShownVerdict::Unexplained) == VERDICT_UNEXPLAINED);

void Presenter::setVerdicts(const std::vector<ShownVerdict>& verdicts) {
    Impl& s = *impl_;
    if (verdicts.empty()) {
        const std::vector<uint> none(s.pixels, VERDICT_NONE);
        s.verdicts.upload(none.data(), sizeof(uint) * s.pixels);
        return;
    }
    if (verdicts.size() != s.pixels)
        throw Error("internal: the verdicts are not the window's size");
    s.verdicts.upload(verdicts.data(), sizeof(uint) * s.pixels);
}

void Presenter::show(const ViewSettings& settings) try {
    Impl& s = *impl_;
    if (s.recreate) s.makeSwapchain();
    std::optional<std::uint32_t> image;
    if (!s.images.empty()) {
        try {
            const auto [result, index] = s.swapchain.acquireNextImage(UINT64_MAX, *s.acquired);
            if (result == vk::Result::eSuccess || result == vk::Result::eSuboptimalKHR)
                image = index;
            if (result == vk::Result::eSuboptimalKHR) s.recreate = true;
        } catch (const vk::OutOfDateKHRError&) {
            s.recreate = true;
        }
    }
    s.begin();
    s.recordDispatch(
        {{0, 0, uint(s.width), uint(s.height)},
         {PRESENT_COMPOSE, uint(settings.view), settings.cpuReference ? 1u : 0u, s.bgra ? 1u : 0u},
         {settings.depthNear, settings.depthFar, settings.threshold, 0}});
    const vk::MemoryBarrier composed(
        vk::AccessFlagBits::eShaderWrite,
        vk::AccessFlagBits::eTransferRead | vk::AccessFlagBits::eHostRead);
    s.commands.pipelineBarrier(
        vk::PipelineStageFlagBits::eComputeShader,
        vk::PipelineStageFlagBits::eTransfer | vk::PipelineStageFlagBits::eHost, {}, composed,
        nullptr, nullptr);
    if (image) {
        const vk::Image target = s.images[*image];
        const vk::ImageSubresourceRange whole(vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1);
        const vk::ImageMemoryBarrier toCopy(
            {}, vk::AccessFlagBits::eTransferWrite, vk::ImageLayout::eUndefined,
            vk::ImageLayout::eTransferDstOptimal, VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED,
            target, whole);
        s.commands.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer,
                                   vk::PipelineStageFlagBits::eTransfer, {}, nullptr, nullptr,
                                   toCopy);
        const std::uint32_t w = std::min(s.extent.width, std::uint32_t(s.width));
        const std::uint32_t h = std::min(s.extent.height, std::uint32_t(s.height));
        if (w < s.extent.width ||
            h < s.extent.height)  // a window larger than the image: black around it
            s.commands.clearColorImage(target, vk::ImageLayout::eTransferDstOptimal,
                                       vk::ClearColorValue(std::array<float, 4>{0, 0, 0, 1}),
                                       whole);
        const vk::BufferImageCopy region(0, std::uint32_t(s.width), std::uint32_t(s.height),
                                         {vk::ImageAspectFlagBits::eColor, 0, 0, 1}, {0, 0, 0},
                                         {w, h, 1});
        s.commands.copyBufferToImage(s.view.buffer(), target, vk::ImageLayout::eTransferDstOptimal,
                                     region);
        const vk::ImageMemoryBarrier toPresent(
            vk::AccessFlagBits::eTransferWrite, {}, vk::ImageLayout::eTransferDstOptimal,
            vk::ImageLayout::ePresentSrcKHR, VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED,
            target, whole);
        s.commands.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer,
                                   vk::PipelineStageFlagBits::eBottomOfPipe, {}, nullptr, nullptr,
                                   toPresent);
    }
    s.commands.end();
    if (!image) {
        s.submitAndWait();
        return;
    }
    s.submitAndWait(*s.acquired, *s.presentReady[*image]);
    const vk::SwapchainKHR chain = *s.swapchain;
    const vk::Semaphore ready = *s.presentReady[*image];
    try {
        const vk::Result result = s.c.queue.presentKHR(vk::PresentInfoKHR(ready, chain, *image));
        if (result == vk::Result::eSuboptimalKHR) s.recreate = true;
    } catch (const vk::OutOfDateKHRError&) {
        s.recreate = true;
    }
} catch (const vk::SystemError& failure) {
    explainVulkanFailure(failure, impl_->c.info);
}

std::pair<float, float> Presenter::depthRange() const {
    Impl& s = *impl_;
    s.range.invalidate();
    const auto* bits = static_cast<const uint*>(s.range.data());
    float lo, hi;
    std::memcpy(&lo, &bits[0], 4);
    std::memcpy(&hi, &bits[1], 4);
    if (std::isinf(lo)) return {0, 0};
    return {lo, hi};
}

Image Presenter::shownImage() const {
    Impl& s = *impl_;
    s.view.invalidate();
    const auto* packed = static_cast<const uint*>(s.view.data());
    Image image{s.width, s.height, 3, std::vector<float>(s.pixels * 3)};
    for (size_t i = 0; i < s.pixels; ++i) {
        for (int channel = 0; channel < 3; ++channel) {
            const int shift = 8 * (s.bgra ? 2 - channel : channel);
            image.pixels[3 * i + size_t(channel)] = float((packed[i] >> shift) & 255u) / 255.0f;
        }
    }
    return image;
}

Image Presenter::pictureColor() const {
    Impl& s = *impl_;
    s.sums.invalidate();
    const auto* sums = static_cast<const vec4*>(s.sums.data());
    Image image{s.width, s.height, 3, std::vector<float>(s.pixels * 3)};
    for (size_t i = 0; i < s.pixels; ++i) {
        image.pixels[3 * i] = sums[i].x / sums[i].w;
        image.pixels[3 * i + 1] = sums[i].y / sums[i].w;
        image.pixels[3 * i + 2] = sums[i].z / sums[i].w;
    }
    return image;
}

}  // namespace vkray::gpu
