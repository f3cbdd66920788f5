// `vkray features SCENE`: the shader variant `render` would compile for the
// scene, and what it binds (app/features_report.h formats it).
#pragma once

#include "app/options.h"

#include <iosfwd>

namespace vkray {

int runFeatures(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace vkray
