// `vkray difftest`: the differential tester. Draws seeded random scenes
// (app/random_scene.h), renders each on the GPU and with the CPU reference,
// and compares them as `render --check` does; each disagreement is kept as a
// scene file with the command that shows it.
#pragma once

#include "app/options.h"

#include <ostream>

namespace vkray {

// Exit status 0 when every scene agreed (or was refused with an error, which
// is reported), 2 when any disagreed, 1 on an error of the run itself.
int runDifftest(const Options& o, std::ostream& out, std::ostream& err);

}  // namespace vkray
