// Which shader variant a scene gets: only the shapes and the parts of
// Whitted shading it can use (no device needed; compiling them is
// `vkray shaders check`, in tests/app/shader_dev_test.cpp).
#include "gpu/shader_variant.h"
#include "gpu/gpu_tracer.h"
#include "shaders/layout.h"

#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <set>
#include <sstream>

namespace vkray::gpu {
namespace {

ShaderFeatures featuresOfText(const std::string& sdl, int spp = 1, bool allFeatures = false) {
    const Scene scene = parseSdl(sdl, "t.sdl", {});
    RenderSettings settings;
    settings.spp = spp;
    settings.aovs = false;  // as `vkray render` without --aov
    return featuresOf(scene, settings, allFeatures);
}

// Every shader source, by path.
std::vector<std::pair<std::string, std::string>> shaderSources() {
    std::vector<std::pair<std::string, std::string>> files;
    for (const auto& entry :
         std::filesystem::recursive_directory_iterator(VKRAY_SOURCE_DIR "/shaders")) {
        if (!entry.is_regular_file()) continue;
        std::stringstream text;
        text << std::ifstream(entry.path()).rdbuf();
        files.emplace_back(entry.path().string(), text.str());
    }
    return files;
}

TEST(ShaderVariant, EveryFlagAShaderTestsIsAVariantFlag) {
    // A misspelt `#if VKRAY_SHAODWS` would read as 0 and leave code out in
    // silence. Every VKRAY_ name an #if or #elif reads (outside defined())
    // is a variant flag or a name the shaders #define themselves.
    const std::vector<std::string> list = variantFlags();
    std::set<std::string> known(list.begin(), list.end());
    const std::regex defineLine(R"(^\s*#\s*define\s+(VKRAY_\w+))");
    const std::regex condition(R"(^\s*#\s*(if|elif)\s+(.*)$)");
    const std::regex inDefined(R"(defined\s*\(\s*VKRAY_\w+\s*\))");
    const std::regex name(R"(VKRAY_\w+)");
    const auto sources = shaderSources();
    for (const auto& [path, text] : sources) {
        std::istringstream lines(text);
        std::smatch m;
        for (std::string line; std::getline(lines, line);)
            if (std::regex_search(line, m, defineLine)) known.insert(m[1]);
    }
    int tested = 0;
    for (const auto& [path, text] : sources) {
        std::istringstream lines(text);
        int number = 0;
        std::smatch m;
        for (std::string line; std::getline(lines, line);) {
            ++number;
            if (!std::regex_match(line, m, condition)) continue;
            const std::string expression = std::regex_replace(std::string(m[2]), inDefined, "");
            for (auto it = std::sregex_iterator(expression.begin(), expression.end(), name);
                 it != std::sregex_iterator(); ++it) {
                ++tested;
                EXPECT_TRUE(known.count(it->str()))
                    << path << ":" << number << ": " << it->str() << " is not a variant flag";
            }
        }
    }
    EXPECT_GT(tested, 40);  // the shaders' guards were found
}

TEST(ShaderVariant, TheShaderChecksEveryVariantFlag) {
    // shaders/variant_flags.glsl names exactly the flags of variantFlags().
    std::stringstream text;
    text << std::ifstream(VKRAY_SOURCE_DIR "/shaders/variant_flags.glsl").rdbuf();
    const std::string checks = text.str();
    std::set<std::string> checked;
    const std::regex inDefined(R"(defined\((VKRAY_\w+)\))");
    for (auto it = std::sregex_iterator(checks.begin(), checks.end(), inDefined);
         it != std::sregex_iterator(); ++it)
        checked.insert((*it)[1]);
    const std::vector<std::string> list = variantFlags();
    EXPECT_EQ(checked, std::set<std::string>(list.begin(), list.end()));
}

bool hasDefine(const ShaderFeatures& features, const std::string& name) {
    const Defines defines = definesFor(features);
    return std::any_of(defines.begin(), defines.end(),
                       [&](const auto& d) { return d.first == name && d.second == "1"; });
}

TEST(ShaderVariant, AScenesOwnShadingOnly) {
    const ShaderFeatures plain = featuresOfText("sphere cube");
    EXPECT_EQ(plain.shading, decltype(plain.shading){}) << describe(plain);
    EXPECT_EQ(describe(plain), "sphere+cube");
    EXPECT_FALSE(hasDefine(plain, "VKRAY_SHADOWS"));
}

TEST(ShaderVariant, AFewObjectsWithoutMeshesAreTestedInAnUnrolledLoop) {
    EXPECT_EQ(featuresOfText("sphere cube plane").unrolledObjects, 3u);
    std::string eight;
    for (int i = 0; i < 8; ++i) eight += "sphere ";
    EXPECT_EQ(featuresOfText(eight).unrolledObjects, 8u);
    // A BVH, the all-features shader (any scene), a mesh among other
    // objects (its walk) and tori alone (their code not kept for after the
    // walk) keep the loop over the run-time count.
    const std::string nine = eight + "sphere";
    EXPECT_TRUE(featuresOfText(nine).objectBvh);
    EXPECT_EQ(featuresOfText(nine).unrolledObjects, 0u);
    EXPECT_EQ(featuresOfText("sphere cube", 1, true).unrolledObjects, 0u);
    EXPECT_EQ(featuresOfText("sphere tetrahedron").unrolledObjects, 0u);
    // Two objects with a mesh among them get the BVH (the mesh's walk then
    // entered only near it); a lone mesh, or the all-features variant of a
    // scene without one, does not.
    const auto withMeshes = [](const std::string& sdl) {
        Scene scene = parseSdl(sdl, "t.sdl", {});
        loadSceneGeometry(scene, false, nullptr);
        return featuresOf(scene, RenderSettings{}, false);
    };
    EXPECT_TRUE(withMeshes("sphere tetrahedron").objectBvh);
    EXPECT_FALSE(withMeshes("tetrahedron").objectBvh);
    EXPECT_FALSE(featuresOfText("sphere cube", 1, true).objectBvh);
    EXPECT_EQ(featuresOfText("torus torus").unrolledObjects, 0u);
    // One object alone is its test, whatever its shape: no loop, its code once.
    EXPECT_EQ(featuresOfText("torus").unrolledObjects, 1u);
    EXPECT_EQ(withMeshes("tetrahedron").unrolledObjects, 1u);
    EXPECT_EQ(withMeshes("tetrahedron").objectKinds, std::vector<std::uint32_t>{KIND_MESH});
    // Tori beside other shapes, and CSG objects, are kept for after the
    // walk: unrolled, they only go on that list, their code compiled once.
    EXPECT_EQ(featuresOfText("sphere torus").unrolledObjects, 2u);
    EXPECT_EQ(featuresOfText("sphere difference sphere cube").unrolledObjects, 2u);
    EXPECT_TRUE(keepsTori(featuresOfText("sphere torus")));
    EXPECT_FALSE(keepsTori(featuresOfText("torus torus")));
    EXPECT_TRUE(hasDefine(featuresOfText("cube torus"), "VKRAY_KEEP_TORI"));
    EXPECT_FALSE(hasDefine(featuresOfText("torus"), "VKRAY_KEEP_TORI"));
    const Defines defines = definesFor(featuresOfText("sphere cube"));
    EXPECT_NE(std::find(defines.begin(), defines.end(),
                        std::pair<std::string, std::string>("VKRAY_OBJECTS", "2")),
              defines.end());
    // Each unrolled test is told its object's shape (KIND_SPHERE 0, KIND_CUBE 3).
    EXPECT_NE(std::find(defines.begin(), defines.end(),
                        std::pair<std::string, std::string>("VKRAY_OBJECT_KINDS", "0u,3u")),
              defines.end());
    const Defines looped = definesFor(featuresOfText(nine));
    EXPECT_EQ(std::count_if(looped.begin(), looped.end(),
                            [](const auto& d) { return d.first == "VKRAY_OBJECT_KINDS"; }),
              0);
}

TEST(ShaderVariant, ShadowsWhereAFeelerCanMeetAnObject) {
    EXPECT_TRUE(featuresOfText("light 1 2 3 1 1 1 sphere cube").has(Shading::Shadows));
    // No light, or a lone plane or square: no feeler can meet anything.
    EXPECT_FALSE(featuresOfText("sphere cube").has(Shading::Shadows));
    EXPECT_FALSE(featuresOfText("light 1 2 3 1 1 1 plane").has(Shading::Shadows));
    EXPECT_FALSE(featuresOfText("light 1 2 3 1 1 1 square").has(Shading::Shadows));
    // A lone sphere or cube seen from inside shadows itself.
    EXPECT_TRUE(featuresOfText("light 1 2 3 1 1 1 sphere").has(Shading::Shadows));
    EXPECT_TRUE(featuresOfText("light 1 2 3 1 1 1 cube").has(Shading::Shadows));
    EXPECT_TRUE(featuresOfText("light 1 2 3 1 1 1 torus").has(Shading::Shadows));
    EXPECT_TRUE(hasDefine(featuresOfText("light 1 2 3 1 1 1 sphere cube"), "VKRAY_SHADOWS"));
}

// Feelers take hints where they walk a BVH and no unbounded object (a plane)
// takes the first turn of each walk; the stress and debug records count
// each walk's tests as the CPU reference makes them, so they go without.
TEST(ShaderVariant, FeelersTakeHintsInABvhWithoutUnboundedObjects) {
    const std::string lit = "light 1 2 3 1 1 1 ",
                      nine = "sphere sphere sphere cube cube cube cone cone cone ";
    EXPECT_TRUE(hintsFeelers(featuresOfText(lit + nine)));
    EXPECT_TRUE(hasDefine(featuresOfText(lit + nine), "VKRAY_FEELER_HINTS"));
    EXPECT_FALSE(hintsFeelers(featuresOfText(lit + nine + "plane")));
    EXPECT_FALSE(hintsFeelers(featuresOfText(nine)));                 // no light, no feelers
    EXPECT_FALSE(hintsFeelers(featuresOfText(lit + "sphere cube")));  // no BVH
    ShaderFeatures stress = featuresOfText(lit + nine);
    stress.stressOutput = true;
    EXPECT_FALSE(hintsFeelers(stress));
    ShaderFeatures debug = featuresOfText(lit + nine);
    debug.debugPixel = true;
    EXPECT_FALSE(hintsFeelers(debug));
    // The all-features variant of such a scene takes them too.
    EXPECT_TRUE(hintsFeelers(featuresOfText(lit + nine, 1, true)));
}

// Mesh objects go into the object BVH as their triangles in world space
// where none is transparent, the eye and every bounded object are near
// (kWorldSpaceReach of its sizes), and they fit the texel buffer; only in
// the robust mode, never in the all-features variant nor in the stress and
// debug records. A lone mesh then gets an object BVH, and the meshes' nodes
// stay apart from the objects' (a mesh in CSG walks them).
TEST(ShaderVariant, OpaqueMeshesNearTheEyeGoIntoTheObjectBvhInWorldSpace) {
    const auto built = [](const std::string& sdl) {
        Scene scene = parseSdl(sdl, "t.sdl", {});
        loadSceneGeometry(scene, false, nullptr);
        return scene;
    };
    const glm::dvec3 eye(5, 5, 5);
    const std::uint64_t room = std::numeric_limits<std::uint64_t>::max();
    const std::string nine = "sphere sphere sphere cube cube cube cone cone cone ";
    const auto fits = [&](const std::string& sdl) {
        return meshesFitWorldSpace(built(sdl), eye, room);
    };
    EXPECT_TRUE(fits(nine + "tetrahedron octahedron"));
    EXPECT_FALSE(fits(nine));  // no mesh
    EXPECT_FALSE(fits(nine + "tetrahedron transparency 0.5 octahedron"));
    // A mesh in CSG stays in its own space: it is not a mesh object.
    EXPECT_FALSE(fits(nine + "intersection sphere octahedron"));
    // The eye, or another object, within 4096 of the tetrahedron's sizes
    // (its box's diagonal) of its box's centre, and beyond.
    const Scene tetrahedron = built("tetrahedron");
    const Aabb box = worldBounds(tetrahedron.objects[0], tetrahedron);
    const double size = glm::length(box.hi - box.lo);
    const glm::dvec3 away = box.centroid() + glm::dvec3(0, 0, size);
    EXPECT_TRUE(
        meshesFitWorldSpace(tetrahedron, box.centroid() + 4000.0 * (away - box.centroid()), room));
    EXPECT_FALSE(
        meshesFitWorldSpace(tetrahedron, box.centroid() + 4200.0 * (away - box.centroid()), room));
    EXPECT_FALSE(fits("tetrahedron push translate 0 0 " + std::to_string(4200 * size) +
                      " sphere pop"));  // an object that far
    // 4 triangles and their 4 copies, 6 texels each: 48.
    EXPECT_TRUE(meshesFitWorldSpace(built("tetrahedron"), eye, 48));
    EXPECT_FALSE(meshesFitWorldSpace(built("tetrahedron"), eye, 47));

    const Scene scene = built(nine + "tetrahedron");
    const RenderSettings settings;
    const ShaderFeatures robust =
        variantFeatures(scene, settings, false, Precision::Robust, eye, room);
    EXPECT_TRUE(placesTrianglesInWorld(robust));
    EXPECT_TRUE(hasDefine(robust, "VKRAY_WORLD_TRIANGLES"));
    EXPECT_FALSE(meshNodesWithObjects(robust));
    EXPECT_NE(describe(robust).find("+world-triangles"), std::string::npos);
    for (Precision other : {Precision::Naive, Precision::Fp64})
        EXPECT_FALSE(
            placesTrianglesInWorld(variantFeatures(scene, settings, false, other, eye, room)));
    EXPECT_FALSE(placesTrianglesInWorld(
        variantFeatures(scene, settings, true, Precision::Robust, eye, room)));
    ShaderFeatures stress = robust, debug = robust, noBvh = robust;
    stress.stressOutput = true;
    debug.debugPixel = true;
    noBvh.objectBvh = false;
    EXPECT_FALSE(placesTrianglesInWorld(stress));
    EXPECT_FALSE(placesTrianglesInWorld(debug));
    EXPECT_TRUE(meshNodesWithObjects(debug));  // entered by the walk, as ever
    EXPECT_FALSE(placesTrianglesInWorld(noBvh));
    // A lone mesh's triangles get an object BVH of their own.
    const Scene lone = built("tetrahedron");
    const ShaderFeatures alone =
        variantFeatures(lone, settings, false, Precision::Robust, eye, room);
    EXPECT_TRUE(placesTrianglesInWorld(alone));
    EXPECT_EQ(alone.unrolledObjects, 0u);
    EXPECT_FALSE(variantFeatures(lone, settings, false, Precision::Naive, eye, room).objectBvh);
}

// A scene without lights has no light code and binds no lights; a lit
// lone plane has the light code but no feelers.
TEST(ShaderVariant, LightCodeOnlyWhereTheSceneHasLights) {
    const auto bindsLights = [](const ShaderFeatures& f) {
        const std::vector<ShaderBinding> bindings = bindingsFor(f);
        return std::any_of(bindings.begin(), bindings.end(),
                           [](const ShaderBinding& b) { return b.binding == BINDING_LIGHTS; });
    };
    const ShaderFeatures unlit = featuresOfText("sphere cube");
    EXPECT_FALSE(unlit.lights);
    EXPECT_FALSE(hasDefine(unlit, "VKRAY_LIGHTS"));
    EXPECT_FALSE(bindsLights(unlit));
    const ShaderFeatures plane = featuresOfText("light 1 2 3 1 1 1 plane");
    EXPECT_TRUE(hasDefine(plane, "VKRAY_LIGHTS"));
    EXPECT_FALSE(hasDefine(plane, "VKRAY_SHADOWS"));
    EXPECT_TRUE(bindsLights(plane));
    EXPECT_TRUE(hasDefine(featuresOfText("sphere cube", 1, true), "VKRAY_LIGHTS"));
}

TEST(ShaderVariant, SecondaryRaysAboveTheirThresholdsWithRecursion) {
    // Hill: reflectivity must exceed minReflectivity (default 0.5).
    EXPECT_FALSE(featuresOfText("reflectivity 0.5 sphere").has(Shading::Reflection));
    const ShaderFeatures mirror = featuresOfText("reflectivity 0.6 sphere");
    EXPECT_TRUE(mirror.has(Shading::Reflection));
    EXPECT_FALSE(mirror.has(Shading::Refraction));
    EXPECT_EQ(describe(mirror), "sphere+reflection");
    EXPECT_TRUE(
        featuresOfText("minReflectivity 0.1 reflectivity 0.2 sphere").has(Shading::Reflection));
    EXPECT_FALSE(
        featuresOfText("maxRecursionDepth 0 reflectivity 0.9 sphere").has(Shading::Reflection));
    EXPECT_TRUE(featuresOfText("transparency 0.9 sphere").has(Shading::Refraction));
    EXPECT_FALSE(
        featuresOfText("maxRecursionDepth 0 transparency 0.9 sphere").has(Shading::Refraction));
    // A boolean's operands count.
    EXPECT_TRUE(featuresOfText("union sphere transparency 0.9 cube").has(Shading::Refraction));
}

TEST(ShaderVariant, SolidAndImageTexturesApart) {
    const ShaderFeatures solid = featuresOfText("texture 1 sphere texture 2 cube");
    EXPECT_TRUE(solid.has(Shading::Textures));
    EXPECT_FALSE(solid.has(Shading::Pixmaps));
    const ShaderFeatures image = featuresOfText("texture 3 parameters 1 0 sphere");
    EXPECT_FALSE(image.has(Shading::Textures));
    EXPECT_TRUE(image.has(Shading::Pixmaps));
    EXPECT_TRUE(hasDefine(image, "VKRAY_PIXMAPS"));
}

TEST(ShaderVariant, AntialiasingWithMoreThanOneSample) {
    EXPECT_FALSE(featuresOfText("sphere", 1).has(Shading::Antialias));
    EXPECT_TRUE(featuresOfText("sphere", 2).has(Shading::Antialias));
}

TEST(ShaderVariant, AllFeaturesCompilesEverythingIn) {
    const ShaderFeatures all = featuresOf(parseSdl("sphere", "t.sdl", {}), {}, true);
    EXPECT_EQ(describe(all), "all shapes+all shading+blocks+aovs");
    for (const GpuShading& shading : kGpuShading) EXPECT_TRUE(hasDefine(all, shading.define));
    EXPECT_TRUE(hasDefine(all, "VKRAY_BLOCKS"));
}

TEST(ShaderVariant, BlocksWithABlockOfMoreThanOnePixel) {
    // A block's fill is a loop, whose first turn llvmpipe runs even when no
    // lane needs it: a render of one ray a pixel leaves it out.
    const Scene scene = parseSdl("sphere", "t.sdl", {});
    EXPECT_FALSE(featuresOf(scene, {64, 48, 1}, false).blocks);
    const ShaderFeatures blocks = featuresOf(scene, {64, 48, 4}, false);
    EXPECT_TRUE(blocks.blocks);
    EXPECT_TRUE(hasDefine(blocks, "VKRAY_BLOCKS"));
    EXPECT_EQ(describe(blocks), "sphere+blocks+aovs");
}

TEST(ShaderVariant, DepthAndNormalOnlyWhenAsked) {
    // Each word a shader stores is a loop over llvmpipe's lanes: the AOV
    // texel is written only by a variant that was asked for it.
    const Scene scene = parseSdl("sphere", "t.sdl", {});
    RenderSettings settings;
    EXPECT_TRUE(featuresOf(scene, settings, false).aovs);
    EXPECT_TRUE(hasDefine(featuresOf(scene, settings, false), "VKRAY_AOVS"));
    settings.aovs = false;
    const ShaderFeatures colour = featuresOf(scene, settings, false);
    EXPECT_FALSE(colour.aovs);
    EXPECT_FALSE(hasDefine(colour, "VKRAY_AOVS"));
    EXPECT_EQ(describe(colour), "sphere");
    EXPECT_FALSE(featuresOf(scene, settings, true).aovs);
}

TEST(ShaderVariant, OnlyVariantsWhoseRaysMayPauseKeepRayProgress) {
    const auto keepsProgress = [](const ShaderFeatures& f) {
        const std::vector<ShaderBinding> bindings = bindingsFor(f);
        return std::any_of(bindings.begin(), bindings.end(),
                           [](const ShaderBinding& b) { return b.binding == BINDING_PROGRESS; });
    };
    // One ray a pixel, with its feelers, and nothing after it: every pixel is
    // done in its first dispatch (a ray pauses only between two rays).
    for (const char* onePass : {"sphere cube", "light 1 2 3 1 1 1 plane", "texture 1 sphere",
                                "light 1 2 3 1 1 1 sphere cube"}) {
        EXPECT_TRUE(tracesInOnePass(featuresOfText(onePass))) << onePass;
        EXPECT_FALSE(keepsProgress(featuresOfText(onePass))) << onePass;
    }
    // Secondary rays or several samples: a ray may pause.
    EXPECT_FALSE(tracesInOnePass(featuresOfText("sphere", 2)));
    for (const char* more : {"reflectivity 0.6 sphere", "transparency 0.9 sphere"}) {
        EXPECT_FALSE(tracesInOnePass(featuresOfText(more))) << more;
        EXPECT_TRUE(keepsProgress(featuresOfText(more))) << more;
    }
}

TEST(ShaderVariant, ShadersCheckCoversEachShadingFeatureAndTheirMix) {
    const std::vector<ShaderFeatures> variants = allVariants();
    EXPECT_EQ(variants.size(), 150u);
    EXPECT_EQ(
        count_if(variants.begin(), variants.end(), [](const ShaderFeatures& f) { return !f.aovs; }),
        4);
    const auto count = [&](const auto& predicate) {
        return std::count_if(variants.begin(), variants.end(), predicate);
    };
    for (std::size_t i = 0; i < kGpuShading.size(); ++i)
        EXPECT_GE(count([&](const ShaderFeatures& f) {
                      return f.shading[i] &&
                             std::count(f.shading.begin(), f.shading.end(), true) == 1;
                  }),
                  2)
            << kGpuShading[i].name << " alone, with and without the object BVH";
    EXPECT_EQ(count([](const ShaderFeatures& f) {
                  return f.debugPixel && !f.stressOutput &&
                         describe(f).find("all shading") != std::string::npos;
              }),
              2);
    EXPECT_EQ(count([](const ShaderFeatures& f) { return f.stressOutput; }), 2);
    EXPECT_EQ(count([](const ShaderFeatures& f) { return placesTrianglesInWorld(f); }), 2);
    // Every variant is different.
    for (std::size_t i = 0; i < variants.size(); ++i)
        for (std::size_t j = i + 1; j < variants.size(); ++j)
            ASSERT_FALSE(variants[i] == variants[j]) << describe(variants[i]);
    EXPECT_EQ(allVariants(true).size(), 1674u);
}

}  // namespace
}  // namespace vkray::gpu
