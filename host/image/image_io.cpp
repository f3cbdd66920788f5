#include "image/image_io.h"

#include "image/exr_io.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>

#include "util/error.h"
#include "util/files.h"

namespace vkray {

namespace {

namespace fs = std::filesystem;

// Larger sides are certainly a corrupt header; refusing them early gives a
// clear message instead of a size computation that overflows or a huge allocation.
constexpr long kMaxPfmSide = kMaxImageSide;

// The message for an image whose header asks for more pixels than vkray reads.
std::string tooManyPixels(const std::string& path, long long width, long long height) {
    return path + ": the image is " + std::to_string(width) + "x" + std::to_string(height) +
           ", above vkray's limit of " + std::to_string(kMaxImagePixels) + " pixels (" +
           std::to_string(kMaxImageSide) + " per side)";
}

// ".PNG" -> ".png"; empty when the path has no extension.
std::string lowerExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

enum class Format { Png, Pfm, Exr, Bmp };

// What vkray writes (.png, .pfm, .exr), or with `reading` also what it reads
// (.bmp: Hill's pixmaps).
Format formatOf(const std::string& path, bool reading) {
    const std::string ext = lowerExtension(path);
    if (ext == ".png") return Format::Png;
    if (ext == ".pfm") return Format::Pfm;
    if (ext == ".exr") return Format::Exr;
    if (ext == ".bmp" && reading) return Format::Bmp;
    throw Error(path + ": unsupported image format '" + ext + "' (use .png, .pfm or .exr" +
                (reading ? ", or .bmp to read)" : ")"));
}

// An EXR's colour: R, G, B, else Y (what writeImage writes for 1 channel).
Image decodeExrImage(const std::string& path, const std::string& bytes) {
    const std::vector<std::string> names = exrChannelNames(bytes, path);
    const auto has = [&](const char* name) {
        return std::find(names.begin(), names.end(), name) != names.end();
    };
    std::vector<std::string> wanted{"R", "G", "B"};
    if (!(has("R") && has("G") && has("B")) && has("Y")) wanted = {"Y"};
    const ExrImage exr = decodeExr(bytes, path, wanted);
    Image image{exr.width, exr.height, int(wanted.size()), {}};
    image.pixels.resize(size_t(exr.width) * size_t(exr.height) * wanted.size());
    for (size_t c = 0; c < wanted.size(); ++c)
        for (size_t i = 0; i < exr.channels[c].values.size(); ++i)
            image.pixels[i * wanted.size() + c] = exr.channels[c].values[i];
    return image;
}

void requireWritable(const std::string& path, const Image& image) {
    const bool sizeOk =
        image.width > 0 && image.height > 0 && (image.channels == 1 || image.channels == 3) &&
        image.pixels.size() == size_t(image.width) * size_t(image.height) * size_t(image.channels);
    if (!sizeOk)
        throw Error("cannot write " + path + ": the image is " + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + " with " + std::to_string(image.channels) +
                    " channel(s) and " + std::to_string(image.pixels.size()) +
                    " values; only non-empty 1- or 3-channel images with matching data can be "
                    "written");
}

// ---- PNG -------------------------------------------------------------------

unsigned char toByte(float v) {
    if (std::isnan(v)) return 0;
    return static_cast<unsigned char>(std::lround(double(std::clamp(v, 0.0f, 1.0f)) * 255.0));
}

void appendToString(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

std::string encodePng(const std::string& path, const Image& image) {
    std::vector<unsigned char> bytes(image.pixels.size());
    std::transform(image.pixels.begin(), image.pixels.end(), bytes.begin(), toByte);
    std::string png;
    if (!stbi_write_png_to_func(appendToString, &png, image.width, image.height, image.channels,
                                bytes.data(), image.width * image.channels))
        throw Error("cannot write " + path + ": PNG encoding failed");
    return png;
}

std::uint32_t bigEndian32(const std::string& bytes, size_t at) {
    const auto byte = [&](size_t i) { return std::uint32_t(std::uint8_t(bytes[at + i])); };
    return byte(0) << 24 | byte(1) << 16 | byte(2) << 8 | byte(3);
}

// Walks the PNG's chunks before stb does, for two things fuzzing found
// (fuzz/image_fuzz.cpp; tests/image/image_decode_test.cpp):
// - a chunk whose length runs past the end of the file is refused here: stb
//   would first allocate that length (up to 4 GB, for a 70-byte file);
// - stb_image 2.27 copies a first IDAT chunk of length 0 through a null
//   pointer (memcpy(NULL, p, 0): undefined behaviour). Such chunks carry no
//   data, so they are dropped.
// Bytes that do not start like a PNG come back as they are (stb says what is
// wrong); chunks after IEND are not looked at (decoders ignore them).
// `idatBytes` gets the IDAT chunks' data length in all.
std::string checkedPngChunks(const std::string& path, const std::string& bytes,
                             std::uint64_t& idatBytes) {
    constexpr size_t kSignature = 8, kLengthAndType = 8, kCrc = 4;
    idatBytes = 0;
    if (bytes.compare(0, kSignature, "\x89PNG\r\n\x1a\n") != 0) return bytes;
    std::vector<size_t> emptyIdat;
    for (size_t at = kSignature; at + kLengthAndType <= bytes.size();) {
        const size_t length = bigEndian32(bytes, at);
        std::string type = bytes.substr(at + 4, 4);
        const size_t left = bytes.size() - at - kLengthAndType;  // data and CRC must fit
        if (length > left || left - length < kCrc) {
            for (char& c : type)
                if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
            throw Error(path + ": corrupt PNG: the '" + type + "' chunk at byte " +
                        std::to_string(at) + " runs past the end of the file (it claims " +
                        std::to_string(length) + " bytes of data; " + std::to_string(left) +
                        " bytes are left)");
        }
        if (type == "IEND") break;
        if (length == 0 && type == "IDAT") emptyIdat.push_back(at);
        if (type == "IDAT") idatBytes += length;
        at += kLengthAndType + length + kCrc;
    }
    if (emptyIdat.empty()) return bytes;
    std::string kept;
    kept.reserve(bytes.size());
    size_t from = 0;
    for (const size_t chunk : emptyIdat) {
        kept.append(bytes, from, chunk - from);
        from = chunk + kLengthAndType + kCrc;
    }
    kept.append(bytes, from, std::string::npos);
    return kept;
}

// PNG or BMP bytes (already checked to start like one) through stb, as 3
// channels in [0, 1]. `pngIdatBytes`: a PNG's compressed data length.
Image decodeWithStb(const std::string& path, const std::string& bytes, const char* what,
                    std::optional<std::uint64_t> pngIdatBytes = std::nullopt) {
    if (bytes.size() > size_t(INT32_MAX))
        throw Error(path + ": " + what + " file is too large");
    // stb allocates the whole image before it finds out that the data is
    // missing: check the size the header claims first.
    int claimedWidth = 0, claimedHeight = 0, claimedChannels = 0;
    if (stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()),
                              &claimedWidth, &claimedHeight, &claimedChannels) &&
        (std::abs(claimedWidth) > kMaxImageSide || std::abs(claimedHeight) > kMaxImageSide ||
         std::abs((long long)claimedWidth * claimedHeight) > kMaxImagePixels))
        // (stb's BMP info gives a top-down file's height as it is stored: negative)
        throw Error(tooManyPixels(path, std::abs(claimedWidth), std::abs(claimedHeight)));
    // Found by fuzz/image_fuzz.cpp: an 80-byte PNG claiming 8451x7426 pixels
    // made stb allocate 188 MB before finding the data missing (a timeout under
    // ASan). Every pixel takes at least one bit, and deflate packs at most 1032
    // bytes into one: data that cannot hold the image is refused first.
    if (pngIdatBytes && claimedWidth > 0 && claimedHeight > 0) {
        const std::uint64_t leastRaw = (std::uint64_t(claimedWidth) * std::uint64_t(claimedHeight) + 7) / 8;
        constexpr std::uint64_t kDeflateMaxRatio = 1032;
        if (*pngIdatBytes * kDeflateMaxRatio < leastRaw)
            throw Error(path + ": not a readable PNG file (its " + std::to_string(claimedWidth) +
                        "x" + std::to_string(claimedHeight) + " pixels need at least " +
                        std::to_string((leastRaw + kDeflateMaxRatio - 1) / kDeflateMaxRatio) +
                        " bytes of compressed data; its IDAT chunks hold " +
                        std::to_string(*pngIdatBytes) + ")");
    }
    Image image;
    int fileChannels = 0;
    stbi_uc* data =
        stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()),
                              &image.width, &image.height, &fileChannels, 3);
    if (!data)
        throw Error(path + ": not a readable " + what + " file (" +
                    std::string(stbi_failure_reason()) + ")");
    if (image.width <= 0 || image.height <= 0) {
        // stb's BMP decoder accepts a 0 x 0 header (fuzz/image_fuzz.cpp found it).
        stbi_image_free(data);
        throw Error(path + ": not a readable " + what + " file (it has no pixels: " +
                    std::to_string(image.width) + "x" + std::to_string(image.height) + ")");
    }
    image.channels = 3;  // forced above, whatever the file holds
    const size_t count = size_t(image.width) * size_t(image.height) * 3;
    image.pixels.resize(count);
    for (size_t i = 0; i < count; ++i) image.pixels[i] = float(data[i]) / 255.0f;
    stbi_image_free(data);
    return image;
}

// stb tries every decoder it has on any bytes: each format checks its own
// signature first, so that a .png is only ever read by the PNG decoder.
Image decodePng(const std::string& path, const std::string& fileBytes) {
    if (fileBytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0)
        throw Error(path + ": not a readable PNG file (no PNG signature)");
    std::uint64_t idatBytes = 0;
    const std::string bytes = checkedPngChunks(path, fileBytes, idatBytes);
    return decodeWithStb(path, bytes, "PNG", idatBytes);
}

std::uint32_t littleEndianAt(const std::string& bytes, size_t at, int count) {
    std::uint32_t v = 0;
    for (int i = count - 1; i >= 0; --i) v = v << 8 | std::uint8_t(bytes[at + size_t(i)]);
    return v;
}

// stb reads zeros past the end of a BMP instead of failing: a truncated file
// would come back black. The pixel rows an uncompressed header promises must
// be there. (stb refuses the RLE forms itself.)
void checkBmpHeader(const std::string& path, const std::string& bytes) {
    const auto cutShort = [&] {
        return Error(path + ": truncated BMP: the file ends inside its header (" +
                     std::to_string(bytes.size()) + " bytes)");
    };
    if (bytes.size() < 18) throw cutShort();
    const std::uint32_t offset = littleEndianAt(bytes, 10, 4);
    const std::uint32_t headerSize = littleEndianAt(bytes, 14, 4);
    long long width = 0, height = 0, bitsPerPixel = 0, compression = 0;
    if (headerSize == 12) {  // OS/2 BITMAPCOREHEADER
        if (bytes.size() < 14 + 12) throw cutShort();
        width = littleEndianAt(bytes, 18, 2);
        height = littleEndianAt(bytes, 20, 2);
        bitsPerPixel = littleEndianAt(bytes, 24, 2);
        // stb_image 2.27 miscounts these palettes and decodes all black.
        if (bitsPerPixel < 16)
            throw Error(path + ": OS/2 BMP files with a palette are not supported (save it as a "
                               "Windows BMP or a PNG)");
    } else if (headerSize >= 40) {
        if (bytes.size() < 14 + 40) throw cutShort();
        width = std::int32_t(littleEndianAt(bytes, 18, 4));
        height = std::int32_t(littleEndianAt(bytes, 22, 4));
        bitsPerPixel = littleEndianAt(bytes, 28, 2);
        compression = littleEndianAt(bytes, 30, 4);
    } else {
        return;
    }
    // stb takes any other code but the RLE ones (1, 2) for uncompressed rows.
    if (compression != 0 && compression != 3)  // 3: bit fields, the same row layout
        throw Error(path + ": BMP compression " + std::to_string(compression) +
                    " is not supported (only uncompressed BMP files are read)");
    height = height < 0 ? -height : height;             // negative: rows top-down
    if (width <= 0 || width > kMaxImageSide || height > kMaxImageSide ||
        width * height > kMaxImagePixels)
        return;  // stb or the size limits say what is wrong
    const long long rowBytes = (width * bitsPerPixel + 31) / 32 * 4;
    const long long needed = (long long)offset + rowBytes * height;
    if ((long long)bytes.size() < needed)
        throw Error(path + ": truncated BMP: a " + std::to_string(width) + "x" +
                    std::to_string(height) + " image of " + std::to_string(bitsPerPixel) +
                    " bits per pixel needs " + std::to_string(needed) + " bytes, the file has " +
                    std::to_string(bytes.size()));
}

Image decodeBmp(const std::string& path, const std::string& bytes) {
    if (bytes.compare(0, 2, "BM") != 0)
        throw Error(path + ": not a readable BMP file (no 'BM' signature)");
    checkBmpHeader(path, bytes);
    return decodeWithStb(path, bytes, "BMP");
}

// ---- PFM -------------------------------------------------------------------

void appendLittleEndian(std::string& out, float v) {
    const auto bits = std::bit_cast<std::uint32_t>(v);
    for (int shift = 0; shift < 32; shift += 8) out.push_back(char((bits >> shift) & 0xffu));
}

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

}  // namespace

unsigned char pngByte(float value) { return toByte(value); }

Image colorImage(const Frame& frame) {
    Image image{frame.width, frame.height, 3, {}};
    image.pixels.reserve(frame.pixelCount() * 3);
    for (size_t i = 0; i < frame.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) image.pixels.push_back(frame.color.at(i)[c]);
    return image;
}

Image depthImage(const Frame& frame) {
    Image image{frame.width, frame.height, 1, {}};
    image.pixels.reserve(frame.pixelCount());
    for (size_t i = 0; i < frame.pixelCount(); ++i) image.pixels.push_back(frame.depth.at(i));
    return image;
}

Image normalImage(const Frame& frame) {
    Image image{frame.width, frame.height, 3, {}};
    image.pixels.reserve(frame.pixelCount() * 3);
    for (size_t i = 0; i < frame.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) image.pixels.push_back(frame.normal.at(i)[c]);
    return image;
}

Image idImage(const Frame& frame) {
    Image image{frame.width, frame.height, 1, {}};
    image.pixels.reserve(frame.pixelCount());
    // Object indices stay exact as floats up to 2^24, far beyond any scene.
    for (size_t i = 0; i < frame.pixelCount(); ++i) image.pixels.push_back(float(frame.id.at(i)));
    return image;
}

std::string pngBytes(const Image& image) {
    requireWritable("a PNG image", image);
    return encodePng("a PNG image", image);
}

void writeImage(const std::string& path, const Image& image) {
    StagedFiles files;
    stageImage(files, path, image);
    files.commit();
}

Image decodeImage(const std::string& bytes, const std::string& path) {
    switch (formatOf(path, true)) {
    case Format::Png: return decodePng(path, bytes);
    case Format::Bmp: return decodeBmp(path, bytes);
    case Format::Exr:
        return decodeExrImage(path, bytes);
    default: return decodePfm(path, bytes);
    }
}

Image readIds(const std::string& path) {
    if (formatOf(path, true) != Format::Exr) return readImage(path);
    const ExrImage exr = decodeExr(readFile(path), path, {kExrIdChannel});
    return Image{exr.width, exr.height, 1, exr.channels.front().values};
}

bool hasIdChannel(const std::string& path) {
    if (!isExrPath(path)) return false;
    const std::vector<std::string> names = exrChannelNames(readFile(path), path);
    return std::find(names.begin(), names.end(), kExrIdChannel) != names.end();
}

bool isExrPath(const std::string& path) {
    return lowerExtension(path) == ".exr";
}

Image readImage(const std::string& path) {
    formatOf(path, true);  // an unsupported extension is refused before the file is read
    return decodeImage(readFile(path), path);
}

void writeAovs(const std::string& target, const Frame& frame,
               const std::vector<glm::vec3>& hitPoints) {
    StagedFiles files;
    stageAovs(files, target, frame, hitPoints);
    files.commit();
}

std::string aovFilesText(const std::string& target) {
    if (isExrPath(target)) return target + " (R, G, B, Z, N.X, N.Y, N.Z, id, P.X, P.Y, P.Z)";
    return target + ".depth.pfm, .normal.pfm, .id.pfm";
}

// ---- staged images ---------------------------------------------------------

void stageImage(StagedFiles& files, const std::string& path, const Image& image) {
    const Format format = formatOf(path, false);
    requireWritable(path, image);
    files.stage(path, format == Format::Png   ? encodePng(path, image)
                : format == Format::Exr ? encodeExr(exrFromImage(image), path)
                                        : encodePfm(image));
}

void stageAovs(StagedFiles& files, const std::string& target, const Frame& frame,
               const std::vector<glm::vec3>& hitPoints) {
    if (isExrPath(target)) {
        files.stage(target, encodeExr(aovExr(frame, hitPoints), target));
        return;
    }
    const std::string& prefix = target;
    stageImage(files, prefix + ".depth.pfm", depthImage(frame));
    stageImage(files, prefix + ".normal.pfm", normalImage(frame));
    stageImage(files, prefix + ".id.pfm", idImage(frame));
}

}  // namespace vkray
