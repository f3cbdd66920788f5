#include "scene/sdl_reader.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>
#include <memory>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "scene/scene_builder.h"
#include "scene/sdl_lexer.h"
#include "util/error.h"
#include "util/files.h"

namespace vkray {

namespace {

// Every statement word of Hill's grammar (shapes are looked up separately)
// plus vkray's `camera`.
// clang-format off
enum class Keyword {
    Light, Background, GlobalAmbient, MinReflectivity, MinTransparency, MaxRecursionDepth,
    Translate, Rotate, Scale, Push, Pop, IdentityAffine,
    Ambient, Diffuse, Specular, Emissive, SpecularExponent, Reflectivity, Transparency,
    SpeedOfLight, SpecularFraction, SurfaceRoughness, Texture, Parameters, DefaultMaterials,
    MakePixmap, Camera,
};
// clang-format on

const std::unordered_map<std::string_view, Keyword>& keywordTable() {
    static const std::unordered_map<std::string_view, Keyword> table = {
        {"light", Keyword::Light},
        {"background", Keyword::Background},
        {"globalAmbient", Keyword::GlobalAmbient},
        {"minReflectivity", Keyword::MinReflectivity},
        {"minTransparency", Keyword::MinTransparency},
        {"maxRecursionDepth", Keyword::MaxRecursionDepth},
        {"translate", Keyword::Translate},
        {"rotate", Keyword::Rotate},
        {"scale", Keyword::Scale},
        {"push", Keyword::Push},
        {"pop", Keyword::Pop},
        {"identityAffine", Keyword::IdentityAffine},
        {"ambient", Keyword::Ambient},
        {"diffuse", Keyword::Diffuse},
        {"specular", Keyword::Specular},
        {"emissive", Keyword::Emissive},
        {"specularExponent", Keyword::SpecularExponent},
        {"reflectivity", Keyword::Reflectivity},
        {"transparency", Keyword::Transparency},
        {"speedOfLight", Keyword::SpeedOfLight},
        {"specularFraction", Keyword::SpecularFraction},
        {"surfaceRoughness", Keyword::SurfaceRoughness},
        {"texture", Keyword::Texture},
        {"parameters", Keyword::Parameters},
        {"defaultMaterials", Keyword::DefaultMaterials},
        {"makePixmap", Keyword::MakePixmap},
        {"camera", Keyword::Camera},
    };
    return table;
}

std::optional<ShapeType> shapeFor(std::string_view word) {
    for (int i = 0; i < kShapeTypeCount; ++i) {
        const auto type = static_cast<ShapeType>(i);
        if (word == shapeKeyword(type)) return type;
    }
    return std::nullopt;
}

bool isNumberToken(const Token& token) {
    double ignored = 0;
    return parseSdlNumber(token.text, ignored) == NumberStatus::Ok;
}

class SdlParser {
public:
    SdlParser(std::string_view text, const std::string& fileName, const SdlOptions& options,
              std::vector<std::string>* warnings)
        : stream_(tokenizeSdl(text, fileName), options),
          options_(options),
          warnings_(warnings),
          sceneFolder_(std::filesystem::path(fileName).parent_path()) {}

    // A statement in error is reported and skipped up to the next keyword,
    // so that one run names every error of the file (up to
    // kMaxReportedErrors), each at its place; the scene is then refused with
    // all of them.
    Scene parse() {
        std::vector<std::string> errors;
        bool skipping = false;
        for (;;) {
            try {
                if (skipping) skipToNextStatement();
                skipping = false;
                const std::optional<Token> word = nextToken();
                if (!word) break;
                parseStatement(*word);
            } catch (const Error& e) {
                errors.push_back(e.what());
                // An error of def/use expansion leaves no statement to go on from.
                if (streamFailed_ || errors.size() == kMaxReportedErrors) break;
                skipping = true;
            }
        }
        std::optional<Scene> scene;
        try {
            scene = builder_.finish();
        } catch (const Error& e) {
            if (errors.size() < kMaxReportedErrors) errors.push_back(e.what());
        }
        if (!errors.empty()) {
            std::string message = errors.front();
            for (std::size_t i = 1; i < errors.size(); ++i) message += "\n" + errors[i];
            throw Error(message);
        }
        return std::move(*scene);
    }

private:
    static constexpr std::size_t kMaxReportedErrors = 20;

    // After an error: drops the tokens up to the next word that starts a
    // statement (a keyword or a shape).
    void skipToNextStatement() {
        const auto& table = keywordTable();
        while (const Token* following = peekToken()) {
            if (table.count(following->text) != 0 || shapeFor(following->text)) return;
            nextToken();
        }
    }

    // The stream's tokens; an error of the stream itself (def/use
    // expansion) is remembered, as parsing cannot go on after it.
    std::optional<Token> nextToken() {
        try {
            return stream_.next();
        } catch (const Error&) {
            streamFailed_ = true;
            throw;
        }
    }
    const Token* peekToken() {
        try {
            return stream_.peek();
        } catch (const Error&) {
            streamFailed_ = true;
            throw;
        }
    }

    // One statement starting at `word`, told to the builder.
    void parseStatement(const Token& word);
    void parseSetting(Keyword keyword, const Token& word);
    void parseCamera(const Token& word);
    void parseShape(ShapeType type, const Token& word);
    void skipUnknown(const Token& word);

    Token nextArgument(const Token& keyword, const char* what);
    double readNumber(const Token& keyword, Token* where = nullptr);
    glm::dvec3 readVec3(const Token& keyword);
    int readCount(const Token& keyword, const char* what);
    std::string readFileName(const Token& keyword);

    SdlTokenStream stream_;
    SdlOptions options_;
    std::vector<std::string>* warnings_;
    std::filesystem::path sceneFolder_;
    SceneBuilder builder_;
    bool streamFailed_ = false;
};

void SdlParser::parseStatement(const Token& word) {
    const auto& table = keywordTable();
    if (const auto keyword = table.find(word.text); keyword != table.end()) {
        parseSetting(keyword->second, word);
        return;
    }
    if (const std::optional<ShapeType> type = shapeFor(word.text)) return parseShape(*type, word);
    if (word.text == "}") throwAt(word, "'}' without a matching '{'");
    if (word.text == "{") throwAt(word, "'{' outside a def (only 'def NAME { ... }' has braces)");
    skipUnknown(word);
}

void SdlParser::skipUnknown(const Token& word) {
    const bool isNumber = isNumberToken(word);
    if (!options_.lenient) {
        if (isNumber) throwAt(word, "expected a keyword, found the number " + inQuotes(word.text));
        throwAt(word, "unknown keyword " + inQuotes(word.text));
    }
    // Lenient: real files hold words of other SDL dialects, mostly followed
    // by their numbers (`exponent 50`); skip both, say so, go on.
    int skipped = 0;
    while (const Token* following = peekToken()) {
        if (!isNumberToken(*following)) break;
        nextToken();
        ++skipped;
    }
    const std::string what = isNumber ? "unexpected number " : "unknown keyword ";
    const std::string message = what + inQuotes(word.text) + " skipped (with " +
                                std::to_string(skipped) + (skipped == 1 ? " number" : " numbers") +
                                " after it)";
    if (warnings_) warnings_->push_back(diagnosticAt(word, "warning", message));
}

void SdlParser::parseSetting(Keyword keyword, const Token& word) {
    switch (keyword) {
    case Keyword::Light: {
        Light light;
        light.position = readVec3(word);
        light.color = readVec3(word);
        light.loc = word.loc;
        builder_.scene().lights.push_back(light);
        break;
    }
    case Keyword::Background: builder_.scene().background = readVec3(word); break;
    case Keyword::GlobalAmbient: builder_.scene().globalAmbient = readVec3(word); break;
    case Keyword::MinReflectivity: builder_.scene().minReflectivity = readNumber(word); break;
    case Keyword::MinTransparency: builder_.scene().minTransparency = readNumber(word); break;
    case Keyword::MaxRecursionDepth: {
        Token where;
        const double depth = readNumber(word, &where);
        if (depth < 0 || depth > kMaxRecursionDepth || depth != std::floor(depth))
            throwAt(where, "'maxRecursionDepth' needs a whole number from 0 to " +
                               std::to_string(kMaxRecursionDepth) + ", found " +
                               inQuotes(where.text) +
                               " (the GPU follows reflections and refractions with a "
                               "stack of that depth)");
        builder_.scene().maxRecursionDepth = int(depth);
        break;
    }

    case Keyword::Translate: {
        const glm::dvec3 d = readVec3(word);
        builder_.transform(word, glm::translate(glm::dmat4(1.0), d),
                           glm::translate(glm::dmat4(1.0), -d));
        break;
    }
    case Keyword::Rotate: {
        const double degrees = readNumber(word);
        const glm::dvec3 axis = readVec3(word);
        if (axis == glm::dvec3(0.0)) throwAt(word, "rotate axis 0 0 0 has no direction");
        // Scaled to a largest component of 1 first: a tiny axis (1e-200 0 0)
        // would underflow to length 0 and a huge one overflow.
        const double largest = std::max({std::abs(axis.x), std::abs(axis.y), std::abs(axis.z)});
        const glm::dvec3 unitAxis = glm::normalize(axis / largest);
        const double radians = glm::radians(degrees);
        builder_.transform(word, glm::rotate(glm::dmat4(1.0), radians, unitAxis),
                           glm::rotate(glm::dmat4(1.0), -radians, unitAxis));
        break;
    }
    case Keyword::Scale: {
        const glm::dvec3 s = readVec3(word);
        if (s.x == 0 || s.y == 0 || s.z == 0)
            throwAt(word, "scale factor 0 makes the transform singular");
        builder_.transform(word, glm::scale(glm::dmat4(1.0), s),
                           glm::scale(glm::dmat4(1.0), 1.0 / s));
        break;
    }
    case Keyword::Push: builder_.push(); break;
    case Keyword::Pop: builder_.pop(word); break;
    case Keyword::IdentityAffine: builder_.identityAffine(); break;

    case Keyword::Ambient: builder_.material().ambient = readVec3(word); break;
    case Keyword::Diffuse: builder_.material().diffuse = readVec3(word); break;
    case Keyword::Specular: builder_.material().specular = readVec3(word); break;
    case Keyword::Emissive: builder_.material().emissive = readVec3(word); break;
    case Keyword::SpecularExponent: builder_.material().specularExponent = readNumber(word); break;
    case Keyword::Reflectivity: builder_.material().reflectivity = readNumber(word); break;
    case Keyword::Transparency: builder_.material().transparency = readNumber(word); break;
    case Keyword::SpeedOfLight: builder_.material().speedOfLight = readNumber(word); break;
    case Keyword::SpecularFraction: builder_.material().specularFraction = readNumber(word); break;
    case Keyword::SurfaceRoughness: builder_.material().surfaceRoughness = readNumber(word); break;
    case Keyword::Texture: {
        Token where;
        double code = readNumber(word, &where);
        if (code != 0 && code != 1 && code != 2 && code != 3) {
            const std::string message =
                "texture " + where.text + " is not one of 0 none, 1 checkerboard, 2 wood, 3 image";
            if (!options_.lenient) throwAt(word, message);
            // Lenient: real files write codes of other dialects (`texture -1`);
            // the shapes after it are drawn as with `texture 0`.
            if (warnings_)
                warnings_->push_back(diagnosticAt(
                    word, "warning", message + "; drawn without a texture (as texture 0)"));
            code = 0;
        }
        builder_.material().texture = int(code);
        builder_.material().textureLoc = word.loc;
        break;
    }
    case Keyword::Parameters: {
        const int count = readCount(word, "a parameter count >= 0");
        std::vector<double> parameters;
        for (int i = 0; i < count; ++i) parameters.push_back(readNumber(word));
        builder_.material().textureParameters = std::move(parameters);
        break;
    }
    case Keyword::DefaultMaterials: builder_.defaultMaterials(); break;
    case Keyword::MakePixmap: {
        Pixmap pixmap;
        pixmap.index = readCount(word, "a pixmap number >= 0");
        pixmap.file = readFileName(word);
        pixmap.loc = word.loc;
        builder_.scene().pixmaps.push_back(std::move(pixmap));
        break;
    }
    case Keyword::Camera: parseCamera(word); break;
    }
}

void SdlParser::parseCamera(const Token& word) {
    // Parts come in any order, each optional; the statement ends at the first
    // word that is not a part. A second `camera` changes only what it names.
    Camera camera = builder_.scene().camera.value_or(Camera{});
    while (const Token* part = peekToken()) {
        const std::string name = part->text;
        if (name != "eye" && name != "look" && name != "up" && name != "fov") break;
        const Token partWord = *nextToken();
        if (name == "eye") {
            camera.eye = readVec3(partWord);
        } else if (name == "look") {
            camera.look = readVec3(partWord);
        } else if (name == "up") {
            camera.up = readVec3(partWord);
        } else {
            Token where;
            const double fov = readNumber(partWord, &where);
            if (!(fov > 0 && fov < 180))
                throwAt(where, "camera fov " + where.text +
                                   " is outside (0, 180) degrees (the vertical view angle)");
            camera.fovDegrees = fov;
        }
    }
    camera.loc = word.loc;
    builder_.scene().camera = camera;
}

void SdlParser::parseShape(ShapeType type, const Token& word) {
    SceneObject object;
    object.type = type;
    object.loc = word.loc;
    switch (type) {
    case ShapeType::Cone: object.taper = 0; break;
    case ShapeType::TaperedCylinder: object.taper = readNumber(word); break;
    case ShapeType::Mesh:
    case ShapeType::Extrude: object.file = readFileName(word); break;
    default: break;
    }
    builder_.shape(std::move(object), word);
}

Token SdlParser::nextArgument(const Token& keyword, const char* what) {
    std::optional<Token> argument = nextToken();
    if (!argument)
        throwAt(keyword, inQuotes(keyword.text) + " is missing " + what + " (end of file)");
    return std::move(*argument);
}

double SdlParser::readNumber(const Token& keyword, Token* where) {
    const Token argument = nextArgument(keyword, "a number");
    double value = 0;
    switch (parseSdlNumber(argument.text, value)) {
    case NumberStatus::Ok: break;
    case NumberStatus::Malformed:
        throwAt(argument, "expected a number after " + inQuotes(keyword.text) + ", found " +
                              inQuotes(argument.text));
    case NumberStatus::NotFinite:
        throwAt(argument, "expected a finite number after " + inQuotes(keyword.text) + ", found " +
                              inQuotes(argument.text));
    case NumberStatus::OutOfRange:
        throwAt(argument, "number " + inQuotes(argument.text) + " after " + inQuotes(keyword.text) +
                              " is out of range");
    }
    if (std::abs(value) > kMaxSceneMagnitude)
        throwAt(argument, "number " + inQuotes(argument.text) + " after " + inQuotes(keyword.text) +
                              " is beyond vkray's limit of 1e18 for scene numbers (the GPU "
                              "computes in float)");
    if (where) *where = argument;
    return value;
}

glm::dvec3 SdlParser::readVec3(const Token& keyword) {
    const double x = readNumber(keyword);
    const double y = readNumber(keyword);
    const double z = readNumber(keyword);
    return {x, y, z};
}

int SdlParser::readCount(const Token& keyword, const char* what) {
    Token where;
    const double value = readNumber(keyword, &where);
    if (value < 0 || value != std::floor(value) || value > 2147483647.0)
        throwAt(where,
                inQuotes(keyword.text) + " needs " + what + ", found " + inQuotes(where.text));
    return static_cast<int>(value);
}

std::string SdlParser::readFileName(const Token& keyword) {
    const Token name = nextArgument(keyword, "a file name");
    if (name.text == "{" || name.text == "}")
        throwAt(name, "expected a file name after " + inQuotes(keyword.text) + ", found " +
                          inQuotes(name.text));
    // Relative to the scene file's folder, as the scene's author meant it;
    // the file itself is read by whoever needs it.
    return (sceneFolder_ / name.text).string();
}

}  // namespace

Scene parseSdl(std::string_view text, const std::string& fileName, const SdlOptions& options,
               std::vector<std::string>* warnings) {
    return SdlParser(text, fileName, options, warnings).parse();
}

Scene loadSdlFile(const std::string& path, const SdlOptions& options,
                  std::vector<std::string>* warnings) {
    std::string text;
    try {
        text = readFile(path);
    } catch (const FileReadError& e) {
        throw Error(path + ": error: cannot read scene file: " + std::strerror(e.errorNumber()));
    }
    Scene scene = parseSdl(text, path, options, warnings);
    scene.path = path;
    return scene;
}

}  // namespace vkray
