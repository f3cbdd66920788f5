// `vkray stress` and `vkray report SCENE`: precision modes against
// the float128 oracle over scenes/stress/, and error against run time over
// the knobs that trade them for one scene. Both print a table and write CSV,
// JSON and a self-contained HTML page with SVG plots. `stress` exits 2 when a
// robust or double row is beyond its bounds, or naive passes a case built to
// break it.
#pragma once

#include "app/options.h"

#include <iosfwd>

namespace vkray {

int runStress(const Options& options, std::ostream& out, std::ostream& err);
int runReport(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace vkray
