#include "app/pixel_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vkray {

namespace {

std::string format(const char* pattern, double a, double b = 0, double c = 0) {
    char text[128];
    std::snprintf(text, sizeof text, pattern, a, b, c);
    return text;
}

// A number with `digits` significant digits: 9 show a float exactly, 17 a double.
std::string show(double v, int digits) {
    if (std::isinf(v)) return "miss";
    char text[64];
    std::snprintf(text, sizeof text, "%.*g", digits, v);
    return text;
}
std::string show(const glm::dvec3& v, int digits) {
    return "(" + show(v.x, digits) + ", " + show(v.y, digits) + ", " + show(v.z, digits) + ")";
}
std::string show(const std::optional<double>& t, int digits) {
    return t ? show(*t, digits) : "miss";
}

std::string feelerText(const PixelTrace::LightTerms& terms) {
    if (!terms.feelerMet) return "not traced";
    if (!*terms.feelerMet) return "clear";
    return terms.feelerMetLeft.value_or(false) ? "met the object it left" : "met a surface";
}

double difference(double a, double b) {
    if (std::isinf(a) && std::isinf(b)) return 0;
    return std::abs(a - b);
}
double difference(const glm::dvec3& a, const glm::dvec3& b) {
    return std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z)});
}
double difference(const std::optional<double>& a, const std::optional<double>& b) {
    if (!a && !b) return 0;
    if (!a || !b) return INFINITY;
    return std::abs(*a - *b);
}

// One row: label, GPU value, CPU value, |GPU - CPU| (largest component),
// each side with its own significant digits.
class Table {
public:
    template <typename T>
    void row(const std::string& label, const T& gpu, int gpuDigits, const T& cpu, int cpuDigits) {
        const double d = difference(gpu, cpu);
        line(label, show(gpu, gpuDigits), show(cpu, cpuDigits),
             std::isinf(d) ? "DIFFERENT" : format("%.2g", d));
    }
    void line(const std::string& label, const std::string& gpu, const std::string& cpu,
              const std::string& diff) {
        char text[512];
        std::snprintf(text, sizeof text, "%-22s %-50s %-50s %s\n", label.c_str(), gpu.c_str(),
                      cpu.c_str(), diff.c_str());
        text_ += text;
    }
    std::string text_;
};

std::string objectName(const Scene& scene, int index) {
    if (index < 0) return "background";
    const SceneObject& object = scene.objects[size_t(index)];
    return "object " + std::to_string(index) + " " + shapeKeyword(object.type) + " (" +
           object.loc.str() + ")";
}

}  // namespace

std::string formatPixelReport(const Scene& scene, const RenderSettings& settings,
                              const PixelTrace& gpu, const PixelTrace& cpu) {
    Table table;
    table.text_ = "pixel (" + std::to_string(gpu.x) + ", " + std::to_string(gpu.y) + ") of " +
                  std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                  (settings.block > 1 ? ", block " + std::to_string(settings.block) : "") +
                  (settings.spp > 1 ? ", sample " + std::to_string(settings.firstSample) + " of " +
                                          std::to_string(settings.spp) + " (seed " +
                                          std::to_string(settings.seed) + ")"
                                    : "") +
                  "\n";
    table.line("", gpu.geometryDigits == 17 ? "GPU (t and normal in double)" : "GPU (float)",
               "CPU reference (double)", "|GPU - CPU|");
    const int g = gpu.digits, c = cpu.digits;
    table.row("ray origin", gpu.rayOrigin, g, cpu.rayOrigin, c);
    table.row("ray direction", gpu.rayDirection, g, cpu.rayDirection, c);
    const size_t objects = std::min(gpu.objects.size(), cpu.objects.size());
    for (size_t i = 0; i < objects; ++i) {
        table.text_ += objectName(scene, int(i)) + "\n";
        table.row("  generic origin", gpu.objects[i].genericOrigin, g, cpu.objects[i].genericOrigin,
                  c);
        table.row("  generic direction", gpu.objects[i].genericDirection, g,
                  cpu.objects[i].genericDirection, c);
        table.row("  t", gpu.objects[i].t, g, cpu.objects[i].t, c);
    }
    const bool same = gpu.hitObject == cpu.hitObject;
    table.line("closest hit", objectName(scene, gpu.hitObject), objectName(scene, cpu.hitObject),
               same ? "same" : "DIFFERENT");
    if (gpu.hitObject >= 0 || cpu.hitObject >= 0) {
        table.row("t", gpu.t, gpu.geometryDigits, cpu.t, cpu.geometryDigits);
        table.row("point", gpu.point, g, cpu.point, c);
        table.row("normal", gpu.normal, gpu.geometryDigits, cpu.normal, cpu.geometryDigits);
        table.row("emissive", gpu.emissive, g, cpu.emissive, c);
        table.row("ambient x global", gpu.ambient, g, cpu.ambient, c);
        const size_t lights = std::min(gpu.lights.size(), cpu.lights.size());
        for (size_t i = 0; i < lights; ++i) {
            const std::string light = "light " + std::to_string(i);
            const PixelTrace::LightTerms &a = gpu.lights[i], &b = cpu.lights[i];
            table.line(light + " feeler", feelerText(a), feelerText(b),
                       a.feelerMet == b.feelerMet ? "same" : "DIFFERENT");
            table.row(light + " m.s", a.mDotS, g, b.mDotS, c);
            table.row(light + " diffuse", a.diffuse, g, b.diffuse, c);
            table.row(light + " m.h", a.mDotH, g, b.mDotH, c);
            table.row(light + " specular", a.specular, g, b.specular, c);
        }
    }
    table.row("colour", gpu.color, g, cpu.color, c);
    return table.text_;
}

}  // namespace vkray
