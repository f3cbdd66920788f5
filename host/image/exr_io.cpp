#include "image/exr_io.h"

#include "image/image_io.h"
#include "util/error.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <ImfVersion.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <stdexcept>

namespace vkray {

namespace {

// OpenEXR reads through this from the bytes already in memory (decodeImage's
// contract), never from the file again.
class MemoryInput final : public Imf::IStream {
public:
    MemoryInput(const std::string& bytes, const std::string& path)
        : Imf::IStream(path.c_str()), bytes_(bytes) {}

    bool read(char c[], int n) override {
        if (n < 0 || std::uint64_t(n) > bytes_.size() - std::min<std::uint64_t>(at_, bytes_.size()))
            throw std::runtime_error("the file ends early (truncated?)");
        std::memcpy(c, bytes_.data() + at_, size_t(n));
        at_ += std::uint64_t(n);
        return at_ < bytes_.size();
    }
    std::uint64_t tellg() override { return at_; }
    void seekg(std::uint64_t at) override { at_ = at; }

private:
    const std::string& bytes_;
    std::uint64_t at_ = 0;
};

std::string channelNames(const Imf::ChannelList& channels) {
    std::string names;
    for (auto c = channels.begin(); c != channels.end(); ++c)
        names += std::string(names.empty() ? "" : ", ") + c.name();
    return names.empty() ? "none" : names;
}

// OpenEXR sizes its buffers by the header before it reads a pixel: a line
// (or tile) of every channel, for as many lines as a chunk holds (up to
// 256). These bound what a damaged or hostile header can make it allocate;
// vkray writes 11 channels, production files rarely more than a few dozen.
constexpr long long kMaxExrChannels = 256;
constexpr long long kMaxExrValuesPerLine = 1 << 20;  // width x channels
constexpr int kMaxExrTileSide = 512;

// A header within image_io.h's size limits and the bounds above, or an Error.
void requireReadableHeader(const Imf::Header& header, const std::string& path) {
    const Imath::Box2i window = header.dataWindow();
    const long long width = (long long)window.max.x - window.min.x + 1;
    const long long height = (long long)window.max.y - window.min.y + 1;
    if (width < 1 || height < 1)
        throw Error(path + ": not a readable OpenEXR file (its data window is empty)");
    if (width > kMaxImageSide || height > kMaxImageSide || width * height > kMaxImagePixels)
        throw Error(path + ": the image is " + std::to_string(width) + "x" +
                    std::to_string(height) + ", above vkray's limit of " +
                    std::to_string(kMaxImagePixels) + " pixels (" + std::to_string(kMaxImageSide) +
                    " per side)");
    long long channels = 0;
    for (auto c = header.channels().begin(); c != header.channels().end(); ++c) ++channels;
    if (channels > kMaxExrChannels || width * channels > kMaxExrValuesPerLine)
        throw Error(path + ": the OpenEXR file has " + std::to_string(channels) + " channels of " +
                    std::to_string(width) + " pixels a line, above vkray's limit of " +
                    std::to_string(kMaxExrChannels) + " channels and " +
                    std::to_string(kMaxExrValuesPerLine) + " values a line");
}

// Opens the bytes as an OpenEXR file and hands it to `use`; OpenEXR's own
// exceptions come back as Error naming the path.
template <typename Use>
auto withExrFile(const std::string& bytes, const std::string& path, Use&& use) {
    // The signature first, so that no other bytes reach OpenEXR's parser.
    if (bytes.size() < 8 || !Imf::isImfMagic(bytes.data()))
        throw Error(path + ": not a readable OpenEXR file (no OpenEXR signature)");
    // Every part's sides and tiles are held to the limits by OpenEXR's own
    // check; the first part's header is read and checked in full before the
    // file is opened.
    static const bool limited = [] {
        Imf::Header::setMaxImageSize(int(kMaxImageSide), int(kMaxImageSide));
        Imf::Header::setMaxTileSize(kMaxExrTileSide, kMaxExrTileSide);
        return true;
    }();
    (void)limited;
    try {
        MemoryInput stream(bytes, path);
        stream.seekg(8);  // past the magic number and the version field
        Imf::Header first;
        int version = int(std::uint8_t(bytes[4])) | int(std::uint8_t(bytes[5])) << 8 |
                      int(std::uint8_t(bytes[6])) << 16 | int(std::uint8_t(bytes[7])) << 24;
        first.readFrom(stream, version);
        requireReadableHeader(first, path);
        stream.seekg(0);
        Imf::InputFile file(stream);
        return use(file);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(path + ": not a readable OpenEXR file (" + e.what() + ")");
    }
}

}  // namespace

const ExrChannel* ExrImage::find(const std::string& name) const {
    for (const ExrChannel& c : channels)
        if (c.name == name) return &c;
    return nullptr;
}

std::string encodeExr(const ExrImage& image, const std::string& path) {
    const size_t count = size_t(std::max(image.width, 0)) * size_t(std::max(image.height, 0));
    if (count == 0 || image.channels.empty())
        throw Error("cannot write " + path + ": the image is " + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + " with " +
                    std::to_string(image.channels.size()) + " channel(s); nothing to write");
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;  // lossless
    Imf::FrameBuffer frameBuffer;
    for (const ExrChannel& c : image.channels) {
        if (c.values.size() != count)
            throw Error("cannot write " + path + ": channel " + c.name + " holds " +
                        std::to_string(c.values.size()) + " values, the image " +
                        std::to_string(count) + " pixels");
        if (header.channels().findChannel(c.name))
            throw Error("cannot write " + path + ": two channels are named " + c.name);
        header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
        frameBuffer.insert(
            c.name, Imf::Slice(Imf::FLOAT,
                               const_cast<char*>(reinterpret_cast<const char*>(c.values.data())),
                               sizeof(float), sizeof(float) * size_t(image.width)));
    }
    try {
        Imf::StdOSStream stream;
        {
            Imf::OutputFile file(stream, header);
            file.setFrameBuffer(frameBuffer);
            file.writePixels(image.height);
        }  // the destructor writes the table of line offsets
        return stream.str();
    } catch (const std::exception& e) {
        throw Error("cannot write " + path + ": OpenEXR: " + e.what());
    }
}

std::vector<std::string> exrChannelNames(const std::string& bytes, const std::string& path) {
    return withExrFile(bytes, path, [](Imf::InputFile& file) {
        std::vector<std::string> names;
        for (auto c = file.header().channels().begin(); c != file.header().channels().end(); ++c)
            names.push_back(c.name());
        return names;
    });
}

ExrImage decodeExr(const std::string& bytes, const std::string& path,
                   const std::vector<std::string>& wanted) {
    return withExrFile(bytes, path, [&](Imf::InputFile& file) {
        const Imf::Header& header = file.header();
        const Imath::Box2i window = header.dataWindow();
        requireReadableHeader(header, path);
        const long long width = (long long)window.max.x - window.min.x + 1;
        const long long height = (long long)window.max.y - window.min.y + 1;
        std::vector<std::string> names = wanted;
        if (names.empty())
            for (auto c = header.channels().begin(); c != header.channels().end(); ++c)
                names.push_back(c.name());
        for (const std::string& name : names) {
            const Imf::Channel* channel = header.channels().findChannel(name);
            if (!channel)
                throw Error(path + ": the OpenEXR file has no channel " + name + " (it has " +
                            channelNames(header.channels()) + ")");
            if (channel->xSampling != 1 || channel->ySampling != 1)
                throw Error(path + ": channel " + name +
                            " is subsampled; vkray reads only full-resolution channels");
        }
        ExrImage image{int(width), int(height), {}};
        image.channels.reserve(names.size());  // the slices point into these
        Imf::FrameBuffer frameBuffer;
        for (const std::string& name : names) {
            image.channels.push_back({name, std::vector<float>(size_t(width) * size_t(height))});
            frameBuffer.insert(
                name, Imf::Slice::Make(Imf::FLOAT, image.channels.back().values.data(), window));
        }
        file.setFrameBuffer(frameBuffer);
        file.readPixels(window.min.y, window.max.y);
        return image;
    });
}

ExrImage exrFromImage(const Image& image) {
    ExrImage exr{image.width, image.height, {}};
    const std::vector<std::string> names = image.channels == 3
                                               ? std::vector<std::string>{"R", "G", "B"}
                                               : std::vector<std::string>{"Y"};
    const size_t count = size_t(image.width) * size_t(image.height);
    for (size_t c = 0; c < names.size(); ++c) {
        ExrChannel channel{names[c], std::vector<float>(count)};
        for (size_t i = 0; i < count; ++i)
            channel.values[i] = image.pixels.at(i * names.size() + c);
        exr.channels.push_back(std::move(channel));
    }
    return exr;
}

ExrImage aovExr(const Frame& frame, const std::vector<glm::vec3>& hitPoints) {
    const size_t count = frame.pixelCount();
    if (hitPoints.size() != count)
        throw Error("internal: " + std::to_string(hitPoints.size()) + " hit points for " +
                    std::to_string(count) + " pixels");
    ExrImage exr{frame.width, frame.height, {}};
    const auto add = [&](const std::string& name, auto value) {
        ExrChannel channel{name, std::vector<float>(count)};
        for (size_t i = 0; i < count; ++i) channel.values[i] = value(i);
        exr.channels.push_back(std::move(channel));
    };
    const char* const axes[] = {"X", "Y", "Z"};
    const char* const colours[] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) add(colours[c], [&](size_t i) { return frame.color.at(i)[c]; });
    add("Z", [&](size_t i) { return frame.depth.at(i); });
    for (int c = 0; c < 3; ++c)
        add(std::string("N.") + axes[c], [&](size_t i) { return frame.normal.at(i)[c]; });
    // Object indices stay exact as floats up to 2^24, far beyond any scene.
    add(kExrIdChannel, [&](size_t i) { return float(frame.id.at(i)); });
    for (int c = 0; c < 3; ++c)
        add(std::string("P.") + axes[c], [&](size_t i) { return hitPoints[i][c]; });
    return exr;
}

}  // namespace vkray
