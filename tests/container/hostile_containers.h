// Hostile .limn containers (formats/limn.md section 4), built field by field: the damaged files
// that the readers in process and the tools must both refuse, and valid containers to cut.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace limn::test::hostile {

struct Case {
    std::string name;
    std::vector<uint8_t> bytes;
    std::string message;       // a substring of the error
    bool classifyReads = true; // false where only CLSF is bad: limn-classify replaces CLSF
};

// Every damaged container, with the message that refuses it.
std::vector<Case> cases();

// Valid containers to cut: the worked triangle, and a creased cube with UVs, every tag kind and
// an unknown chunk.
std::vector<std::vector<uint8_t>> validContainers();

// A container of these chunks, in this order, each of this version.
std::vector<uint8_t> frame(std::vector<std::pair<const char*, std::vector<uint8_t>>> chunks,
                           uint32_t version = 1);

// The worked example's triangle (section 6) as a MESH payload, with these corners.
std::vector<uint8_t> triangleMesh(std::vector<uint32_t> corners = {0, 1, 2});

} // namespace limn::test::hostile
