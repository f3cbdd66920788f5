#include "app/devices_command.h"

#include "app/commands.h"
#include "gpu/context.h"
#include "util/error.h"

#include <ostream>
#include <string>

namespace vkray {

int runDevices(std::ostream& out) {
    int preferred = -1;
    const auto devices = gpu::Context::listDevices(&preferred);
    if (devices.empty())
        throw Error(
            "no Vulkan device found; install mesa-vulkan-drivers (lavapipe) or a GPU "
            "driver, or check VK_ICD_FILENAMES");
    for (const gpu::DeviceInfo& d : devices) {
        out << d.index << ": " << d.name << (d.index == preferred ? "  [render picks this]" : "")
            << "\n   type " << d.type << ", driver " << d.driverName << " " << d.driverInfo
            << " (version " << d.driverVersion << "), Vulkan " << d.apiVersionString()
            << "\n   compute " << (d.hasCompute ? "yes" : "no") << ", shaderFloat64 "
            << (d.shaderFloat64 ? "yes" : "no") << ", ray queries "
            << (d.rayQuery ? "yes (--traversal rayquery)" : "no") << ", subgroup size "
            << d.subgroupSize << ", max storage buffer " << d.maxStorageBufferRange << " bytes"
            << ", max uniform buffer " << d.maxUniformBufferRange << " bytes"
            << ", max texel buffer " << d.maxTexelBufferElements << " texels"
            << ", memory heap " << d.memoryHeapBytes << " bytes"
            << ", max workgroup size " << d.maxWorkgroupSize[0] << "x" << d.maxWorkgroupSize[1]
            << "x" << d.maxWorkgroupSize[2] << ", max workgroup count " << d.maxWorkgroupCount[0]
            << "x" << d.maxWorkgroupCount[1] << "x" << d.maxWorkgroupCount[2] << ", timestamps "
            << (d.timestampValidBits > 0 ? std::to_string(d.timestampValidBits) + " bits, " +
                                               fixedDigits(d.timestampPeriodNs, 3) + " ns a tick"
                                         : std::string("no"))
            << "\n";
    }
    return 0;
}

}  // namespace vkray
