#include "app/random_scene_draw.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>
#include <glm/trigonometric.hpp>

#include <cstdio>
#include <cstdlib>

namespace vkray::random_scene {

std::string num(double v, bool precise) {
    char text[32];
    std::snprintf(text, sizeof text, precise ? "%.17g" : "%.6g", v);
    return text;
}

double written(double v, bool precise) {
    return std::strtod(num(v, precise).c_str(), nullptr);
}

dvec3 written(dvec3 v, bool precise) {
    return {written(v.x, precise), written(v.y, precise), written(v.z, precise)};
}

std::string triple(dvec3 v, bool precise) {
    return num(v.x, precise) + " " + num(v.y, precise) + " " + num(v.z, precise);
}

std::string pyramid3vn() {
    return "5 5 5\n"
           "-1 0 -1  1 0 -1  1 0 1  -1 0 1  0 1.5 0\n"
           "0 -1 0  0 0.5547 -0.83205  0.83205 0.5547 0  0 0.5547 0.83205  -0.83205 0.5547 0\n"
           "4 0 1 2 3  0 0 0 0\n"
           "3 0 4 1  1 1 1\n"
           "3 1 4 2  2 2 2\n"
           "3 2 4 3  3 3 3\n"
           "3 3 4 0  4 4 4\n";
}

dvec3 unrotate(const Rotation& r, dvec3 v) {
    const glm::dmat4 m =
        glm::rotate(glm::dmat4(1.0), glm::radians(r.degrees), glm::normalize(r.axis));
    return dvec3(glm::transpose(m) * glm::dvec4(v, 0.0));
}

bool centredSolid(const std::string& shape) {
    return shape == "sphere" || shape == "cube" || shape == "torus" || shape == "tetrahedron" ||
           shape == "octahedron" || shape == "dodecahedron" || shape == "icosahedron" ||
           shape == "buckyball";
}

std::string drawLights(Draw& d, double extent) {
    std::string lines;
    const int lights = 1 + d.below(4);
    for (int i = 0; i < lights; ++i) {
        lines += "light " + triple(d.vec({-3, 0, -3}, {3, 4, 3}) * extent);
        lines += " " + triple(d.vec(.2, 1)) + "\n";
    }
    return lines;
}

void drawSettings(Draw& d, RandomScene& r) {
    const int sizes[][2] = {{24, 18}, {32, 24}, {40, 30}};
    const int* size = sizes[d.below(3)];
    r.width = size[0];
    r.height = size[1];
    r.block = d.chance(.2) ? 2 + d.below(2) : 1;
    const int spps[] = {1, 1, 1, 2, 4, 9, 16};
    r.spp = d.chance(.02) ? 256 : spps[d.below(7)];
    r.sampleSeed = std::uint32_t(d.next());
}

double toward(Draw& d, double least, double most) {
    return d.chance(.3) ? most * d.range(.5, 1) : d.logRange(least, most);
}

}  // namespace vkray::random_scene
