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

#include "util/error.h"
#include "util/files.h"
#include "scene/sdl_lexer.h"

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

// A word as a message quotes it: bytes that are not printable ASCII (a NUL
// would end the message in a terminal; binary junk garbles it) as \xNN.
std::string inQuotes(const std::string& text) {
    std::string quoted = "'";
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte >= 0x20 && byte < 0x7f) {
            quoted += c;
        } else {
            static const char kHex[] = "0123456789abcdef";
            quoted += {'\\', 'x', kHex[byte >> 4], kHex[byte & 15]};
        }
    }
    return quoted + "'";
}

// The current transform: M (object -> world) and M^-1 kept beside it, each
// composed from exact inverses rather than by inverting M.
struct Transform {
    glm::dmat4 worldFromObject{1.0};
    glm::dmat4 objectFromWorld{1.0};
};

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
                const std::optional<Token> word = stream_.next();
                if (!word) break;
                if (std::optional<SceneObject> object = parseStatement(*word))
                    deliver(std::move(*object), *word);
            } catch (const Error& e) {
                // The same error again: the stream cannot go past it.
                if (!errors.empty() && errors.back() == e.what()) break;
                errors.push_back(e.what());
                if (errors.size() == kMaxReportedErrors) break;
                skipping = true;
            }
        }
        if (!openBooleans_.empty() && errors.size() < kMaxReportedErrors) {
            const Token& word = openBooleans_.back().word;
            errors.push_back(diagnosticAt(
                word, "error",
                inQuotes(word.text) + " needs two objects after it; the file ends before them"));
        }
        if (!errors.empty()) {
            std::string message = errors.front();
            for (std::size_t i = 1; i < errors.size(); ++i) message += "\n" + errors[i];
            throw Error(message);
        }
        return std::move(scene_);
    }

private:
    static constexpr std::size_t kMaxReportedErrors = 20;

    // After an error: drops the tokens up to the next word that starts a
    // statement (a keyword or a shape).
    void skipToNextStatement() {
        const auto& table = keywordTable();
        while (const Token* following = stream_.peek()) {
            if (table.count(following->text) != 0 || shapeFor(following->text)) return;
            stream_.next();
        }
    }

    // One statement starting at `word`; returns the object it made, if any.
    std::optional<SceneObject> parseStatement(const Token& word);
    void parseSetting(Keyword keyword, const Token& word);
    void parseCamera(const Token& word);
    SceneObject parseShape(ShapeType type, const Token& word);
    void deliver(SceneObject object, const Token& word);
    void skipUnknown(const Token& word);

    Token nextArgument(const Token& keyword, const char* what);
    double readNumber(const Token& keyword, Token* where = nullptr);
    glm::dvec3 readVec3(const Token& keyword);
    int readCount(const Token& keyword, const char* what);
    std::string readFileName(const Token& keyword);

    void applyTransform(const Token& word, const glm::dmat4& forward, const glm::dmat4& inverse);

    SdlTokenStream stream_;
    SdlOptions options_;
    std::vector<std::string>* warnings_;
    std::filesystem::path sceneFolder_;
    Scene scene_;
    Material material_;
    Transform current_;
    std::vector<Transform> saved_;  // push / pop
    // Booleans still waiting for their operands, innermost last. Kept here
    // rather than on the call stack so that `union union union ...` cannot
    // overflow it.
    struct OpenBoolean {
        SceneObject object;
        Token word;
    };
    std::vector<OpenBoolean> openBooleans_;
};

void SdlParser::applyTransform(const Token& word, const glm::dmat4& forward,
                               const glm::dmat4& inverse) {
    Transform next;
    next.worldFromObject = current_.worldFromObject * forward;  // M <- M * T
    next.objectFromWorld = inverse * current_.objectFromWorld;  // M^-1 <- T^-1 * M^-1
    // Both go to the renderers (M^-1 to the GPU in float): an entry beyond
    // kMaxSceneMagnitude (scale 1e-30: M^-1 holds 1e30) is refused here, at
    // the statement that made it, not rendered black.
    for (const glm::dmat4* matrix : {&next.worldFromObject, &next.objectFromWorld}) {
        for (int column = 0; column < 4; ++column) {
            for (int row = 0; row < 3; ++row) {
                const double entry = (*matrix)[column][row];
                if (std::abs(entry) <= kMaxSceneMagnitude) continue;
                char value[32];
                std::snprintf(value, sizeof value, "%.3g", entry);
                throwAt(word, inQuotes(word.text) + " makes the " +
                                  (matrix == &next.worldFromObject ? "transform" : "inverse transform") +
                                  " hold " + value + ", beyond vkray's limit of 1e18 (the GPU computes "
                                  "in float); use factors and offsets nearer 1 (e.g. scale the whole "
                                  "scene's units)");
            }
        }
    }
    current_ = next;
}

std::optional<SceneObject> SdlParser::parseStatement(const Token& word) {
    const auto& table = keywordTable();
    if (const auto keyword = table.find(word.text); keyword != table.end()) {
        parseSetting(keyword->second, word);
        return std::nullopt;
    }
    if (const std::optional<ShapeType> type = shapeFor(word.text)) return parseShape(*type, word);
    if (word.text == "}") throwAt(word, "'}' without a matching '{'");
    if (word.text == "{") throwAt(word, "'{' outside a def (only 'def NAME { ... }' has braces)");
    skipUnknown(word);
    return std::nullopt;
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
    while (const Token* following = stream_.peek()) {
        if (!isNumberToken(*following)) break;
        stream_.next();
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
            scene_.lights.push_back(light);
            break;
        }
        case Keyword::Background:
            scene_.background = readVec3(word);
            break;
        case Keyword::GlobalAmbient:
            scene_.globalAmbient = readVec3(word);
            break;
        case Keyword::MinReflectivity:
            scene_.minReflectivity = readNumber(word);
            break;
        case Keyword::MinTransparency:
            scene_.minTransparency = readNumber(word);
            break;
        case Keyword::MaxRecursionDepth: {
            Token where;
            const double depth = readNumber(word, &where);
            if (depth < 0 || depth > kMaxRecursionDepth || depth != std::floor(depth))
                throwAt(where, "'maxRecursionDepth' needs a whole number from 0 to " +
                                   std::to_string(kMaxRecursionDepth) + ", found " +
                                   inQuotes(where.text) +
                                   " (the GPU follows reflections and refractions with a "
                                   "stack of that depth)");
            scene_.maxRecursionDepth = int(depth);
            break;
        }

        case Keyword::Translate: {
            const glm::dvec3 d = readVec3(word);
            applyTransform(word, glm::translate(glm::dmat4(1.0), d),
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
            applyTransform(word, glm::rotate(glm::dmat4(1.0), radians, unitAxis),
                           glm::rotate(glm::dmat4(1.0), -radians, unitAxis));
            break;
        }
        case Keyword::Scale: {
            const glm::dvec3 s = readVec3(word);
            if (s.x == 0 || s.y == 0 || s.z == 0)
                throwAt(word, "scale factor 0 makes the transform singular");
            applyTransform(word, glm::scale(glm::dmat4(1.0), s),
                           glm::scale(glm::dmat4(1.0), 1.0 / s));
            break;
        }
        case Keyword::Push:
            saved_.push_back(current_);
            break;
        case Keyword::Pop:
            if (saved_.empty()) throwAt(word, "'pop' without a matching 'push'");
            current_ = saved_.back();
            saved_.pop_back();
            break;
        case Keyword::IdentityAffine:
            current_ = Transform{};
            break;

        case Keyword::Ambient:
            material_.ambient = readVec3(word);
            break;
        case Keyword::Diffuse:
            material_.diffuse = readVec3(word);
            break;
        case Keyword::Specular:
            material_.specular = readVec3(word);
            break;
        case Keyword::Emissive:
            material_.emissive = readVec3(word);
            break;
        case Keyword::SpecularExponent:
            material_.specularExponent = readNumber(word);
            break;
        case Keyword::Reflectivity:
            material_.reflectivity = readNumber(word);
            break;
        case Keyword::Transparency:
            material_.transparency = readNumber(word);
            break;
        case Keyword::SpeedOfLight:
            material_.speedOfLight = readNumber(word);
            break;
        case Keyword::SpecularFraction:
            material_.specularFraction = readNumber(word);
            break;
        case Keyword::SurfaceRoughness:
            material_.surfaceRoughness = readNumber(word);
            break;
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
                    warnings_->push_back(
                        diagnosticAt(word, "warning", message + "; drawn without a texture (as texture 0)"));
                code = 0;
            }
            material_.texture = int(code);
            material_.textureLoc = word.loc;
            break;
        }
        case Keyword::Parameters: {
            const int count = readCount(word, "a parameter count >= 0");
            std::vector<double> parameters;
            for (int i = 0; i < count; ++i) parameters.push_back(readNumber(word));
            material_.textureParameters = std::move(parameters);
            break;
        }
        case Keyword::DefaultMaterials:
            material_ = Material{};
            break;
        case Keyword::MakePixmap: {
            Pixmap pixmap;
            pixmap.index = readCount(word, "a pixmap number >= 0");
            pixmap.file = readFileName(word);
            pixmap.loc = word.loc;
            scene_.pixmaps.push_back(std::move(pixmap));
            break;
        }
        case Keyword::Camera:
            parseCamera(word);
            break;
    }
}

void SdlParser::parseCamera(const Token& word) {
    // Parts come in any order, each optional; the statement ends at the first
    // word that is not a part. A second `camera` changes only what it names.
    Camera camera = scene_.camera.value_or(Camera{});
    while (const Token* part = stream_.peek()) {
        const std::string name = part->text;
        if (name != "eye" && name != "look" && name != "up" && name != "fov") break;
        const Token partWord = *stream_.next();
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
    scene_.camera = camera;
}

SceneObject SdlParser::parseShape(ShapeType type, const Token& word) {
    SceneObject object;
    object.type = type;
    object.loc = word.loc;
    object.worldFromObject = current_.worldFromObject;
    object.objectFromWorld = current_.objectFromWorld;
    object.material = material_;
    switch (type) {
        case ShapeType::Cone:
            object.taper = 0;
            break;
        case ShapeType::TaperedCylinder:
            object.taper = readNumber(word);
            break;
        case ShapeType::Mesh:
        case ShapeType::Extrude:
            object.file = readFileName(word);
            break;
        default:
            break;
    }
    return object;
}

void SdlParser::deliver(SceneObject object, const Token& word) {
    // A boolean takes the next two objects made, whatever statements come
    // between them; a finished boolean is itself an object for the one around
    // it, or for the scene.
    if (isBoolean(object.type)) {
        // Every open boolean is one level of the tree it ends up in.
        if (openBooleans_.size() >= std::size_t(kMaxCsgDepth))
            throwAt(word, inQuotes(word.text) + " nests booleans " +
                              std::to_string(kMaxCsgDepth + 1) + " deep, beyond vkray's limit of " +
                              std::to_string(kMaxCsgDepth) +
                              "; combine the objects in a balanced tree, or in fewer booleans");
        openBooleans_.push_back(OpenBoolean{std::move(object), word});
        return;
    }
    while (!openBooleans_.empty()) {
        SceneObject& open = openBooleans_.back().object;
        open.operands.push_back(std::move(object));
        if (open.operands.size() < 2) return;
        object = std::move(open);
        openBooleans_.pop_back();
    }
    scene_.objects.push_back(std::move(object));
}

Token SdlParser::nextArgument(const Token& keyword, const char* what) {
    std::optional<Token> argument = stream_.next();
    if (!argument)
        throwAt(keyword, inQuotes(keyword.text) + " is missing " + what + " (end of file)");
    return std::move(*argument);
}

double SdlParser::readNumber(const Token& keyword, Token* where) {
    const Token argument = nextArgument(keyword, "a number");
    double value = 0;
    switch (parseSdlNumber(argument.text, value)) {
        case NumberStatus::Ok:
            break;
        case NumberStatus::Malformed:
            throwAt(argument, "expected a number after " + inQuotes(keyword.text) + ", found " +
                                  inQuotes(argument.text));
        case NumberStatus::NotFinite:
            throwAt(argument, "expected a finite number after " + inQuotes(keyword.text) +
                                  ", found " + inQuotes(argument.text));
        case NumberStatus::OutOfRange:
            throwAt(argument, "number " + inQuotes(argument.text) + " after " +
                                  inQuotes(keyword.text) + " is out of range");
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
