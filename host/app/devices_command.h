// `vkray devices`: the Vulkan devices and what vkray needs of each.
#pragma once

#include "app/options.h"

#include <iosfwd>

namespace vkray {

int runDevices(std::ostream& out);

}  // namespace vkray
