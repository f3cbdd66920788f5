#include "image/stb_codecs.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "util/error.h"

namespace vkray {

unsigned char pngByte(float v) {
    if (std::isnan(v)) return 0;
    return static_cast<unsigned char>(std::lround(double(std::clamp(v, 0.0f, 1.0f)) * 255.0));
}

namespace {

void appendToString(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

}  // namespace

std::string encodePng(const std::string& path, const Image& image) {
    std::vector<unsigned char> bytes(image.pixels.size());
    std::transform(image.pixels.begin(), image.pixels.end(), bytes.begin(), pngByte);
    return encodePng(path, image.width, image.height, image.channels, bytes);
}

std::string encodePng(const std::string& path, int width, int height, int channels,
                      const std::vector<unsigned char>& bytes) {
    std::string png;
    // Every row Paeth-filtered: a third faster than stb's trying all five
    // filters on each row, and no larger on rendered images (measured on a
    // 1920x1080 frame of castle.dat: 0.064 s against 0.094 s, 85 300 bytes
    // against 86 017).
    stbi_write_force_png_filter = 4;
    if (!stbi_write_png_to_func(appendToString, &png, width, height, channels, bytes.data(),
                                width * channels))
        throw Error("cannot write " + path + ": PNG encoding failed");
    return png;
}

namespace {

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
    if (bytes.size() > size_t(INT32_MAX)) throw Error(path + ": " + what + " file is too large");
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
        const std::uint64_t leastRaw =
            (std::uint64_t(claimedWidth) * std::uint64_t(claimedHeight) + 7) / 8;
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
}  // namespace

Image decodePng(const std::string& path, const std::string& fileBytes) {
    if (fileBytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0)
        throw Error(path + ": not a readable PNG file (no PNG signature)");
    std::uint64_t idatBytes = 0;
    const std::string bytes = checkedPngChunks(path, fileBytes, idatBytes);
    return decodeWithStb(path, bytes, "PNG", idatBytes);
}

namespace {

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
            throw Error(path +
                        ": OS/2 BMP files with a palette are not supported (save it as a "
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
    height = height < 0 ? -height : height;  // negative: rows top-down
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

}  // namespace

Image decodeBmp(const std::string& path, const std::string& bytes) {
    if (bytes.compare(0, 2, "BM") != 0)
        throw Error(path + ": not a readable BMP file (no 'BM' signature)");
    checkBmpHeader(path, bytes);
    return decodeWithStb(path, bytes, "BMP");
}

}  // namespace vkray
