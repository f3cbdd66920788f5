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

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

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

// VKRAY_CACHE_DIR set to `dir` for a test's lifetime.
class ScopedCacheDir {
public:
    explicit ScopedCacheDir(const fs::path& dir) {
        if (const char* previous = std::getenv("VKRAY_CACHE_DIR")) saved_ = previous;
        ::setenv("VKRAY_CACHE_DIR", dir.c_str(), 1);
    }
    ~ScopedCacheDir() {
        if (saved_)
            ::setenv("VKRAY_CACHE_DIR", saved_->c_str(), 1);
        else
            ::unsetenv("VKRAY_CACHE_DIR");
    }
    ScopedCacheDir(const ScopedCacheDir&) = delete;
    ScopedCacheDir& operator=(const ScopedCacheDir&) = delete;

private:
    std::optional<std::string> saved_;
};

TEST(SpirvCache, KeyFollowsSourcesAndDefinesAndSecondLoadHits) {
    const test::TempFolder scratch("vkray-shaders");
    fs::path dir = shaderFolder(scratch, {{"main.comp", kTinyMain},
                                          {"lib/helper.glsl", "float helper() { return 1.0; }\n"}});
    const fs::path cache = scratch.path() / "cache";
    const ScopedCacheDir cacheDir(cache);
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
}

// A file of `bytes` bytes at `path`, last used `age` ago.
void writeAged(const fs::path& path, std::size_t bytes, std::chrono::hours age) {
    std::ofstream(path) << std::string(bytes, 'x');
    fs::last_write_time(path, fs::file_time_type::clock::now() - age);
}

TEST(SpirvCache, PruningRemovesTheEntriesUsedLeastRecentlyAndNothingElse) {
    const test::TempFolder scratch("vkray-cache");
    const fs::path dir = scratch.path();
    // Five entries of 1000 bytes, the first the oldest; and files that are not entries.
    const std::vector<std::string> entries = {"000000000000000a.spv", "000000000000000b.spv",
                                              "000000000000000c.spv", "000000000000000d.spv",
                                              "000000000000000e.spv"};
    for (std::size_t i = 0; i < entries.size(); ++i)
        writeAged(dir / entries[i], 1000, std::chrono::hours(10 - i));
    const std::vector<std::string> others = {"notes.txt", "0123.spv", "000000000000000f.spv.tmp",
                                             "000000000000000g.spv"};
    for (const std::string& other : others) writeAged(dir / other, 5000, std::chrono::hours(99));

    // 2500 bytes of entries at most, the oldest kept (it was just written):
    // the next three oldest go, the newest stays.
    EXPECT_EQ(pruneSpirvCache(dir.string(), 2500, entries[0]), 3u);
    for (std::size_t i = 0; i < entries.size(); ++i)
        EXPECT_EQ(fs::exists(dir / entries[i]), i == 0 || i == 4) << entries[i];
    for (const std::string& other : others) EXPECT_TRUE(fs::exists(dir / other)) << other;

    // Within the limit, nothing goes; a folder that is not there is no error.
    EXPECT_EQ(pruneSpirvCache(dir.string(), 2000, ""), 0u);
    EXPECT_EQ(pruneSpirvCache((dir / "absent").string(), 0, ""), 0u);
}

TEST(SpirvCache, ALoadMarksItsEntryUsedSoThatPruningKeepsIt) {
    const test::TempFolder scratch("vkray-shaders");
    const fs::path dir = shaderFolder(
        scratch,
        {{"main.comp", kTinyMain}, {"lib/helper.glsl", "float helper() { return 1.0; }\n"}});
    const fs::path cache = scratch.path() / "cache";
    const ScopedCacheDir cacheDir(cache);
    const ShaderSource used{dir.string(), "main.comp", {}};
    const ShaderSource unused{dir.string(), "main.comp", {{"X", "1"}}};
    const fs::path usedEntry = cache / (loadOrCompile(used).key + ".spv");
    const fs::path unusedEntry = cache / (loadOrCompile(unused).key + ".spv");
    // Both written long ago, the one to be used the earlier.
    fs::last_write_time(usedEntry, fs::file_time_type::clock::now() - std::chrono::hours(20));
    fs::last_write_time(unusedEntry, fs::file_time_type::clock::now() - std::chrono::hours(10));

    EXPECT_TRUE(loadOrCompile(used).cacheHit);
    EXPECT_EQ(pruneSpirvCache(cache.string(), fs::file_size(usedEntry), ""), 1u);
    EXPECT_TRUE(fs::exists(usedEntry));
    EXPECT_FALSE(fs::exists(unusedEntry));
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
