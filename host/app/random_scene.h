// Seeded random scenes over the whole scene language, for the differential
// tester (`vkray difftest`): every shape (negative and zero tapers,
// booleans, polyhedra, the teapot, a 3VN mesh), strong and near-singular
// transforms, cameras far away, grazing, inside objects and close above a
// huge one, one to several lights, every material word, and the render
// settings (spp, block, precision). What is drawn covers, and stays inside,
// the envelope in which the GPU is documented to agree with the CPU
// reference (docs/numerics.md, "Envelope").
#pragma once

#include "gpu/precision.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vkray {

// The limits a drawn scene stays within, by precision mode. A distance in
// object sizes is |eye - centre| over the object's largest scale; |M^-1 eye|
// is the eye's distance in the object's generic space.
struct EnvelopeLimits {
    double farthestEye;          // object sizes, for objects not squashed
    double farthestGeneric;      // |M^-1 eye| of a squashed object
    double farthestPerCell;      // |M^-1 eye| over a textured object's cell or ring width
    double farthestWorldEye;     // |eye| in world units (the CPU reference's own limit)
    double smallestSquash;       // the ratio of an object's scales, squashed between rotations
    double smallestInnerSquash;  // the same, squashed before its only rotation
    double largestNearRatio;     // R / H: a huge object of size R seen from H above it
    // A solid that refracts (transparency above minTransparency): its
    // smallest scale over its distance from the eye at least this; its
    // refracted rays start a step inside it that grows with that distance.
    double thinnestPerDistance;
};

// Two families of scenes, each with its limits (docs/numerics.md,
// "Envelope"): scenes of several objects of every kind, with every material
// word; and a lone object as the envelope's sweeps place it (a sphere far
// away, plain or checkered; a cube, sphere, icosahedron or teapot squashed
// after or before its rotation; a huge sphere, cylinder or torus, or a mirror
// floor, seen from close), opaque, to the figures the sweeps measured. Every
// mode draws the same shapes and materials; fp64's figures go further.
struct SceneEnvelope {
    EnvelopeLimits scenes;
    EnvelopeLimits lone;
};

SceneEnvelope envelopeOf(Precision precision);

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

struct RandomScene {
    bool lone = false;     // a lone object (SceneEnvelope::lone), else several
    std::string sdl;       // the scene, with a camera
    std::string meshFile;  // the 3VN file it names ("" when none), to write beside it
    std::string meshText;
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
// `precision`: the mode to draw for; null draws robust or fp64 (naive, the
// textbook's float, is expected to disagree and is drawn only when asked).
RandomScene randomScene(std::uint64_t seed, const Precision* precision = nullptr);

}  // namespace vkray
