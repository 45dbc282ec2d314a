// limn-tables on the command line: a mesh file or a classified container in, the same bytes as
// limn-classify | limn-tables, every run alike; bad input and a bad depth refused.
#include "test_support.h"

#include <gtest/gtest.h>

using namespace limn;

namespace {

// A mesh file is classified with the defaults first, exactly as limn-classify | limn-tables.
TEST(TablesTool, TakesAMeshOrAClassifiedContainer) {
    test::ScratchDir dir;
    auto r = test::run({test::tool("limn-tables").string(), "--depth", "2",
                        test::modelPath("quad/spot_control_mesh.obj").string(), "-o",
                        (dir / "out.limn").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    auto classified = test::run({test::tool("limn-classify").string(),
                                 test::modelPath("quad/spot_control_mesh.obj").string()});
    ASSERT_EQ(classified.exitCode, 0);
    auto tables = test::run({test::tool("limn-tables").string(), "--depth", "2"}, classified.out);
    ASSERT_EQ(tables.exitCode, 0) << tables.err;
    EXPECT_EQ(test::readFile(dir / "out.limn"), tables.out)
        << "a mesh input differs from limn-classify | limn-tables";
    auto garbage = test::run({test::tool("limn-tables").string(), "-"}, "not a mesh at all");
    EXPECT_EQ(garbage.exitCode, 1);
    EXPECT_NE(garbage.err.find("limn-tables: error: "), std::string::npos) << garbage.err;
    auto again = test::run({test::tool("limn-tables").string(), "--depth", "2"}, classified.out);
    EXPECT_EQ(tables.out, again.out) << "not deterministic";
    auto bad = test::run({test::tool("limn-tables").string(), "--depth", "99"}, classified.out);
    EXPECT_EQ(bad.exitCode, 2);
}

} // namespace
