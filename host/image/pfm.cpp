#include "image/pfm.h"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <system_error>

#include "util/error.h"

namespace vkray {

namespace {

// Larger sides are certainly a corrupt header; refusing them early gives a
// clear message instead of a size computation that overflows or a huge allocation.
constexpr long kMaxPfmSide = kMaxImageSide;

void appendLittleEndian(std::string& out, float v) {
    const auto bits = std::bit_cast<std::uint32_t>(v);
    for (int shift = 0; shift < 32; shift += 8) out.push_back(char((bits >> shift) & 0xffu));
}

bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

// Reads the PFM header tokens: "PF"/"Pf", width, height and scale separated by
// whitespace, then exactly one whitespace character before the pixel data.
class PfmHeaderReader {
public:
    PfmHeaderReader(const std::string& path, const std::string& bytes)
        : path_(path), bytes_(bytes) {}

    std::string token(const char* what) {
        const size_t start = pos_;
        while (pos_ < bytes_.size() && !isSpace(bytes_[pos_])) ++pos_;
        if (pos_ == start) fail(std::string("missing ") + what);
        if (pos_ == bytes_.size()) fail(std::string("header ends after the ") + what);
        std::string text = bytes_.substr(start, pos_ - start);
        ++pos_;  // the single whitespace character that ends the token
        return text;
    }

    void skipSpace() {
        while (pos_ < bytes_.size() && isSpace(bytes_[pos_])) ++pos_;
    }

    long side(const char* what) {
        skipSpace();
        const std::string text = token(what);
        long value = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (ec != std::errc() || end != text.data() + text.size())
            fail(std::string("the ") + what + " '" + text + "' is not a whole number");
        if (value < 1 || value > kMaxPfmSide)
            fail(std::string("the ") + what + " " + text + " is outside 1.." +
                 std::to_string(kMaxPfmSide));
        return value;
    }

    double scale() {
        skipSpace();
        const std::string text = token("scale");
        double value = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (ec != std::errc() || end != text.data() + text.size() || value == 0 ||
            !std::isfinite(value))
            fail("the scale '" + text + "' is not a non-zero number");
        return value;
    }

    size_t position() const { return pos_; }

    [[noreturn]] void fail(const std::string& what) const {
        throw Error(path_ + ": bad PFM header: " + what);
    }

private:
    const std::string& path_;
    const std::string& bytes_;
    size_t pos_ = 0;
};

}  // namespace

std::string encodePfm(const Image& image) {
    char header[64];
    const int headerLength =
        std::snprintf(header, sizeof header, "%s\n%d %d\n-1.0\n", image.channels == 3 ? "PF" : "Pf",
                      image.width, image.height);
    std::string out(header, size_t(headerLength));
    out.reserve(out.size() + image.pixels.size() * 4);
    const size_t rowValues = size_t(image.width) * size_t(image.channels);
    // PFM stores the bottom row first.
    for (int y = image.height - 1; y >= 0; --y) {
        const float* row = image.pixels.data() + size_t(y) * rowValues;
        for (size_t i = 0; i < rowValues; ++i) appendLittleEndian(out, row[i]);
    }
    return out;
}

Image decodePfm(const std::string& path, const std::string& bytes) {
    PfmHeaderReader header(path, bytes);
    const std::string magic = header.token("'PF' or 'Pf' magic");
    if (magic != "PF" && magic != "Pf")
        header.fail("expected 'PF' (colour) or 'Pf' (grey) at the start, found '" +
                    magic.substr(0, 16) + "'");
    Image image;
    image.channels = magic == "PF" ? 3 : 1;
    image.width = int(header.side("width"));
    image.height = int(header.side("height"));
    // The scale's sign gives the byte order; its magnitude is a brightness hint
    // that readers conventionally ignore (values are stored as they are).
    const bool littleEndian = header.scale() < 0;
    if ((long long)image.width * image.height > kMaxImagePixels)
        throw Error(tooManyPixels(path, image.width, image.height));

    const size_t count = size_t(image.width) * size_t(image.height) * size_t(image.channels);
    const size_t expected = count * 4;
    const size_t found = bytes.size() - header.position();
    if (found != expected)
        throw Error(path + ": " + (found < expected ? "truncated PFM" : "PFM has trailing data") +
                    ": a " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                    (image.channels == 3 ? " colour" : " grey") + " image needs " +
                    std::to_string(expected) + " bytes of pixel data, the file has " +
                    std::to_string(found));

    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data() + header.position());
    image.pixels.resize(count);
    const size_t rowValues = size_t(image.width) * size_t(image.channels);
    for (size_t i = 0; i < count; ++i) {
        const unsigned char* b = data + i * 4;
        const std::uint32_t bits = littleEndian
                                       ? std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 |
                                             std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24
                                       : std::uint32_t(b[3]) | std::uint32_t(b[2]) << 8 |
                                             std::uint32_t(b[1]) << 16 | std::uint32_t(b[0]) << 24;
        // Stored row r (bottom first) is image row height - 1 - r (top first).
        const size_t storedRow = i / rowValues, column = i % rowValues;
        const size_t imageRow = size_t(image.height) - 1 - storedRow;
        image.pixels[imageRow * rowValues + column] = std::bit_cast<float>(bits);
    }
    return image;
}

}  // namespace vkray
