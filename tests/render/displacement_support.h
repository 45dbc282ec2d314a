// Shared by the displacement tests: the pipeline as users run it (limn-classify | limn-tables |
// limn-seams, limn-heightmap, limn-render --mesh-out) and a generated all-islands mesh.
#pragma once

#include "drawn_ply.h"
#include "mesh/examples.h"
#include "mesh/obj.h"
#include "reference_mesh.h"
#include "test_support.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace limn::test::displacement {

inline std::string bin(const std::string& name) {
    return tool(name).string();
}

inline void runOk(const std::vector<std::string>& argv) {
    auto r = run(argv);
    ASSERT_EQ(r.exitCode, 0) << argv[0] << ": " << r.err;
}

// A quad sphere whose every face is its own UV island (every edge a UV seam), placed on an
// 8 x 8 atlas with a quarter-cell margin so a surface map's padding stays inside the cell.
inline std::string writeIslandSphere(const ScratchDir& dir) {
    Mesh m = makeQuadSphere(3);
    m.uvs.clear();
    m.uvIndices.clear();
    const double cell = 1.0 / 8, inset = cell / 4;
    for (size_t f = 0; f < m.faceCount(); ++f) {
        const double x = double(f % 8) * cell, y = double(f / 8) * cell;
        const glm::dvec2 corners[4] = {{x + inset, y + inset},
                                       {x + cell - inset, y + inset},
                                       {x + cell - inset, y + cell - inset},
                                       {x + inset, y + cell - inset}};
        for (uint32_t k = 0; k < 4; ++k) {
            m.uvIndices.push_back(static_cast<uint32_t>(m.uvs.size()));
            m.uvs.push_back(corners[k]);
        }
    }
    const std::string path = (dir / "islands.obj").string();
    writeFile(path, writeObj(m));
    return path;
}

struct Model {
    std::string name;
    std::string path; // empty: the generated island sphere
};

inline std::string modelFile(const Model& m, const ScratchDir& dir) {
    return m.path.empty() ? writeIslandSphere(dir) : modelPath(m.path).string();
}

// classify -> tables -> seams; returns the container.
inline std::string prepare(const std::string& obj, int depth, bool uniform, const ScratchDir& dir,
                           const std::string& stem) {
    const std::string limn = (dir / (stem + ".limn")).string();
    runOk({bin("limn-classify"), "-q", obj, "-o", limn});
    std::vector<std::string> tables = {bin("limn-tables"),   "-q", limn, "-o", limn, "--depth",
                                       std::to_string(depth)};
    if (uniform) tables.push_back("--uniform");
    runOk(tables);
    runOk({bin("limn-seams"), "-q", limn, "-o", limn});
    return limn;
}

inline std::string heightmap(const std::string& limn, const std::string& kind,
                             const ScratchDir& dir) {
    const std::string map = (dir / (kind + "_map.png")).string();
    runOk({bin("limn-heightmap"), limn, "--kind", kind, "--size", "128", "-o", map});
    return map;
}

inline double diagonalOf(const std::string& obj) {
    ReferenceObj ref = readReferenceObj(obj);
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& p : ref.positions) {
        lo = glm::min(lo, glm::dvec3(p[0], p[1], p[2]));
        hi = glm::max(hi, glm::dvec3(p[0], p[1], p[2]));
    }
    return glm::length(hi - lo);
}

// Renders with --mesh-out and returns the drawn triangles. `extra` holds --displace and friends.
inline Drawn drawn(const std::string& limn, const std::vector<std::string>& extra,
                   const ScratchDir& dir, int tess = 2) {
    const std::string ply = (dir / "drawn.ply").string();
    std::vector<std::string> argv = {
        bin("limn-render"),          limn,         "--size",     "8x8", "--tess",
        std::to_string(tess),        "--validate", "--mesh-out", ply,   "-o",
        (dir / "drawn.png").string(), "--edge-pixels", "0"}; // the fixed grids (as --displace)
    argv.insert(argv.end(), extra.begin(), extra.end());
    auto r = run(argv);
    if (r.exitCode != 0) throw std::runtime_error("limn-render: " + r.err);
    return parsePly(readFile(ply));
}

} // namespace limn::test::displacement
