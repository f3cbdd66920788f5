// Results as they travel between ranks: numbers and strings appended to a
// byte string and read back in the same order, bit for bit (doubles too), so
// that a report gathered from several ranks holds exactly what one rank's
// would. Both ends are the same binary, so byte order needs no care.
#pragma once

#include "util/error.h"

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

namespace vkray::dist {

class ByteWriter {
public:
    template <typename T>
    requires std::is_arithmetic_v<T> ByteWriter& operator<<(T value) {
        bytes_.append(reinterpret_cast<const char*>(&value), sizeof value);
        return *this;
    }
    ByteWriter& operator<<(const std::string& text) {
        *this << std::uint64_t(text.size());
        bytes_ += text;
        return *this;
    }
    const std::string& bytes() const { return bytes_; }

private:
    std::string bytes_;
};

class ByteReader {
public:
    explicit ByteReader(const std::string& bytes) : bytes_(bytes) {}
    template <typename T>
    requires std::is_arithmetic_v<T> ByteReader& operator>>(T& value) {
        std::memcpy(&value, take(sizeof value), sizeof value);
        return *this;
    }
    ByteReader& operator>>(std::string& text) {
        std::uint64_t size = 0;
        *this >> size;
        text.assign(take(size), size);
        return *this;
    }
    bool atEnd() const { return at_ == bytes_.size(); }

private:
    const char* take(std::size_t count) {
        if (count > bytes_.size() - at_)
            throw Error("MPI: a result from another rank is cut short (" +
                        std::to_string(bytes_.size()) + " bytes)");
        at_ += count;
        return bytes_.data() + at_ - count;
    }
    const std::string& bytes_;
    std::size_t at_ = 0;
};

}  // namespace vkray::dist
