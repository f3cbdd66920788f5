#include "gpu/shader_compiler.h"

#include "util/error.h"
#include "util/files.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <algorithm>
#include <filesystem>
#include <optional>

namespace vkray::gpu {

namespace fs = std::filesystem;

namespace {

// glslang's process-wide state: initialised once, finalised at exit.
struct GlslangProcess {
    GlslangProcess() { glslang::InitializeProcess(); }
    ~GlslangProcess() { glslang::FinalizeProcess(); }
};

void ensureGlslang() {
    static GlslangProcess process;
}

bool isShaderSource(const fs::path& path) {
    const std::string ext = path.extension().string();
    return ext == ".comp" || ext == ".glsl" || ext == ".h";
}

// Resolves `#include "x"` relative to the including file, then to the shader
// folder, among the files read from it: never outside it.
class FolderIncluder : public glslang::TShader::Includer {
public:
    FolderIncluder(const fs::path& root, const ShaderFiles& files)
        : root_(fs::weakly_canonical(root)), files_(files) {}

    IncludeResult* includeLocal(const char* header, const char* includer, size_t) override {
        fs::path from = fs::path(includer).parent_path();
        if (auto* result = tryInclude(from / header)) return result;
        return tryInclude(root_ / header);
    }
    IncludeResult* includeSystem(const char* header, const char*, size_t) override {
        return tryInclude(root_ / header);
    }
    void releaseInclude(IncludeResult* result) override { delete result; }

private:
    IncludeResult* tryInclude(const fs::path& candidate) {
        const fs::path path = fs::weakly_canonical(candidate);
        auto [rootEnd, _] = std::mismatch(root_.begin(), root_.end(), path.begin(), path.end());
        if (rootEnd != root_.end()) return nullptr;  // outside the shader folder
        const auto file = files_.find(path.lexically_relative(root_).string());
        if (file == files_.end()) return nullptr;
        return new IncludeResult(path.string(), file->second.data(), file->second.size(), nullptr);
    }
    fs::path root_;
    const ShaderFiles& files_;
};

}  // namespace

std::string glslangVersion() {
    const glslang::Version v = glslang::GetVersion();
    return std::to_string(v.major) + "." + std::to_string(v.minor) + "." + std::to_string(v.patch) +
           v.flavor;
}

ShaderFiles readShaderFiles(const std::string& directory) {
    fs::path root = fs::path(directory).lexically_normal();
    if (root.has_parent_path() && root.filename().empty()) root = root.parent_path();  // "dir/"
    ShaderFiles files;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_regular_file() && isShaderSource(it->path()))
            if (std::optional<std::string> bytes = readFileIfPresent(it->path().string()))
                files.emplace(it->path().lexically_relative(root).string(), std::move(*bytes));
    return files;
}

std::vector<std::uint32_t> compileComputeShader(const ShaderSource& source) {
    return compileComputeShader(source, readShaderFiles(source.directory));
}

std::vector<std::uint32_t> compileComputeShader(const ShaderSource& source,
                                                const ShaderFiles& files) {
    ensureGlslang();
    const fs::path mainPath = fs::path(source.directory) / source.mainFile;
    const auto mainFile = files.find(fs::path(source.mainFile).lexically_normal().string());
    if (mainFile == files.end())
        throw Error("cannot read shader '" + mainPath.string() +
                    "'; pass the shader folder with --shader-dir DIR");

    std::string preamble;
    for (const auto& [name, value] : source.defines)
        preamble += "#define " + name + " " + value + "\n";

    glslang::TShader shader(EShLangCompute);
    const std::string name = mainPath.string();
    const std::string& text = mainFile->second;
    const char* texts[] = {text.c_str()};
    const int lengths[] = {int(text.size())};
    const char* names[] = {name.c_str()};
    shader.setStringsWithLengthsAndNames(texts, lengths, names, 1);
    shader.setPreamble(preamble.c_str());
    shader.setEnvInput(glslang::EShSourceGlsl, EShLangCompute, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);

    FolderIncluder includer(source.directory, files);
    const auto messages = EShMessages(EShMsgSpvRules | EShMsgVulkanRules);
    if (!shader.parse(GetDefaultResources(), 460, false, messages, includer))
        throw Error("shader compile failed (" + name + "):\n" + shader.getInfoLog());

    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(messages))
        throw Error("shader link failed (" + name + "):\n" + program.getInfoLog());

    std::vector<std::uint32_t> spirv;
    spv::SpvBuildLogger logger;
    glslang::SpvOptions options;
    options.disableOptimizer = false;
    glslang::GlslangToSpv(*program.getIntermediate(EShLangCompute), spirv, &logger, &options);
    if (spirv.empty())
        throw Error("SPIR-V generation failed (" + name + "): " + logger.getAllMessages());
    return spirv;
}

}  // namespace vkray::gpu
