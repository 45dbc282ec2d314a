// A test model (under tests/data) and its feature-adaptive or uniform tables, built in process
// the way limn-classify | limn-tables builds them, for tests that drive lib/render directly.
#pragma once

#include "mesh/import.h"
#include "subdiv/tables.h"
#include "test_support.h"
#include "topology/features.h"

#include <string>

namespace limn::test {

struct ModelTables {
    Mesh mesh;
    Tables tables;
};

inline ModelTables buildModelTables(const std::string& model, int depth, bool uniform = false) {
    Warnings w;
    ModelTables b;
    b.mesh = importMeshFile(modelPath(model).string(), w);
    TablesOptions o;
    o.depth = depth;
    o.uniform = uniform;
    b.tables = buildTables(b.mesh, resolveSchemeOptions(b.mesh.tags, {}), o, w);
    return b;
}

} // namespace limn::test
