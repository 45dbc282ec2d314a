// What tables_test.cpp and irregular_surface_test.cpp share: a case (a model of tests/data, a
// depth, uniform or adaptive, a boundary rule), its tables built with the library's defaults and
// evaluated on the CPU, and the bounding-box diagonal errors are measured against.
#pragma once

#include "mesh/import.h"
#include "subdiv/evaluate.h"
#include "subdiv/tables.h"
#include "test_support.h"
#include "topology/features.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cctype>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace limn::test {

struct Case {
    std::string model;
    int depth;
    bool uniform;
    std::optional<BoundaryRule> boundary = {}; // overrides the mesh's tag (limn-classify --boundary)
};
inline void PrintTo(const Case& c, std::ostream* os) {
    *os << c.model << " depth " << c.depth << (c.uniform ? " uniform" : " adaptive");
    if (c.boundary) *os << " boundary rule " << int(*c.boundary);
}

inline std::string caseName(const ::testing::TestParamInfo<Case>& info) {
    std::string s = info.param.model;
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    static const char* rules[] = {"_bnone", "_bedge", "_bedgecorner"};
    return s + "_d" + std::to_string(info.param.depth) + (info.param.uniform ? "_uniform" : "") +
           (info.param.boundary ? rules[int(*info.param.boundary)] : "");
}

inline double diagonal(const Mesh& m) {
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& p : m.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return glm::length(hi - lo);
}

struct Fixture {
    Mesh mesh;
    SchemeOptions options;
    Tables tables;
    std::vector<glm::dvec3> vertices;
    double diag = 1;
};

// `bases`: boundary bases, interior bases with features on their rim and crease chains (the default), or
// none of them (more faces refined, and smooth faces below level N where those features decay).
inline Fixture build(const Case& c, bool bases = true) {
    Fixture f;
    Warnings w;
    f.mesh = importMeshFile(test::modelPath(c.model).string(), w);
    f.options = resolveSchemeOptions(f.mesh.tags, c.boundary);
    TablesOptions opts;
    opts.depth = c.depth;
    opts.uniform = c.uniform;
    opts.boundaryBases = opts.basisRimFeatures = opts.creaseChains = bases;
    f.tables = buildTables(f.mesh, f.options, opts, w);
    f.vertices = evaluateVertices(f.tables, f.mesh.positions);
    f.diag = diagonal(f.mesh);
    return f;
}

} // namespace limn::test
