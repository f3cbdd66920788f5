// `vkray pixel SCENE X Y`: the same pixel traced on the GPU (the debug-pixel
// variant) and the CPU reference, printed side by side (app/pixel_report.h).
#pragma once

#include "app/options.h"

#include <iosfwd>

namespace vkray {

int runPixel(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace vkray
