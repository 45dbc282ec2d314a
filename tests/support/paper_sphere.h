// The paper's demo sphere (paper 000's figures), generated for the tests and bench_render: a UV sphere of 16
// segments x 16 rings (242 vertices) of radius r at the origin, triangle fans at the valence-16
// poles, faces outward. Radius 1 is the view-adaptive benchmark's: from (0,12,22) at 1280x720 (35 degree field of
// view) it covers about 6,300 pixels.
#pragma once

#include "mesh/mesh.h"

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <span>

namespace limn::test {

inline Mesh paperSphere(double r) {
    Mesh m;
    const int S = 16, R = 16;
    m.positions.push_back({0, r, 0});
    for (int i = 1; i < R; ++i)
        for (int j = 0; j < S; ++j) {
            const double th = M_PI * i / R, ph = 2 * M_PI * j / S;
            m.positions.push_back({r * std::sin(th) * std::cos(ph), r * std::cos(th), -r * std::sin(th) * std::sin(ph)});
        }
    m.positions.push_back({0, -r, 0});
    auto idx = [&](int i, int j) { return uint32_t(1 + (i - 1) * S + (j % S)); };
    auto face = [&](std::initializer_list<uint32_t> v) { m.addFace(std::span<const uint32_t>(v.begin(), v.size())); };
    for (int j = 0; j < S; ++j) face({0, idx(1, j), idx(1, j + 1)});
    for (int i = 1; i + 1 < R; ++i)
        for (int j = 0; j < S; ++j) face({idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)});
    const uint32_t last = uint32_t(m.positions.size() - 1);
    for (int j = 0; j < S; ++j) face({idx(R - 1, j), last, idx(R - 1, j + 1)});
    return m;
}

} // namespace limn::test
