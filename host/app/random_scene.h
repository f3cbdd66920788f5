// Seeded random scenes over the whole scene language, for the differential
// tester (`vkray difftest`): every shape (negative and zero tapers,
// booleans, polyhedra, the teapot, a 3VN mesh), strong and near-singular
// transforms, cameras far away, grazing, inside objects and close above a
// huge one, one to several lights, every material word and texture, and the
// render settings (spp, block, precision). Drawn for a mode, a scene covers
// and stays inside the envelope in which the mode is documented to agree
// with the CPU reference (docs/numerics.md, "Envelope"); drawn open, it goes
// past it, and `--precision auto` chooses.
#pragma once

#include "gpu/precision.h"
#include "numerics/envelope.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vkray {

// How far into its envelope a drawn scene reaches (each figure the most any
// of its objects reaches; 0, or 1 for the squashes, when none does), in the
// terms of EnvelopeLimits.
struct SceneReach {
    double eye = 0;                  // largest distance in object sizes
    double generic = 0;              // largest |M^-1 eye| of an object squashed between rotations
    double perCell = 0;              // largest |M^-1 eye| / cell
    double worldEye = 0;             // |eye|
    double squash = 1;               // smallest ratio of scales, squashed between rotations
    double innerSquash = 1;          // smallest ratio of scales, squashed before the rotation
    double nearRatio = 0;            // R / H of the huge object the eye is close above (0: none)
    double thinPerDistance = 1e300;  // smallest thickness / distance of a refracting solid
};

// A file a scene names, to be written beside it.
struct SideFile {
    std::string name, bytes;
};

struct RandomScene {
    bool lone = false;  // a lone object (SceneEnvelope::lone), else several
    // Drawn past every envelope (openScene), for `--precision auto` to
    // choose the mode: `precision` is then robust until it has.
    bool open = false;
    std::string sdl;              // the scene, with a camera
    std::vector<SideFile> files;  // the 3VN mesh and the pixmap it names
    int width = 32, height = 24, block = 1, spp = 1;
    std::uint32_t sampleSeed = 0;
    Precision precision = Precision::Robust;
    SceneReach reach;
    // |M^-1 eye| of each object in the order the scene lists them (a
    // boolean's the boolean's own placement's): what the scene reader's
    // objectFromWorld gives, computed by the generator.
    std::vector<double> genericEye;
};

// The scene of `seed`: the same seed draws the same scene on every machine.
// `precision`: the mode to draw for, inside its envelope; null draws half
// the seeds open (past every envelope, for auto to choose from: several and
// tilted planes, textured, pixmaps, nested booleans of every solid, glass
// of any thickness, squashes and eyes beyond robust's figures) and the rest
// for robust or fp64 (naive, the textbook's float, is expected to disagree
// and is drawn only when asked).
RandomScene randomScene(std::uint64_t seed, const Precision* precision = nullptr);

}  // namespace vkray
