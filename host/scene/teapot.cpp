// The Utah teapot: Martin Newell's 1975 Bezier patch data (public domain: 32
// bicubic patches over 306 control points, the 4 bottom patches included as
// in the widely shared data set), with our own evaluator and tessellator.
//
// Size and orientation are those of GLUT's glutSolidTeapot(1.0), which Hill's
// OpenGL programs draw: GLUT draws the same 32 patches after
//   glRotatef(270, 1, 0, 0); glScalef(0.5, 0.5, 0.5); glTranslatef(0, 0, -1.5);
// i.e. a Newell point (x, y, z) (z up, spout toward +x) lands at
//   (0.5 x, 0.5 (z - 1.5), -0.5 y):
// up is +y, the spout points toward +x, the handle toward -x. Bounds (exact
// surface): x in [-1.5, 1.71704] (the handle's back at Newell x = -3, the
// spout's lip at x = 3.43408), y in [-0.75, 0.825] (bottom z = 0, knob top
// z = 3.15), z in [-1, 1] (the body's radius 2 along Newell's y axis).
//
// Tessellation: segments x segments quads per patch (16: 16256 triangles; the
// 128 quads' halves that collapse at the lid's and bottom's poles are left
// out), each vertex with its analytic normal dP/du x dP/dv (outward for every
// patch of this data set). At the two poles that cross product vanishes; the
// normal is taken a hair inside the patch instead. Patch edges are welded:
// points that agree to 2^-30 (the two patches' evaluations of a shared edge,
// which may differ in the last bit) become one vertex, the first one made, so
// neighbouring patches' triangles share exactly those vertices. The teapot is not watertight (the
// spout and handle pierce the body, the spout is open), so closed = false.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <glm/geometric.hpp>
#include <unordered_map>

#include "scene/triangle_mesh.h"

namespace vkray {

namespace {

// clang-format off
// Newell's control points, (x, y, z) with z up.
constexpr double kControlPoints[306][3] = {
    {1.4, 0.0, 2.4}, {1.4, -0.784, 2.4}, {0.784, -1.4, 2.4},
    {0.0, -1.4, 2.4}, {1.3375, 0.0, 2.53125}, {1.3375, -0.749, 2.53125},
    {0.749, -1.3375, 2.53125}, {0.0, -1.3375, 2.53125}, {1.4375, 0.0, 2.53125},
    {1.4375, -0.805, 2.53125}, {0.805, -1.4375, 2.53125}, {0.0, -1.4375, 2.53125},
    {1.5, 0.0, 2.4}, {1.5, -0.84, 2.4}, {0.84, -1.5, 2.4},
    {0.0, -1.5, 2.4}, {-0.784, -1.4, 2.4}, {-1.4, -0.784, 2.4},
    {-1.4, 0.0, 2.4}, {-0.749, -1.3375, 2.53125}, {-1.3375, -0.749, 2.53125},
    {-1.3375, 0.0, 2.53125}, {-0.805, -1.4375, 2.53125}, {-1.4375, -0.805, 2.53125},
    {-1.4375, 0.0, 2.53125}, {-0.84, -1.5, 2.4}, {-1.5, -0.84, 2.4},
    {-1.5, 0.0, 2.4}, {-1.4, 0.784, 2.4}, {-0.784, 1.4, 2.4},
    {0.0, 1.4, 2.4}, {-1.3375, 0.749, 2.53125}, {-0.749, 1.3375, 2.53125},
    {0.0, 1.3375, 2.53125}, {-1.4375, 0.805, 2.53125}, {-0.805, 1.4375, 2.53125},
    {0.0, 1.4375, 2.53125}, {-1.5, 0.84, 2.4}, {-0.84, 1.5, 2.4},
    {0.0, 1.5, 2.4}, {0.784, 1.4, 2.4}, {1.4, 0.784, 2.4},
    {0.749, 1.3375, 2.53125}, {1.3375, 0.749, 2.53125}, {0.805, 1.4375, 2.53125},
    {1.4375, 0.805, 2.53125}, {0.84, 1.5, 2.4}, {1.5, 0.84, 2.4},
    {1.75, 0.0, 1.875}, {1.75, -0.98, 1.875}, {0.98, -1.75, 1.875},
    {0.0, -1.75, 1.875}, {2.0, 0.0, 1.35}, {2.0, -1.12, 1.35},
    {1.12, -2.0, 1.35}, {0.0, -2.0, 1.35}, {2.0, 0.0, 0.9},
    {2.0, -1.12, 0.9}, {1.12, -2.0, 0.9}, {0.0, -2.0, 0.9},
    {-0.98, -1.75, 1.875}, {-1.75, -0.98, 1.875}, {-1.75, 0.0, 1.875},
    {-1.12, -2.0, 1.35}, {-2.0, -1.12, 1.35}, {-2.0, 0.0, 1.35},
    {-1.12, -2.0, 0.9}, {-2.0, -1.12, 0.9}, {-2.0, 0.0, 0.9},
    {-1.75, 0.98, 1.875}, {-0.98, 1.75, 1.875}, {0.0, 1.75, 1.875},
    {-2.0, 1.12, 1.35}, {-1.12, 2.0, 1.35}, {0.0, 2.0, 1.35},
    {-2.0, 1.12, 0.9}, {-1.12, 2.0, 0.9}, {0.0, 2.0, 0.9},
    {0.98, 1.75, 1.875}, {1.75, 0.98, 1.875}, {1.12, 2.0, 1.35},
    {2.0, 1.12, 1.35}, {1.12, 2.0, 0.9}, {2.0, 1.12, 0.9},
    {2.0, 0.0, 0.45}, {2.0, -1.12, 0.45}, {1.12, -2.0, 0.45},
    {0.0, -2.0, 0.45}, {1.5, 0.0, 0.225}, {1.5, -0.84, 0.225},
    {0.84, -1.5, 0.225}, {0.0, -1.5, 0.225}, {1.5, 0.0, 0.15},
    {1.5, -0.84, 0.15}, {0.84, -1.5, 0.15}, {0.0, -1.5, 0.15},
    {-1.12, -2.0, 0.45}, {-2.0, -1.12, 0.45}, {-2.0, 0.0, 0.45},
    {-0.84, -1.5, 0.225}, {-1.5, -0.84, 0.225}, {-1.5, 0.0, 0.225},
    {-0.84, -1.5, 0.15}, {-1.5, -0.84, 0.15}, {-1.5, 0.0, 0.15},
    {-2.0, 1.12, 0.45}, {-1.12, 2.0, 0.45}, {0.0, 2.0, 0.45},
    {-1.5, 0.84, 0.225}, {-0.84, 1.5, 0.225}, {0.0, 1.5, 0.225},
    {-1.5, 0.84, 0.15}, {-0.84, 1.5, 0.15}, {0.0, 1.5, 0.15},
    {1.12, 2.0, 0.45}, {2.0, 1.12, 0.45}, {0.84, 1.5, 0.225},
    {1.5, 0.84, 0.225}, {0.84, 1.5, 0.15}, {1.5, 0.84, 0.15},
    {-1.6, 0.0, 2.025}, {-1.6, -0.3, 2.025}, {-1.5, -0.3, 2.25},
    {-1.5, 0.0, 2.25}, {-2.3, 0.0, 2.025}, {-2.3, -0.3, 2.025},
    {-2.5, -0.3, 2.25}, {-2.5, 0.0, 2.25}, {-2.7, 0.0, 2.025},
    {-2.7, -0.3, 2.025}, {-3.0, -0.3, 2.25}, {-3.0, 0.0, 2.25},
    {-2.7, 0.0, 1.8}, {-2.7, -0.3, 1.8}, {-3.0, -0.3, 1.8},
    {-3.0, 0.0, 1.8}, {-1.5, 0.3, 2.25}, {-1.6, 0.3, 2.025},
    {-2.5, 0.3, 2.25}, {-2.3, 0.3, 2.025}, {-3.0, 0.3, 2.25},
    {-2.7, 0.3, 2.025}, {-3.0, 0.3, 1.8}, {-2.7, 0.3, 1.8},
    {-2.7, 0.0, 1.575}, {-2.7, -0.3, 1.575}, {-3.0, -0.3, 1.35},
    {-3.0, 0.0, 1.35}, {-2.5, 0.0, 1.125}, {-2.5, -0.3, 1.125},
    {-2.65, -0.3, 0.9375}, {-2.65, 0.0, 0.9375}, {-2.0, -0.3, 0.9},
    {-1.9, -0.3, 0.6}, {-1.9, 0.0, 0.6}, {-3.0, 0.3, 1.35},
    {-2.7, 0.3, 1.575}, {-2.65, 0.3, 0.9375}, {-2.5, 0.3, 1.125},
    {-1.9, 0.3, 0.6}, {-2.0, 0.3, 0.9}, {1.7, 0.0, 1.425},
    {1.7, -0.66, 1.425}, {1.7, -0.66, 0.6}, {1.7, 0.0, 0.6},
    {2.6, 0.0, 1.425}, {2.6, -0.66, 1.425}, {3.1, -0.66, 0.825},
    {3.1, 0.0, 0.825}, {2.3, 0.0, 2.1}, {2.3, -0.25, 2.1},
    {2.4, -0.25, 2.025}, {2.4, 0.0, 2.025}, {2.7, 0.0, 2.4},
    {2.7, -0.25, 2.4}, {3.3, -0.25, 2.4}, {3.3, 0.0, 2.4},
    {1.7, 0.66, 0.6}, {1.7, 0.66, 1.425}, {3.1, 0.66, 0.825},
    {2.6, 0.66, 1.425}, {2.4, 0.25, 2.025}, {2.3, 0.25, 2.1},
    {3.3, 0.25, 2.4}, {2.7, 0.25, 2.4}, {2.8, 0.0, 2.475},
    {2.8, -0.25, 2.475}, {3.525, -0.25, 2.49375}, {3.525, 0.0, 2.49375},
    {2.9, 0.0, 2.475}, {2.9, -0.15, 2.475}, {3.45, -0.15, 2.5125},
    {3.45, 0.0, 2.5125}, {2.8, 0.0, 2.4}, {2.8, -0.15, 2.4},
    {3.2, -0.15, 2.4}, {3.2, 0.0, 2.4}, {3.525, 0.25, 2.49375},
    {2.8, 0.25, 2.475}, {3.45, 0.15, 2.5125}, {2.9, 0.15, 2.475},
    {3.2, 0.15, 2.4}, {2.8, 0.15, 2.4}, {0.0, 0.0, 3.15},
    {0.0, -0.002, 3.15}, {0.002, 0.0, 3.15}, {0.8, 0.0, 3.15},
    {0.8, -0.45, 3.15}, {0.45, -0.8, 3.15}, {0.0, -0.8, 3.15},
    {0.0, 0.0, 2.85}, {0.2, 0.0, 2.7}, {0.2, -0.112, 2.7},
    {0.112, -0.2, 2.7}, {0.0, -0.2, 2.7}, {-0.002, 0.0, 3.15},
    {-0.45, -0.8, 3.15}, {-0.8, -0.45, 3.15}, {-0.8, 0.0, 3.15},
    {-0.112, -0.2, 2.7}, {-0.2, -0.112, 2.7}, {-0.2, 0.0, 2.7},
    {0.0, 0.002, 3.15}, {-0.8, 0.45, 3.15}, {-0.45, 0.8, 3.15},
    {0.0, 0.8, 3.15}, {-0.2, 0.112, 2.7}, {-0.112, 0.2, 2.7},
    {0.0, 0.2, 2.7}, {0.45, 0.8, 3.15}, {0.8, 0.45, 3.15},
    {0.112, 0.2, 2.7}, {0.2, 0.112, 2.7}, {0.4, 0.0, 2.55},
    {0.4, -0.224, 2.55}, {0.224, -0.4, 2.55}, {0.0, -0.4, 2.55},
    {1.3, 0.0, 2.55}, {1.3, -0.728, 2.55}, {0.728, -1.3, 2.55},
    {0.0, -1.3, 2.55}, {1.3, 0.0, 2.4}, {1.3, -0.728, 2.4},
    {0.728, -1.3, 2.4}, {0.0, -1.3, 2.4}, {-0.224, -0.4, 2.55},
    {-0.4, -0.224, 2.55}, {-0.4, 0.0, 2.55}, {-0.728, -1.3, 2.55},
    {-1.3, -0.728, 2.55}, {-1.3, 0.0, 2.55}, {-0.728, -1.3, 2.4},
    {-1.3, -0.728, 2.4}, {-1.3, 0.0, 2.4}, {-0.4, 0.224, 2.55},
    {-0.224, 0.4, 2.55}, {0.0, 0.4, 2.55}, {-1.3, 0.728, 2.55},
    {-0.728, 1.3, 2.55}, {0.0, 1.3, 2.55}, {-1.3, 0.728, 2.4},
    {-0.728, 1.3, 2.4}, {0.0, 1.3, 2.4}, {0.224, 0.4, 2.55},
    {0.4, 0.224, 2.55}, {0.728, 1.3, 2.55}, {1.3, 0.728, 2.55},
    {0.728, 1.3, 2.4}, {1.3, 0.728, 2.4}, {0.0, 0.0, 0.0},
    {1.5, 0.0, 0.15}, {1.5, 0.84, 0.15}, {0.84, 1.5, 0.15},
    {0.0, 1.5, 0.15}, {1.5, 0.0, 0.075}, {1.5, 0.84, 0.075},
    {0.84, 1.5, 0.075}, {0.0, 1.5, 0.075}, {1.425, 0.0, 0.0},
    {1.425, 0.798, 0.0}, {0.798, 1.425, 0.0}, {0.0, 1.425, 0.0},
    {-0.84, 1.5, 0.15}, {-1.5, 0.84, 0.15}, {-1.5, 0.0, 0.15},
    {-0.84, 1.5, 0.075}, {-1.5, 0.84, 0.075}, {-1.5, 0.0, 0.075},
    {-0.798, 1.425, 0.0}, {-1.425, 0.798, 0.0}, {-1.425, 0.0, 0.0},
    {-1.5, -0.84, 0.15}, {-0.84, -1.5, 0.15}, {0.0, -1.5, 0.15},
    {-1.5, -0.84, 0.075}, {-0.84, -1.5, 0.075}, {0.0, -1.5, 0.075},
    {-1.425, -0.798, 0.0}, {-0.798, -1.425, 0.0}, {0.0, -1.425, 0.0},
    {0.84, -1.5, 0.15}, {1.5, -0.84, 0.15}, {0.84, -1.5, 0.075},
    {1.5, -0.84, 0.075}, {0.798, -1.425, 0.0}, {1.425, -0.798, 0.0},
};

// Each patch's 16 control points, row by row (1-based, as published). Within
// a row the parameter u runs; from row to row, v.
constexpr int kPatches[32][16] = {
    {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16},
    {4, 17, 18, 19, 8, 20, 21, 22, 12, 23, 24, 25, 16, 26, 27, 28},
    {19, 29, 30, 31, 22, 32, 33, 34, 25, 35, 36, 37, 28, 38, 39, 40},
    {31, 41, 42, 1, 34, 43, 44, 5, 37, 45, 46, 9, 40, 47, 48, 13},
    {13, 14, 15, 16, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60},
    {16, 26, 27, 28, 52, 61, 62, 63, 56, 64, 65, 66, 60, 67, 68, 69},
    {28, 38, 39, 40, 63, 70, 71, 72, 66, 73, 74, 75, 69, 76, 77, 78},
    {40, 47, 48, 13, 72, 79, 80, 49, 75, 81, 82, 53, 78, 83, 84, 57},
    {57, 58, 59, 60, 85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95, 96},
    {60, 67, 68, 69, 88, 97, 98, 99, 92, 100, 101, 102, 96, 103, 104, 105},
    {69, 76, 77, 78, 99, 106, 107, 108, 102, 109, 110, 111, 105, 112, 113, 114},
    {78, 83, 84, 57, 108, 115, 116, 85, 111, 117, 118, 89, 114, 119, 120, 93},
    {121, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135, 136},
    {124, 137, 138, 121, 128, 139, 140, 125, 132, 141, 142, 129, 136, 143, 144, 133},
    {133, 134, 135, 136, 145, 146, 147, 148, 149, 150, 151, 152, 69, 153, 154, 155},
    {136, 143, 144, 133, 148, 156, 157, 145, 152, 158, 159, 149, 155, 160, 161, 69},
    {162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175, 176, 177},
    {165, 178, 179, 162, 169, 180, 181, 166, 173, 182, 183, 170, 177, 184, 185, 174},
    {174, 175, 176, 177, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 196, 197},
    {177, 184, 185, 174, 189, 198, 199, 186, 193, 200, 201, 190, 197, 202, 203, 194},
    {204, 204, 204, 204, 207, 208, 209, 210, 211, 211, 211, 211, 212, 213, 214, 215},
    {204, 204, 204, 204, 210, 217, 218, 219, 211, 211, 211, 211, 215, 220, 221, 222},
    {204, 204, 204, 204, 219, 224, 225, 226, 211, 211, 211, 211, 222, 227, 228, 229},
    {204, 204, 204, 204, 226, 230, 231, 207, 211, 211, 211, 211, 229, 232, 233, 212},
    {212, 213, 214, 215, 234, 235, 236, 237, 238, 239, 240, 241, 242, 243, 244, 245},
    {215, 220, 221, 222, 237, 246, 247, 248, 241, 249, 250, 251, 245, 252, 253, 254},
    {222, 227, 228, 229, 248, 255, 256, 257, 251, 258, 259, 260, 254, 261, 262, 263},
    {229, 232, 233, 212, 257, 264, 265, 234, 260, 266, 267, 238, 263, 268, 269, 242},
    {270, 270, 270, 270, 279, 280, 281, 282, 275, 276, 277, 278, 271, 272, 273, 274},
    {270, 270, 270, 270, 282, 289, 290, 291, 278, 286, 287, 288, 274, 283, 284, 285},
    {270, 270, 270, 270, 291, 298, 299, 300, 288, 295, 296, 297, 285, 292, 293, 294},
    {270, 270, 270, 270, 300, 305, 306, 279, 297, 303, 304, 275, 294, 301, 302, 271},
};
// clang-format on

// Cubic Bernstein basis and its derivative at t.
void bernstein(double t, double value[4], double derivative[4]) {
    const double s = 1 - t;
    value[0] = s * s * s;
    value[1] = 3 * t * s * s;
    value[2] = 3 * t * t * s;
    value[3] = t * t * t;
    derivative[0] = -3 * s * s;
    derivative[1] = 3 * s * s - 6 * t * s;
    derivative[2] = 6 * t * s - 3 * t * t;
    derivative[3] = 3 * t * t;
}

struct PatchSample {
    glm::dvec3 position, du, dv;
};

// Columns first (each a curve in v), then across them in u: on an edge u = 0
// or 1 the result is exactly that edge's curve, as its neighbour computes it.
PatchSample evaluate(const std::array<glm::dvec3, 16>& control, double u, double v) {
    double bu[4], dbu[4], bv[4], dbv[4];
    bernstein(u, bu, dbu);
    bernstein(v, bv, dbv);
    PatchSample sample{glm::dvec3(0), glm::dvec3(0), glm::dvec3(0)};
    for (int i = 0; i < 4; ++i) {
        glm::dvec3 column(0), columnDv(0);
        for (int j = 0; j < 4; ++j) {
            column += bv[j] * control[std::size_t(4 * j + i)];
            columnDv += dbv[j] * control[std::size_t(4 * j + i)];
        }
        sample.position += bu[i] * column;
        sample.du += dbu[i] * column;
        sample.dv += bu[i] * columnDv;
    }
    return sample;
}

glm::dvec3 patchNormal(const std::array<glm::dvec3, 16>& control, double u, double v) {
    // Derivatives far below the patch's size are rounding noise (at a pole,
    // dP/du is a sum of equal points times basis slopes that cancel).
    double size = 0;
    for (const glm::dvec3& c : control) size = std::max(size, glm::distance(c, control[0]));
    PatchSample sample = evaluate(control, u, v);
    glm::dvec3 normal = glm::cross(sample.du, sample.dv);
    if (!(glm::length(sample.du) > 1e-9 * size && glm::length(sample.dv) > 1e-9 * size &&
          glm::length(normal) > 1e-9 * size * size)) {
        // A pole (a patch row collapsed to a point): step toward the patch's middle.
        sample = evaluate(control, u + (0.5 - u) * 1e-4, v + (0.5 - v) * 1e-4);
        normal = glm::cross(sample.du, sample.dv);
    }
    return glm::normalize(normal);
}

// GLUT's placement (see the top of this file); a rotation, so normals turn alike.
glm::dvec3 glutFromNewell(const glm::dvec3& p) {
    return {p.x, p.z, -p.y};
}

// Points that agree to 2^-30 share a key (coordinates here are below 4).
struct WeldKey {
    std::int64_t x, y, z;
    bool operator==(const WeldKey&) const = default;
};
struct WeldKeyHash {
    std::size_t operator()(const WeldKey& k) const {
        const std::uint64_t h = std::uint64_t(k.x) * 0x9E3779B97F4A7C15ull ^
                                std::rotl(std::uint64_t(k.y) * 0xC2B2AE3D27D4EB4Full, 21) ^
                                std::rotl(std::uint64_t(k.z) * 0x165667B19E3779F9ull, 42);
        return std::size_t(h ^ (h >> 29));
    }
};
WeldKey weldKey(const glm::dvec3& p) {
    constexpr double kGrid = 1073741824.0;  // 2^30
    return {std::llround(p.x * kGrid), std::llround(p.y * kGrid), std::llround(p.z * kGrid)};
}

}  // namespace

TriangleMesh utahTeapot(int segments) {
    segments = std::clamp(segments, 1, 256);
    TriangleMesh mesh;
    mesh.name = "built-in teapot";
    std::unordered_map<WeldKey, std::uint32_t, WeldKeyHash> weld;
    weld.reserve(std::size(kPatches) * std::size_t(segments + 1) * std::size_t(segments + 1));
    const auto side = std::size_t(segments + 1);
    std::vector<std::uint32_t> positionAt(side * side), normalAt(side * side);

    for (const auto& patch : kPatches) {
        std::array<glm::dvec3, 16> control;
        for (std::size_t k = 0; k < 16; ++k) {
            const double* p = kControlPoints[patch[k] - 1];
            control[k] = glm::dvec3(p[0], p[1], p[2]);
        }
        for (std::size_t j = 0; j < side; ++j) {
            for (std::size_t i = 0; i < side; ++i) {
                const double u = double(i) / segments, v = double(j) / segments;
                const glm::dvec3 p = evaluate(control, u, v).position;
                const auto [where, added] =
                    weld.try_emplace(weldKey(p), std::uint32_t(mesh.positions.size()));
                if (added)
                    mesh.positions.push_back(0.5 * glutFromNewell(p - glm::dvec3(0, 0, 1.5)));
                positionAt[j * side + i] = where->second;
                normalAt[j * side + i] = std::uint32_t(mesh.normals.size());
                mesh.normals.push_back(glutFromNewell(patchNormal(control, u, v)));
            }
        }
        // Two triangles per quad, wound like dP/du x dP/dv (outward).
        for (std::size_t j = 0; j < side - 1; ++j) {
            for (std::size_t i = 0; i < side - 1; ++i) {
                const std::size_t corners[4] = {j * side + i, j * side + i + 1,
                                                (j + 1) * side + i + 1, (j + 1) * side + i};
                for (const auto& [a, b, c] :
                     {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
                    const std::uint32_t pa = positionAt[corners[a]], pb = positionAt[corners[b]],
                                        pc = positionAt[corners[c]];
                    if (pa == pb || pb == pc || pc == pa) continue;  // collapsed at a pole
                    mesh.triangles.push_back(
                        {{pa, pb, pc},
                         {normalAt[corners[a]], normalAt[corners[b]], normalAt[corners[c]]}});
                }
            }
        }
    }
    mesh.closed = false;
    finishMesh(mesh);
    return mesh;
}

}  // namespace vkray
