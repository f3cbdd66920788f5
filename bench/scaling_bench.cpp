// Cost per ray against scene size (issue #4): 10, 1 000 and 100 000 random
// spheres and a mesh of about a million triangles, on the GPU (lavapipe
// here) and with the CPU reference, side by side in one run; and the BVH
// build times. Prints a Markdown table for BENCHMARKS.md.
//   LP_NUM_THREADS=2 build/vkray_scaling_bench [--size WxH]
#include "gpu/context.h"
#include "gpu/gpu_tracer.h"
#include "reference/reference_tracer.h"
#include "scene/camera.h"
#include "scene/scene_geometry.h"
#include "scene/triangle_mesh.h"

#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <random>
#include <thread>

namespace {

using namespace vkray;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

SceneObject placed(ShapeType type, const glm::dmat4& worldFromObject) {
    SceneObject object;
    object.type = type;
    object.worldFromObject = worldFromObject;
    object.objectFromWorld = glm::inverse(worldFromObject);
    return object;
}

// n spheres at random in a cube whose side grows like n^(1/3), so that the
// image stays about as full whatever n.
Scene randomSpheres(int n) {
    Scene scene;
    scene.lights.push_back({{50, 80, 60}, {1, 1, 1}, {}});
    const double side = 4 * std::cbrt(double(n));
    std::mt19937 random(12345);
    std::uniform_real_distribution<double> coordinate(-side / 2, side / 2);
    for (int i = 0; i < n; ++i) {
        const glm::dvec3 centre(coordinate(random), coordinate(random), coordinate(random));
        glm::dmat4 m = glm::translate(glm::dmat4(1.0), centre);
        scene.objects.push_back(placed(ShapeType::Sphere, glm::scale(m, glm::dvec3(1.0))));
    }
    scene.camera = Camera{{side * 1.2, side * 0.9, side * 1.2}, {0, 0, 0}, {0, 1, 0}, 60};
    return scene;
}

// A UV sphere of 2 * rings * rings triangles with smooth normals.
Scene bigMesh(int rings) {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->name = "uv sphere";
    const double pi = 3.14159265358979323846;
    for (int i = 0; i <= rings; ++i) {
        for (int j = 0; j <= rings; ++j) {
            const double theta = pi * i / rings, phi = 2 * pi * j / rings;
            const glm::dvec3 p(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                               std::cos(theta));
            mesh->positions.push_back(p);
            mesh->normals.push_back(p);
        }
    }
    const auto at = [&](int i, int j) { return std::uint32_t(i * (rings + 1) + j); };
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < rings; ++j) {
            const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            mesh->triangles.push_back({{a, b, c}, {a, b, c}});
            mesh->triangles.push_back({{a, c, d}, {a, c, d}});
        }
    }
    const auto start = Clock::now();
    finishMesh(*mesh);
    std::printf("mesh BVH over %zu triangles built in %.3f s\n", mesh->triangles.size(),
                secondsSince(start));
    Scene scene;
    scene.lights.push_back({{5, 8, 6}, {1, 1, 1}, {}});
    scene.meshes.push_back(mesh);
    SceneObject object = placed(ShapeType::Mesh, glm::dmat4(1.0));
    object.mesh = 0;
    scene.objects.push_back(object);
    scene.camera = Camera{{2.2, 1.2, 2.4}, {0, 0, 0}, {0, 1, 0}, 45};
    return scene;
}

struct Rates {
    double gpu, gpuDispatch, cpu;  // whole render / dispatch loop only / CPU reference
};

Rates measure(const Scene& scene, const RenderSettings& settings, gpu::GpuTracer& tracer,
              int threads) {
    const CameraBasis camera = makeCameraBasis(*scene.camera, settings.width, settings.height);
    const double rays = double(settings.width) * settings.height;
    tracer.render(scene, camera, settings);  // compile and warm the variant's pipeline
    gpu::GpuRenderStats stats;
    auto start = Clock::now();
    tracer.render(scene, camera, settings, &stats);
    const double gpuSeconds = secondsSince(start);
    start = Clock::now();
    reference::render(scene, camera, settings, {threads});
    const double cpuSeconds = secondsSince(start);
    return {rays / gpuSeconds / 1e6, rays / stats.renderSeconds / 1e6, rays / cpuSeconds / 1e6};
}

}  // namespace

int main(int argc, char** argv) {
    RenderSettings settings{960, 540, 1};
    for (int i = 1; i + 1 < argc; ++i)
        if (std::string(argv[i]) == "--size")
            std::sscanf(argv[i + 1], "%dx%d", &settings.width, &settings.height);
    try {
        gpu::Context context;
        const std::string shaders =
            (std::filesystem::path(argv[0]).parent_path() / "shaders").string();
        gpu::GpuTracer tracer(context, {.shaderDirectory = shaders});
        const int threads = int(std::max(1u, std::thread::hardware_concurrency()));
        const char* lp = std::getenv("LP_NUM_THREADS");
        std::printf("%dx%d primary rays; GPU %s, LP_NUM_THREADS=%s; CPU reference %d threads\n\n",
                    settings.width, settings.height, context.device().name.c_str(),
                    lp ? lp : "(unset)", threads);

        std::printf("| scene | object BVH build | GPU Mrays/s (whole render) | GPU Mrays/s "
                    "(dispatch) | CPU Mrays/s | GPU/CPU (whole) |\n");
        std::printf("|---|---|---|---|---|---|\n");
        double gpuAt10 = 0, cpuAt10 = 0, gpuAtMost = 0, cpuAtMost = 0;
        for (int n : {10, 1000, 100000}) {
            const Scene scene = randomSpheres(n);
            const auto start = Clock::now();
            buildObjectBvh(scene);
            const double build = secondsSince(start);
            const Rates r = measure(scene, settings, tracer, threads);
            std::printf("| %d spheres | %.4f s | %.2f | %.2f | %.2f | %.2f |\n", n, build, r.gpu,
                        r.gpuDispatch, r.cpu, r.gpu / r.cpu);
            std::fflush(stdout);
            if (n == 10) { gpuAt10 = r.gpuDispatch; cpuAt10 = r.cpu; }
            if (n == 100000) { gpuAtMost = r.gpuDispatch; cpuAtMost = r.cpu; }
        }
        const Scene mesh = bigMesh(708);
        const Rates r = measure(mesh, settings, tracer, threads);
        std::printf("| mesh, %zu triangles | - | %.2f | %.2f | %.2f | %.2f |\n",
                    size_t(2) * 708 * 708, r.gpu, r.gpuDispatch, r.cpu, r.gpu / r.cpu);
        std::printf("\ncost per ray at 100000 spheres / at 10: GPU (dispatch) %.2fx, CPU %.2fx\n",
                    gpuAt10 / gpuAtMost, cpuAt10 / cpuAtMost);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vkray_scaling_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
