// formats/limn.md section 6: the single triangle and the 256 bytes limn-classify writes for it,
// pinned here for the container tests, in process and through the tool.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace limn::test::worked_example {

inline const char* const kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

// The 256 bytes of formats/limn.md section 6, one line per 16 bytes.
inline const char* const kTriangleHex = "4c494d4e0d0a1a0a0100000000000000"
                                        "00010000000000004d45534801000000"
                                        "68000000000000000300000001000000"
                                        "03000000000000000000000000000000"
                                        "00000000000000000000000000000000"
                                        "000000000000f03f0000000000000000"
                                        "00000000000000000000000000000000"
                                        "000000000000f03f0000000000000000"
                                        "03000000000000000100000002000000"
                                        "54414753010000001000000000000000"
                                        "ffffffff000000000000000000000000"
                                        "434c5346010000003c00000000000000"
                                        "01000005030000000100000003000000"
                                        "03000000000000000000000000000000"
                                        "02000000020000000200000049020000"
                                        "49020000490200001800000000000000";

inline std::vector<uint8_t> fromHex(const std::string& hex) {
    std::vector<uint8_t> out;
    for (size_t i = 0; i + 1 < hex.size(); i += 2)
        out.push_back(static_cast<uint8_t>(std::stoi(hex.substr(i, 2), nullptr, 16)));
    return out;
}

inline std::vector<uint8_t> pinned() {
    return fromHex(kTriangleHex);
}

} // namespace limn::test::worked_example
