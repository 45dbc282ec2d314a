#include "container/container.h"

#include "base/io.h"

#include <cstdio>

#include "base/bytes.h"
#include "base/error.h"

#include <algorithm>
#include <cstring>

namespace limn {

std::string FourCC::str() const {
    std::string s;
    for (int i = 0; i < 4; ++i) {
        char c = static_cast<char>((value >> (8 * i)) & 0xFF);
        if (c >= 0x20 && c < 0x7F) {
            s += c;
        } else {
            static const char* hex = "0123456789ABCDEF";
            s += "\\x";
            s += hex[(c >> 4) & 0xF];
            s += hex[c & 0xF];
        }
    }
    return s;
}

const Chunk* Container::find(FourCC type) const {
    for (const auto& c : chunks)
        if (c.type == type) return &c;
    return nullptr;
}

Chunk* Container::find(FourCC type) {
    for (auto& c : chunks)
        if (c.type == type) return &c;
    return nullptr;
}

void Container::set(Chunk chunk) {
    if (Chunk* existing = find(chunk.type))
        *existing = std::move(chunk);
    else
        chunks.push_back(std::move(chunk));
}

void Container::remove(FourCC type) {
    chunks.erase(std::remove_if(chunks.begin(), chunks.end(),
                                [&](const Chunk& c) { return c.type == type; }),
                 chunks.end());
}

bool looksLikeContainer(std::span<const uint8_t> bytes) {
    return bytes.size() >= 4 && std::memcmp(bytes.data(), kContainerMagic, 4) == 0;
}

bool isContainerFile(const std::string& path) {
    if (isStdio(path)) return false;
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return false;
    uint8_t head[16] = {};
    const size_t n = std::fread(head, 1, sizeof head, f);
    std::fclose(f);
    return looksLikeContainer({head, n});
}

static bool isTypeChar(uint8_t c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
}

Container parseContainer(std::span<const uint8_t> bytes) {
    ByteReader r(bytes, "container");
    if (bytes.size() < kContainerHeaderSize) {
        if (!looksLikeContainer(bytes))
            throwBadInput("not a .limn container (bad magic)");
        throwBadInput("truncated container: " + std::to_string(bytes.size()) +
                      " bytes, the header alone is 24");
    }
    auto magic = r.readBytes(8, "magic");
    if (std::memcmp(magic.data(), kContainerMagic, 8) != 0) {
        if (looksLikeContainer(bytes))
            throwBadInput("damaged container magic (was the file transferred in text mode?)");
        throwBadInput("not a .limn container (bad magic)");
    }
    uint32_t version = r.read<uint32_t>();
    if (version != kContainerVersion)
        throwBadInput("container version " + std::to_string(version) +
                      " is not supported (this limn reads version 1)");
    uint32_t flags = r.read<uint32_t>();
    if (flags != 0) throwBadInput("reserved header flags are not zero", "offset 12");
    uint64_t total = r.read<uint64_t>();
    if (total != bytes.size())
        throwBadInput("header says " + std::to_string(total) + " bytes but the file has " +
                      std::to_string(bytes.size()) + " (truncated or trailing data)");
    if (total % 8 != 0) throwBadInput("total length is not a multiple of 8", "offset 16");

    Container c;
    while (!r.atEnd()) {
        size_t at = r.offset();
        std::string where = "chunk at offset " + std::to_string(at);
        if (r.remaining() < kChunkHeaderSize)
            throwBadInput("truncated chunk header", where);
        uint32_t type = r.read<uint32_t>();
        for (int i = 0; i < 4; ++i)
            if (!isTypeChar(uint8_t(type >> (8 * i))))
                throwBadInput("chunk type is not four characters from [A-Za-z0-9_]", where);
        Chunk chunk;
        chunk.type = FourCC::fromValue(type);
        where = "chunk " + chunk.type.str() + " at offset " + std::to_string(at);
        chunk.version = r.read<uint32_t>();
        if (chunk.version == 0) throwBadInput("chunk version 0 is invalid", where);
        uint64_t length = r.read<uint64_t>();
        if (length > r.remaining())
            throwBadInput("payload length " + std::to_string(length) + " runs past the end (" +
                          std::to_string(r.remaining()) + " bytes left)",
                          where);
        auto payload = r.readBytes(length, "payload");
        chunk.payload.assign(payload.begin(), payload.end());
        uint64_t pad = (8 - length % 8) % 8;
        if (pad > r.remaining()) throwBadInput("missing padding after the payload", where);
        for (uint8_t b : r.readBytes(pad, "padding"))
            if (b != 0) throwBadInput("padding bytes are not zero", where);
        if (c.has(chunk.type)) throwBadInput("chunk type appears twice", where);
        c.chunks.push_back(std::move(chunk));
    }
    return c;
}

std::vector<uint8_t> serializeContainer(const Container& container) {
    ByteWriter w;
    size_t size = 24;
    for (const auto& chunk : container.chunks) size += 16 + (chunk.payload.size() + 7) / 8 * 8;
    w.reserve(size);
    w.writeArray(std::span<const uint8_t>(kContainerMagic, 8));
    w.write<uint32_t>(kContainerVersion);
    w.write<uint32_t>(0);
    w.write<uint64_t>(0); // total length, patched below
    for (const auto& chunk : container.chunks) {
        w.write<uint32_t>(chunk.type.value);
        w.write<uint32_t>(chunk.version);
        w.write<uint64_t>(chunk.payload.size());
        w.writeArray(chunk.payload);
        w.padTo(8);
    }
    auto bytes = w.take();
    uint64_t total = bytes.size();
    std::memcpy(bytes.data() + 16, &total, sizeof total);
    return bytes;
}

} // namespace limn

#include "base/io.h"

namespace limn {

Container loadContainerFile(const std::string& path) {
    auto bytes = readInput(path);
    try {
        return parseContainer(bytes);
    } catch (Error& e) {
        e.setFile(path);
        throw;
    }
}

void saveContainerFile(const std::string& path, const Container& container) {
    auto bytes = serializeContainer(container);
    writeOutput(path, bytes, OutputFile::Kind::Binary);
}

uint64_t hashBytes(std::span<const uint8_t> bytes, uint64_t seed) {
    uint64_t h = seed;
    for (uint8_t b : bytes) {
        h ^= b;
        h *= 0x100000001b3ull;
    }
    return h;
}

} // namespace limn
