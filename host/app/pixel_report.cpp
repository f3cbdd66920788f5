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

std::string show(double v) { return std::isinf(v) ? "miss" : format("%.9g", v); }
std::string show(const glm::dvec3& v) { return format("(%.7g, %.7g, %.7g)", v.x, v.y, v.z); }
std::string show(const std::optional<double>& t) { return t ? show(*t) : "miss"; }

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

// One row: label, GPU value, CPU value, |GPU - CPU| (largest component).
class Table {
public:
    template <typename T>
    void row(const std::string& label, const T& gpu, const T& cpu) {
        const double d = difference(gpu, cpu);
        line(label, show(gpu), show(cpu), std::isinf(d) ? "DIFFERENT" : format("%.2g", d));
    }
    void line(const std::string& label, const std::string& gpu, const std::string& cpu,
              const std::string& diff) {
        char text[512];
        std::snprintf(text, sizeof text, "%-22s %-40s %-40s %s\n", label.c_str(), gpu.c_str(),
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
                  (settings.block > 1 ? ", block " + std::to_string(settings.block) : "") + "\n";
    table.line("", "GPU (as float)", "CPU reference (double)", "|GPU - CPU|");
    table.row("ray origin", gpu.rayOrigin, cpu.rayOrigin);
    table.row("ray direction", gpu.rayDirection, cpu.rayDirection);
    const size_t objects = std::min(gpu.objects.size(), cpu.objects.size());
    for (size_t i = 0; i < objects; ++i) {
        table.text_ += objectName(scene, int(i)) + "\n";
        table.row("  generic origin", gpu.objects[i].genericOrigin, cpu.objects[i].genericOrigin);
        table.row("  generic direction", gpu.objects[i].genericDirection,
                  cpu.objects[i].genericDirection);
        table.row("  t", gpu.objects[i].t, cpu.objects[i].t);
    }
    const bool same = gpu.hitObject == cpu.hitObject;
    table.line("closest hit", objectName(scene, gpu.hitObject), objectName(scene, cpu.hitObject),
               same ? "same" : "DIFFERENT");
    if (gpu.hitObject >= 0 || cpu.hitObject >= 0) {
        table.row("t", gpu.t, cpu.t);
        table.row("point", gpu.point, cpu.point);
        table.row("normal", gpu.normal, cpu.normal);
        table.row("emissive", gpu.emissive, cpu.emissive);
        table.row("ambient x global", gpu.ambient, cpu.ambient);
        const size_t lights = std::min(gpu.lights.size(), cpu.lights.size());
        for (size_t i = 0; i < lights; ++i) {
            const std::string light = "light " + std::to_string(i);
            table.row(light + " m.s", gpu.lights[i].mDotS, cpu.lights[i].mDotS);
            table.row(light + " diffuse", gpu.lights[i].diffuse, cpu.lights[i].diffuse);
            table.row(light + " m.h", gpu.lights[i].mDotH, cpu.lights[i].mDotH);
            table.row(light + " specular", gpu.lights[i].specular, cpu.lights[i].specular);
        }
    }
    table.row("colour", gpu.color, cpu.color);
    return table.text_;
}

}  // namespace vkray
