// `vkray shaders check [--all]`: every shader variant compiles; each failure
// printed with its file:line.
#pragma once

#include "app/options.h"

#include <iosfwd>

namespace vkray {

// Exit status: 0 when all compiled, 1 when any failed.
int runShadersCheck(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace vkray
