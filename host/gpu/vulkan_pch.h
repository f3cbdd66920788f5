// Precompiled header of host/gpu: Vulkan-Hpp's RAII layer is large, so it is
// parsed once and included nowhere outside host/gpu. The loader is opened at
// run time (vk::raii::Context), so a machine without libvulkan gets a clear
// error instead of a failure to start.
#pragma once

#include <vulkan/vulkan_raii.hpp>
