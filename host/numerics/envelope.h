// Where each precision mode agrees with the CPU reference (docs/numerics.md,
// "Envelope"), and how far into it a scene seen from its camera reaches:
// what `--precision auto` chooses from, and what `vkray difftest`'s
// generator draws within.
#pragma once

#include <string>
#include <vector>

#include "gpu/precision.h"
#include "render/camera.h"
#include "scene/scene.h"

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
    // A textured plane with its horizon in view: its hits there lie
    // arbitrarily far, its cells finer than a pixel, and only the margin
    // rule tells a rounding from a wrong texture.
    bool texturedHorizon;
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

// One figure of a scene against a mode's limits: what it is, the object
// (its shape keyword's place) whose figure it is, and the limit it passes.
struct EnvelopeExcess {
    std::string what;  // "the 'sphere' at s.sdl:3:1 is seen from 5.2e+04 of its sizes", ...
    FileLoc where;     // unknown for the eye's own distance from the origin
    double figure = 0, limit = 0;
};

// What passes `precision`'s envelope for this scene and camera (empty: the
// scene is inside it). Each bounded primitive (booleans' operands too) is
// taken as docs/numerics.md measures it: |M^-1 eye| in object sizes (the
// generic box's), its squash (smallest over largest scale of M, either
// order), |M^-1 eye| per checker cell or wood ring, and a refracting solid's
// thinnest scale over its distance from the eye or the origin; then the
// eye's distance from the world's origin, and a textured plane whose horizon
// is in view (in fp64's envelope, not robust's). A lone bounded object is held to the
// lone figures, several objects to the scenes'. Not taken: R / H of a huge
// object seen from close above it, and pixmap textures' texels.
std::vector<EnvelopeExcess> envelopeExcesses(const Scene& scene, const CameraBasis& camera,
                                             Precision precision);

// `--precision auto`: robust where the whole scene is inside robust's
// envelope, else fp64; `outside` holds what passed robust's (the first
// forced the choice), and `beyondEvery` what passes fp64's too (no mode is
// documented to agree with the CPU reference there).
struct PrecisionChoice {
    Precision precision = Precision::Robust;
    std::vector<EnvelopeExcess> outside;
    std::vector<EnvelopeExcess> beyondEvery;
};
PrecisionChoice choosePrecision(const Scene& scene, const CameraBasis& camera);

// "the 'sphere' at s.sdl:3:1 is seen from 5.2e+04 of its sizes, beyond
// robust's 2e+03"
std::string describe(const EnvelopeExcess& excess, Precision precision);

}  // namespace vkray
