#include "scene/mesh_file.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <glm/common.hpp>
#include <limits>
#include <memory>
#include <optional>
#include <system_error>

#include "scene/scene.h"
#include "util/error.h"
#include "util/file_loc.h"
#include "util/files.h"

namespace vkray {

namespace {

bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

std::string quoted(std::string_view text) {
    // Long garbage (a binary file) is cut so the message stays one readable line.
    constexpr std::size_t kShown = 40;
    if (text.size() > kShown) return "'" + std::string(text.substr(0, kShown)) + "...'";
    return "'" + std::string(text) + "'";
}

// Splits a data file into whitespace-separated words, tracking line and
// column so every message can point at the word (or the end of the file).
class WordScanner {
public:
    struct Word {
        std::string_view text;
        int line = 0;
        int column = 0;
    };

    WordScanner(std::string_view text, const std::string& path)
        : text_(text), file_(std::make_shared<const std::string>(path)) {}

    std::optional<Word> next() {
        while (pos_ < text_.size() && isSpace(text_[pos_])) {
            if (text_[pos_] == '\n') {
                ++line_;
                lineStart_ = pos_ + 1;
            }
            ++pos_;
        }
        if (pos_ == text_.size()) return std::nullopt;
        const std::size_t start = pos_;
        while (pos_ < text_.size() && !isSpace(text_[pos_])) ++pos_;
        return Word{text_.substr(start, pos_ - start), line_, column(start)};
    }

    // The next word, or an error at the end of the file saying what was expected.
    Word require(const std::string& what) {
        std::optional<Word> word = next();
        if (!word) failAtEnd("the file ends where " + what + " should be");
        return *word;
    }

    std::size_t bytesLeft() const { return text_.size() - pos_; }

    [[noreturn]] void fail(const Word& word, const std::string& message) const {
        throw Error(
            formatDiagnostic(FileLoc{file_, word.line, word.column}, nullptr, "error", message));
    }

    [[noreturn]] void failAtEnd(const std::string& message) const {
        // The end of the file: after its last byte (scanning has reached it).
        throw Error(formatDiagnostic(FileLoc{file_, line_, column(text_.size())}, nullptr, "error",
                                     message));
    }

private:
    int column(std::size_t offset) const {
        // Columns past INT_MAX (one giant line) are clamped, not wrapped.
        return int(std::min<std::size_t>(offset - lineStart_ + 1, INT32_MAX));
    }

    std::string_view text_;
    std::shared_ptr<const std::string> file_;
    std::size_t pos_ = 0;
    std::size_t lineStart_ = 0;
    int line_ = 1;
};

using Word = WordScanner::Word;

// A whole number: an optional '-' and decimal digits, nothing else.
std::optional<long long> wholeNumber(std::string_view text) {
    long long value = 0;
    const char* const end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value);
    if (error != std::errc() || stop != end) return std::nullopt;
    return value;
}

// A count in a header: a whole number in 0..limit. `where` gets its word.
std::size_t readCount(WordScanner& scanner, const char* what, std::size_t limit,
                      Word* where = nullptr) {
    const Word word = scanner.require(std::string("the ") + what);
    if (where) *where = word;
    const std::optional<long long> value = wholeNumber(word.text);
    if (!value) {
        // Digits that do not fit a long long are still a count: just too large.
        const bool allDigits = std::all_of(word.text.begin(), word.text.end(),
                                           [](char c) { return c >= '0' && c <= '9'; });
        if (!allDigits)
            scanner.fail(word, std::string("expected the ") + what + " (a whole number), found " +
                                   quoted(word.text));
        scanner.fail(word, std::string("the ") + what + " " + quoted(word.text) +
                               " is above vkray's limit of " + std::to_string(limit));
    }
    if (*value < 0)
        scanner.fail(word, std::string("the ") + what + " " + quoted(word.text) + " is negative");
    if (std::uint64_t(*value) > limit)
        scanner.fail(word, std::string("the ") + what + " " + quoted(word.text) +
                               " is above vkray's limit of " + std::to_string(limit));
    return std::size_t(*value);
}

// A coordinate: what strtod reads (plus a leading '+'), finite, and within
// kMaxSceneMagnitude (the GPU's float). Values too small for a double read as
// 0 (or a subnormal), as strtod gives them.
double readReal(WordScanner& scanner, const std::string& what) {
    const Word word = scanner.require(what);
    std::string_view digits = word.text;
    if (digits.size() >= 2 && digits[0] == '+' && digits[1] != '-' && digits[1] != '+')
        digits.remove_prefix(1);
    double value = 0;
    const char* const end = digits.data() + digits.size();
    const auto [stop, error] = std::from_chars(digits.data(), end, value);
    if (error == std::errc::invalid_argument || stop != end)
        scanner.fail(word, "expected a number for " + what + ", found " + quoted(word.text));
    if (error == std::errc::result_out_of_range) {
        // from_chars leaves `value` alone on underflow as on overflow; strtod
        // tells them apart (the word is short: it was just read as a number).
        const std::string copy(digits);
        value = std::strtod(copy.c_str(), nullptr);
        if (std::isinf(value))
            scanner.fail(word,
                         "the number " + quoted(word.text) + " for " + what + " is out of range");
    }
    if (!std::isfinite(value))
        scanner.fail(word, "expected a finite number for " + what + ", found " + quoted(word.text));
    if (std::abs(value) > kMaxSceneMagnitude)
        scanner.fail(word, "the number " + quoted(word.text) + " for " + what +
                               " is beyond vkray's limit of 1e18 (the GPU computes in float)");
    return value;
}

glm::dvec3 readPoint3(WordScanner& scanner, const std::string& what) {
    const double x = readReal(scanner, what + " (x)");
    const double y = readReal(scanner, what + " (y)");
    const double z = readReal(scanner, what + " (z)");
    return {x, y, z};
}

std::string plural(std::size_t count, const char* one, const char* many) {
    return std::to_string(count) + " " + (count == 1 ? one : many);
}

// An index into an array of `size` entries (`one`, `many`: what they are).
int readIndex(WordScanner& scanner, const std::string& what, std::size_t size, const char* one,
              const char* many) {
    const Word word = scanner.require(what);
    const std::optional<long long> value = wholeNumber(word.text);
    if (!value)
        scanner.fail(word, "expected " + what + " (a whole number), found " + quoted(word.text));
    if (*value < 0 || std::uint64_t(*value) >= size) {
        const std::string range = size == 0 ? std::string("the mesh has no ") + many
                                            : "0.." + std::to_string(size - 1) + ": the mesh has " +
                                                  plural(size, one, many);
        scanner.fail(word, what + " " + quoted(word.text) + " is out of range (" + range + ")");
    }
    return int(*value);
}

void requireEnd(WordScanner& scanner, const std::string& after) {
    if (const std::optional<Word> extra = scanner.next())
        scanner.fail(*extra, "unexpected " + quoted(extra->text) + " after " + after +
                                 " (does the header's count match the data?)");
}

std::string readDataFile(const std::string& path, const char* kind) {
    try {
        return readFile(path, kMaxDataFileBytes);
    } catch (const FileReadError& e) {
        if (e.errorNumber() != 0)
            throw Error(path + ": error: cannot read " + kind + ": " +
                        std::strerror(e.errorNumber()));
        if (e.size() != 0)
            throw Error(path + ": error: the " + kind + " is " + std::to_string(e.size()) +
                        " bytes, above vkray's limit of " + std::to_string(kMaxDataFileBytes));
        // a pipe or a growing file
        throw Error(path + ": error: the " + kind + " is larger than vkray's limit of " +
                    std::to_string(kMaxDataFileBytes) + " bytes");
    }
}

}  // namespace

// ---- 3VN ---------------------------------------------------------------------

PolygonMesh parse3vn(std::string_view text, const std::string& path) {
    WordScanner scanner(text, path);
    PolygonMesh mesh;
    mesh.path = path;

    Word header;
    const std::size_t vertexCount = readCount(scanner, "vertex count", kMaxMeshVertices, &header);
    const std::size_t normalCount = readCount(scanner, "normal count", kMaxMeshNormals);
    const std::size_t faceCount = readCount(scanner, "face count", kMaxMeshFaces);

    // Every number needs a byte and a separator before it: a header that asks
    // for more than the file can hold is refused before anything is allocated.
    const std::uint64_t minimumWords =
        3 * std::uint64_t(vertexCount) + 3 * std::uint64_t(normalCount) +
        7 * std::uint64_t(faceCount);  // a face is at least "3 a b c i j k"
    if (minimumWords * 2 > scanner.bytesLeft())
        scanner.fail(header, "the header promises " + plural(vertexCount, "vertex", "vertices") +
                                 ", " + plural(normalCount, "normal", "normals") + " and " +
                                 plural(faceCount, "face", "faces") + ", which need at least " +
                                 std::to_string(minimumWords * 2) + " bytes; the file has only " +
                                 std::to_string(scanner.bytesLeft()) +
                                 " after the header (truncated, or not a 3VN file)");

    mesh.vertices.reserve(vertexCount);
    for (std::size_t i = 0; i < vertexCount; ++i)
        mesh.vertices.push_back(readPoint3(scanner, "vertex " + std::to_string(i)));
    mesh.normals.reserve(normalCount);
    for (std::size_t i = 0; i < normalCount; ++i)
        mesh.normals.push_back(readPoint3(scanner, "normal " + std::to_string(i)));

    mesh.faces.reserve(faceCount);
    for (std::size_t f = 0; f < faceCount; ++f) {
        const std::string face = "face " + std::to_string(f);
        const Word countWord = scanner.require("the corner count of " + face);
        const std::optional<long long> corners = wholeNumber(countWord.text);
        if (!corners)
            scanner.fail(countWord, "expected the corner count of " + face +
                                        " (a whole number), found " + quoted(countWord.text));
        if (*corners < 3)
            scanner.fail(countWord, face + " has " + quoted(countWord.text) +
                                        " corners; a face needs at least 3");
        if (std::uint64_t(*corners) > kMaxMeshCorners - mesh.vertexIndices.size())
            scanner.fail(countWord, face + " with " + quoted(countWord.text) +
                                        " corners takes the mesh above vkray's limit of " +
                                        std::to_string(kMaxMeshCorners) + " corners in all");
        // Each corner needs two indices of two bytes each: checked before growing.
        if (std::uint64_t(*corners) * 4 > scanner.bytesLeft())
            scanner.fail(countWord, face + " has " + quoted(countWord.text) +
                                        " corners, more than the rest of the file can hold");
        PolygonMesh::Face record;
        record.firstCorner = mesh.vertexIndices.size();
        record.cornerCount = int(*corners);
        record.line = countWord.line;
        for (int k = 0; k < record.cornerCount; ++k)
            mesh.vertexIndices.push_back(readIndex(scanner, face + ": vertex index",
                                                   mesh.vertices.size(), "vertex", "vertices"));
        for (int k = 0; k < record.cornerCount; ++k)
            mesh.normalIndices.push_back(readIndex(scanner, face + ": normal index",
                                                   mesh.normals.size(), "normal", "normals"));
        mesh.faces.push_back(record);
    }
    requireEnd(scanner, "the last face (" + plural(faceCount, "face", "faces") + " in the header)");
    return mesh;
}

PolygonMesh load3vn(const std::string& path) {
    return parse3vn(readDataFile(path, "mesh file"), path);
}

std::size_t triangleCount(const PolygonMesh& mesh) {
    std::size_t count = 0;
    for (const PolygonMesh::Face& face : mesh.faces) count += std::size_t(face.cornerCount) - 2;
    return count;
}

std::vector<MeshTriangle> fanTriangles(const PolygonMesh& mesh) {
    std::vector<MeshTriangle> triangles;
    triangles.reserve(triangleCount(mesh));
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const PolygonMesh::Face& face = mesh.faces[f];
        const std::span<const int> v = mesh.vertexIndicesOf(face);
        const std::span<const int> n = mesh.normalIndicesOf(face);
        for (int k = 1; k + 1 < face.cornerCount; ++k)
            triangles.push_back(
                MeshTriangle{{v[0], v[k], v[k + 1]}, {n[0], n[k], n[k + 1]}, int(f)});
    }
    return triangles;
}

MeshBounds boundsOf(const PolygonMesh& mesh) {
    const double inf = std::numeric_limits<double>::infinity();
    MeshBounds bounds{glm::dvec3(inf), glm::dvec3(-inf)};
    for (const int index : mesh.vertexIndices) {
        const glm::dvec3& p = mesh.vertices[std::size_t(index)];
        bounds.lo = glm::min(bounds.lo, p);
        bounds.hi = glm::max(bounds.hi, p);
    }
    return bounds;
}

// ---- outlines -----------------------------------------------------------------

Outline parseOutline(std::string_view text, const std::string& path) {
    WordScanner scanner(text, path);
    Outline outline;
    outline.path = path;

    Word countWord;
    const std::size_t count = readCount(scanner, "point count", kMaxOutlinePoints, &countWord);
    if (count < 3)
        scanner.fail(countWord,
                     "an outline needs at least 3 points; the count is " + std::to_string(count));
    if (std::uint64_t(count) * 4 > scanner.bytesLeft())
        scanner.fail(countWord, "the count promises " + plural(count, "point", "points") +
                                    ", which need at least " + std::to_string(count * 4) +
                                    " bytes; the file has only " +
                                    std::to_string(scanner.bytesLeft()) + " after the count");

    outline.points.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        const std::string point = "point " + std::to_string(i);
        const double x = readReal(scanner, point + " (x)");
        const double y = readReal(scanner, point + " (y)");
        outline.points.emplace_back(x, y);
    }
    requireEnd(scanner, "the last point (" + plural(count, "point", "points") + " in the count)");
    return outline;
}

Outline loadOutline(const std::string& path) {
    return parseOutline(readDataFile(path, "outline file"), path);
}

}  // namespace vkray
