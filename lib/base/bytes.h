// Little-endian binary reading and writing. ByteReader bounds-checks every read against the
// buffer and throws Error(BadInput) naming the offset, so a hostile count can never make a reader
// run off the end (formats/limn.md, "Validity").
#pragma once

#include "base/error.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

static_assert(std::endian::native == std::endian::little, "limn assumes a little-endian host");

namespace limn {

class ByteReader {
public:
    explicit ByteReader(std::span<const uint8_t> data, std::string context = {})
        : data_(data), context_(std::move(context)) {}

    size_t offset() const { return pos_; }
    size_t size() const { return data_.size(); }
    size_t remaining() const { return data_.size() - pos_; }
    bool atEnd() const { return pos_ == data_.size(); }

    template <class T>
    T read() {
        static_assert(std::is_trivially_copyable_v<T>);
        require(sizeof(T), "value");
        T value;
        std::memcpy(&value, data_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        return value;
    }

    // Reads `count` values into a vector after checking that count * sizeof(T) bytes remain,
    // without overflow and before allocating anything.
    template <class T>
    std::vector<T> readArray(uint64_t count, const char* what) {
        static_assert(std::is_trivially_copyable_v<T>);
        if (count > remaining() / sizeof(T)) fail(std::string(what) + ": " + std::to_string(count) +
                                                  " entries do not fit in the " +
                                                  std::to_string(remaining()) + " bytes left");
        std::vector<T> values(count);
        if (count) std::memcpy(values.data(), data_.data() + pos_, count * sizeof(T));
        pos_ += count * sizeof(T);
        return values;
    }

    std::span<const uint8_t> readBytes(uint64_t count, const char* what) {
        if (count > remaining()) fail(std::string(what) + ": needs " + std::to_string(count) +
                                      " bytes, " + std::to_string(remaining()) + " left");
        auto bytes = data_.subspan(pos_, count);
        pos_ += count;
        return bytes;
    }

    void skip(uint64_t count, const char* what) { (void)readBytes(count, what); }

    [[noreturn]] void fail(const std::string& message) const {
        std::string where = context_.empty() ? "" : context_ + " ";
        throwBadInput(message, where + "offset " + std::to_string(pos_));
    }

private:
    void require(size_t n, const char* what) {
        if (n > remaining())
            fail(std::string("truncated: ") + what + " needs " + std::to_string(n) + " bytes, " +
                 std::to_string(remaining()) + " left");
    }

    std::span<const uint8_t> data_;
    size_t pos_ = 0;
    std::string context_;
};

// Appends a value's bytes (host order, little-endian) to a byte vector: for encoders that build
// their output in a plain vector (PLY bodies, glTF buffers).
template <class T>
void appendRaw(std::vector<uint8_t>& out, const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const uint8_t*>(&value);
    out.insert(out.end(), p, p + sizeof(T));
}

class ByteWriter {
public:
    template <class T>
    void write(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        size_t at = grow(sizeof(T));
        std::memcpy(bytes_.data() + at, &value, sizeof(T));
    }
    template <class T>
    void writeArray(std::span<const T> values) {
        static_assert(std::is_trivially_copyable_v<T>);
        if (values.empty()) return;
        size_t at = grow(values.size_bytes());
        std::memcpy(bytes_.data() + at, values.data(), values.size_bytes());
    }
    template <class T>
    void writeArray(const std::vector<T>& values) {
        writeArray(std::span<const T>(values));
    }
    void padTo(size_t alignment) {
        while (bytes_.size() % alignment) bytes_.push_back(0);
    }
    size_t size() const { return bytes_.size(); }
    // Writers of large payloads reserve their size up front: growing by doubling copies and
    // zero-fills every byte again, and fresh pages are what a large encode spends its time on.
    void reserve(size_t n) { bytes_.reserve(n); }
    std::vector<uint8_t>& bytes() { return bytes_; }
    std::vector<uint8_t> take() { return std::move(bytes_); }

private:
    // Amortized growth: resize() alone would reallocate on every small write.
    size_t grow(size_t n) {
        size_t at = bytes_.size();
        if (at + n > bytes_.capacity()) bytes_.reserve(std::max(2 * bytes_.capacity(), at + n + 256));
        bytes_.resize(at + n);
        return at;
    }
    std::vector<uint8_t> bytes_;
};

} // namespace limn
