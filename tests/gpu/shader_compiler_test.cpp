#include "gpu/shader_compiler.h"
#include "gpu/precision.h"
#include "gpu/shader_variant.h"
#include "gpu/spirv_cache.h"
#include "shaders/layout.h"
#include "support/error_of.h"
#include "support/gpu_fixture.h"
#include "support/temp_folder.h"
#include "util/error.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace vkray::gpu {
namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kSpirvMagic = 0x07230203;

// A shader folder in `scratch` with the given files.
fs::path shaderFolder(const test::TempFolder& scratch,
                      const std::vector<std::pair<std::string, std::string>>& files) {
    const fs::path dir = scratch.path() / "shaders";
    for (const auto& [file, text] : files) {
        fs::create_directories((dir / file).parent_path());
        std::ofstream(dir / file) << text;
    }
    return dir;
}

const char* kTinyMain =
    "#version 460\n"
    "#extension GL_GOOGLE_include_directive : require\n"
    "#include \"lib/helper.glsl\"\n"
    "layout(local_size_x = 1) in;\n"
    "layout(std430, binding = 0) buffer B { float v[]; };\n"
    "void main() { v[0] = helper(); }\n";

TEST(ShaderCompiler, CompilesTheTracerInEveryShapeVariant) {
    ShaderFeatures features;
    for (std::uint32_t kind : {KIND_SPHERE, KIND_PLANE, KIND_SQUARE, KIND_CUBE}) {
        features.kinds[kind] = true;
        const ShaderSource source{test::kShaderDir, "trace.comp",
                                  definesFor(features, precisionDefines(Precision::Robust))};
        std::vector<std::uint32_t> spirv = compileComputeShader(source);
        ASSERT_GT(spirv.size(), 5u);
        EXPECT_EQ(spirv[0], kSpirvMagic);
    }
}

TEST(ShaderCompiler, TheTracerRefusesAVariantWithAFlagMissing) {
    // GLSL reads an undefined name in #if as 0: without the check, a flag the
    // host forgot would leave its code out in silence.
    for (const std::string& missing : variantFlags()) {
        Defines defines = definesFor(ShaderFeatures{}, precisionDefines(Precision::Robust));
        std::erase_if(defines, [&](const auto& d) { return d.first == missing; });
        const std::string message = errorOf([&] {
            compileComputeShader({test::kShaderDir, "trace.comp", defines});
        });
        EXPECT_NE(message.find("variant_flags.glsl"), std::string::npos)
            << missing << ": " << message;
        EXPECT_NE(message.find("is not defined"), std::string::npos) << missing << ": " << message;
    }
}

TEST(ShaderCompiler, ErrorInIncludedFileNamesThatFileAndLine) {
    const test::TempFolder scratch("vkray-shaders");
    fs::path dir = shaderFolder(scratch, {{"main.comp", kTinyMain},
                                          {"lib/helper.glsl",
                                           "float helper() {\n"
                                           "  return undefinedName;\n"
                                           "}\n"}});
    try {
        compileComputeShader({dir.string(), "main.comp", {}});
        FAIL() << "a broken shader compiled";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("helper.glsl:2"), std::string::npos) << message;
        EXPECT_NE(message.find("undefinedName"), std::string::npos) << message;
    }
}

TEST(ShaderCompiler, DefinesReachTheShader) {
    const test::TempFolder scratch("vkray-shaders");
    fs::path dir = shaderFolder(
        scratch,
        {{"main.comp", kTinyMain}, {"lib/helper.glsl", "float helper() { return VALUE; }\n"}});
    EXPECT_THROW(compileComputeShader({dir.string(), "main.comp", {}}), Error);
    EXPECT_NO_THROW(compileComputeShader({dir.string(), "main.comp", {{"VALUE", "2.0"}}}));
}

TEST(ShaderCompiler, IncludesOutsideTheShaderFolderAreRefused) {
    const test::TempFolder scratch("vkray-shaders");
    fs::path dir = shaderFolder(
        scratch,
        {{"main.comp", kTinyMain}, {"lib/helper.glsl", "#include \"../../outside.glsl\"\n"}});
    std::ofstream(dir.parent_path() / "outside.glsl") << "float helper() { return 1.0; }\n";
    EXPECT_THROW(compileComputeShader({dir.string(), "main.comp", {}}), Error);
}

TEST(SpirvCache, KeyFollowsSourcesAndDefinesAndSecondLoadHits) {
    const test::TempFolder scratch("vkray-shaders");
    fs::path dir = shaderFolder(scratch, {{"main.comp", kTinyMain},
                                          {"lib/helper.glsl", "float helper() { return 1.0; }\n"}});
    const fs::path cache = scratch.path() / "cache";
    const char* previous = std::getenv("VKRAY_CACHE_DIR");
    const std::string saved = previous ? previous : "";
    ::setenv("VKRAY_CACHE_DIR", cache.c_str(), 1);
    const ShaderSource source{dir.string(), "main.comp", {}};
    const std::string key = spirvCacheKey(source);
    EXPECT_NE(key, spirvCacheKey({dir.string(), "main.comp", {{"X", "1"}}}));

    CompiledShader first = loadOrCompile(source);
    CompiledShader second = loadOrCompile(source);
    EXPECT_FALSE(first.cacheHit);
    EXPECT_TRUE(second.cacheHit);
    EXPECT_EQ(first.spirv, second.spirv);
    EXPECT_TRUE(fs::exists(cache / (key + ".spv")));

    // Editing an included file changes the key: no stale SPIR-V.
    std::ofstream(dir / "lib/helper.glsl") << "float helper() { return 2.0; }\n";
    EXPECT_NE(spirvCacheKey(source), key);
    EXPECT_FALSE(loadOrCompile(source).cacheHit);
    if (previous)
        ::setenv("VKRAY_CACHE_DIR", saved.c_str(), 1);
    else
        ::unsetenv("VKRAY_CACHE_DIR");
}

TEST(SpirvCache, TheKeyAndTheCompileReadTheSameBytes) {
    // A file saved between the key's reading and the compile's must not put
    // the new file's SPIR-V under the old file's key: the compile takes the
    // bytes the key was made of.
    const test::TempFolder scratch("vkray-shaders");
    const fs::path dir = shaderFolder(
        scratch,
        {{"main.comp", kTinyMain}, {"lib/helper.glsl", "float helper() { return 1.0; }\n"}});
    const ShaderSource source{dir.string(), "main.comp", {}};
    const ShaderFiles before = readShaderFiles(dir.string());
    EXPECT_EQ(before.size(), 2u);
    EXPECT_EQ(before.at("lib/helper.glsl"), "float helper() { return 1.0; }\n");
    std::ofstream(dir / "lib/helper.glsl") << "this is not GLSL\n";  // the save
    EXPECT_THROW(compileComputeShader(source), Error);               // the folder now
    const std::vector<std::uint32_t> spirv = compileComputeShader(source, before);
    ASSERT_FALSE(spirv.empty());
    EXPECT_EQ(spirv[0], kSpirvMagic);
    EXPECT_NE(spirvCacheKey(source, before), spirvCacheKey(source));
    EXPECT_EQ(spirvCacheKey(source, before), spirvCacheKey(source, before));
}

TEST(ShaderCompiler, IncludesResolveAmongTheShaderSourcesOnly) {
    // Only .comp, .glsl and .h files are read (and keyed): an include of
    // another kind is refused, rather than compiled and left out of the key.
    const test::TempFolder scratch("vkray-shaders");
    const fs::path dir =
        shaderFolder(scratch, {{"main.comp", kTinyMain},
                               {"lib/helper.glsl", "#include \"part.inc\"\n"},
                               {"lib/part.inc", "float helper() { return 1.0; }\n"}});
    const std::string message = errorOf([&] {
        compileComputeShader({dir.string(), "main.comp", {}});
    });
    EXPECT_NE(message.find("part.inc"), std::string::npos) << message;
}

TEST(ShaderCompiler, CompilesTheViewsPresentShader) {
    // `vkray view`'s shader compiles without a window (its tests need an X server).
    const std::vector<std::uint32_t> spirv =
        compileComputeShader({test::kShaderDir, "present.comp", {}});
    ASSERT_FALSE(spirv.empty());
    EXPECT_EQ(spirv[0], kSpirvMagic);
}

}  // namespace
}  // namespace vkray::gpu
