// Seeded random scenes over the whole scene language, for the differential
// tester (`vkray difftest`): every shape (negative and zero tapers,
// booleans, polyhedra, the teapot, a 3VN mesh), strong and near-singular
// transforms, cameras far away, grazing and inside objects, one to several
// lights, every material word, and the render settings (spp, block,
// precision). What is drawn stays inside the envelope in which the GPU is
// documented to agree with the CPU reference (docs/numerics.md, "Envelope").
#pragma once

#include "numerics/precision.h"

#include <cstdint>
#include <string>

namespace vkray {

// The limits a drawn scene stays within, by precision mode. Every mode draws
// the same shapes and materials; fp64's distances and squashes go further.
// The eye is never inside a squashed object.
struct SceneEnvelope {
    double farthestEye;     // the eye's distance from the scene's centre, in scene extents
    double smallestSquash;  // the smallest ratio of an object's scales
};

SceneEnvelope envelopeOf(Precision precision);

struct RandomScene {
    std::string sdl;        // the scene, with a camera
    std::string meshFile;   // the 3VN file it names ("" when none), to write beside it
    std::string meshText;
    int width = 32, height = 24, block = 1, spp = 1;
    std::uint32_t sampleSeed = 0;
    Precision precision = Precision::Robust;
};

// The scene of `seed`: the same seed draws the same scene on every machine.
// `precision`: the mode to draw for; null draws robust or fp64 (naive, the
// textbook's float, is expected to disagree and is drawn only when asked).
RandomScene randomScene(std::uint64_t seed, const Precision* precision = nullptr);

}  // namespace vkray
