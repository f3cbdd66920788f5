// `vkray render`: one image on the GPU, the CPU reference (--cpu) or both
// compared (--check), across MPI ranks when run under mpirun; --watch renders
// again on every change.
#pragma once

#include "app/options.h"

#include <iosfwd>

namespace vkray {

// Exit status: 0, or 2 when --check found the images beyond tolerance.
int runRender(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace vkray
