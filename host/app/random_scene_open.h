// The generator's open scenes (RandomScene::open): past every mode's
// envelope, for `--precision auto` to choose the mode.
#pragma once

#include "app/random_scene_draw.h"

#include <cstdint>

namespace vkray::random_scene {

// A scene past every envelope, for `--precision auto`: up to three planes at
// any tilt, textured (checkers, wood, a pixmap) and seen to their horizons;
// booleans of every solid, booleans nested in them; glass of any thickness; squashes
// to 1e-6 between rotations and 1e-8 before one; eyes up to 2e5 times the
// scene away, low over a floor, grazing or inside. `vkray difftest` renders
// it in the mode auto chooses, or reports it not comparable where the scene
// passes fp64's envelope too (docs/testing.md).
void openScene(Draw& d, std::uint64_t seed, RandomScene& r);

}  // namespace vkray::random_scene
