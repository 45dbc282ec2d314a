// The .limn container (formats/limn.md): a header (magic, container version, total length) and
// a sequence of typed, versioned chunks, 8-byte aligned with zero padding. This layer knows
// nothing about payloads; each layer above owns the codec of its chunks. Readers skip unknown
// chunks and tools pass them through unchanged.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace limn {

// Four ASCII characters, stored little-endian so the bytes in the file read as the name.
struct FourCC {
    uint32_t value = 0;
    constexpr FourCC() = default;
    constexpr explicit FourCC(const char (&s)[5])
        : value(uint32_t(uint8_t(s[0])) | uint32_t(uint8_t(s[1])) << 8 |
                uint32_t(uint8_t(s[2])) << 16 | uint32_t(uint8_t(s[3])) << 24) {}
    static constexpr FourCC fromValue(uint32_t v) {
        FourCC f;
        f.value = v;
        return f;
    }
    std::string str() const;
    constexpr bool operator==(const FourCC&) const = default;
};

struct Chunk {
    FourCC type;
    uint32_t version = 1;
    std::vector<uint8_t> payload;
};

inline constexpr uint8_t kContainerMagic[8] = {'L', 'I', 'M', 'N', '\r', '\n', 0x1A, '\n'};
inline constexpr uint32_t kContainerVersion = 1;
inline constexpr size_t kContainerHeaderSize = 24;
inline constexpr size_t kChunkHeaderSize = 16;

class Container {
public:
    std::vector<Chunk> chunks; // in file order

    const Chunk* find(FourCC type) const;
    Chunk* find(FourCC type);
    bool has(FourCC type) const { return find(type) != nullptr; }
    // Replaces the chunk of the same type in place, or appends it.
    void set(Chunk chunk);
    void remove(FourCC type);
};

// True when the bytes start with the container magic (for format sniffing on stdin).
bool looksLikeContainer(std::span<const uint8_t> bytes);
// True when the file exists and starts with the container magic (false for stdin).
bool isContainerFile(const std::string& path);

// Parses and validates the framing (formats/limn.md, "Validity"). Throws Error(BadInput).
Container parseContainer(std::span<const uint8_t> bytes);

std::vector<uint8_t> serializeContainer(const Container& container);

} // namespace limn

namespace limn {

// Reads and parses a container file (or stdin for "-"); errors name the file.
Container loadContainerFile(const std::string& path);

// Serializes and writes atomically (binary; refuses a terminal on stdout).
void saveContainerFile(const std::string& path, const Container& container);

// FNV-1a 64-bit hash, used by derived chunks to record which inputs they were built from.
uint64_t hashBytes(std::span<const uint8_t> bytes, uint64_t seed = 0xcbf29ce484222325ull);

} // namespace limn
