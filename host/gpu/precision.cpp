#include "gpu/precision.h"

#include "util/error.h"

#include <cmath>

#include <glm/ext/matrix_transform.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

namespace vkray {

const char* precisionName(Precision precision) {
    switch (precision) {
    case Precision::Naive: return "naive";
    case Precision::Robust: return "robust";
    case Precision::Fp64: return "fp64";
    }
    return "?";
}

Precision parsePrecision(const std::string& flag, const std::string& text) {
    for (Precision p : kAllPrecisions)
        if (text == precisionName(p)) return p;
    throw Error(flag + ": expected naive, robust or fp64, found '" + text + "'");
}

std::vector<std::pair<std::string, std::string>> precisionDefines(Precision precision) {
    return {{"VKRAY_PRECISION_NAIVE", precision == Precision::Naive ? "1" : "0"},
            {"VKRAY_PRECISION_FP64", precision == Precision::Fp64 ? "1" : "0"}};
}

namespace {

// a b + c d + e f + g, rounded once (to within u of the result, plus u^2 of
// the terms' sizes): Ogita, Rump and Oishi's Dot2, from error-free products
// (fma) and sums (Knuth's TwoSum).
double compensatedDot(const double (&a)[3], const glm::dvec3& b, double add) {
    double sum = add, error = 0;
    for (int j = 0; j < 3; ++j) {
        const double product = a[j] * b[j];
        const double productError = std::fma(a[j], b[j], -product);
        const double next = sum + product;
        const double back = next - sum;
        error += productError + ((sum - (next - back)) + (product - back));
        sum = next;
    }
    return sum + error;
}

// Camera-relative world: p' = p - origin. An object's M^-1 becomes
// M^-1 T(origin), whose translation column M^-1 (origin, 1) is computed here
// rounded once; so the eye's generic coordinates reach the shader rounded
// once, instead of being rebuilt in float from a float eye and a float
// translation that both lost the low digits (docs/numerics-background.md,
// "Far from the origin"). In plain double the column would carry u_double
// times the size of the terms (|M^-1| |origin|, 1e7 for an eye 1e7 away):
// fp64's t off by 1e-10 of its distance at 10 units from such an eye.
void rebaseObject(SceneObject& object, const glm::dvec3& origin) {
    glm::dmat4& m = object.objectFromWorld;  // m[column][row]
    for (int row = 0; row < 3; ++row) {
        const double rowLinear[3] = {m[0][row], m[1][row], m[2][row]};
        m[3][row] = compensatedDot(rowLinear, origin, m[3][row]);
    }
    object.worldFromObject = glm::translate(glm::dmat4(1.0), -origin) * object.worldFromObject;
    for (SceneObject& operand : object.operands) rebaseObject(operand, origin);
}

// The textbook's inverse: M rounded to float, then inverted in float. An
// ill-conditioned M loses about cond(M) u here (docs/numerics-background.md,
// "Far from the origin").
void invertInFloat(SceneObject& object) {
    const glm::mat4 m(object.worldFromObject);
    object.objectFromWorld = glm::dmat4(glm::inverse(m));
    for (SceneObject& operand : object.operands) invertInFloat(operand);
}

}  // namespace

Scene rebasedOnPoint(const Scene& scene, const glm::dvec3& origin) {
    Scene rebased = scene;
    for (SceneObject& object : rebased.objects) rebaseObject(object, origin);
    for (Light& light : rebased.lights) light.position -= origin;
    if (rebased.camera) {
        rebased.camera->eye -= origin;
        rebased.camera->look -= origin;
    }
    return rebased;
}

Scene withFloatInverses(const Scene& scene) {
    Scene naive = scene;
    for (SceneObject& object : naive.objects) invertInFloat(object);
    return naive;
}

GpuInputs prepareGpuInputs(Precision precision, const Scene& scene, const CameraBasis& camera) {
    if (precision == Precision::Naive) return {withFloatInverses(scene), camera};
    CameraBasis rebasedCamera = camera;
    rebasedCamera.eye = glm::dvec3(0);
    return {rebasedOnPoint(scene, camera.eye), rebasedCamera};
}

}  // namespace vkray
