// Helpers shared by limn-render's look tests (look_cli_test.cpp, gltf_material_cli_test.cpp):
// the tools from the build, limn-render with --validate, PNG read-back and containers made.
#pragma once

#include "image/srgb_image.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace limn::look_test {

using limn::test::RunResult;
using limn::test::ScratchDir;

constexpr const char* kKey = "1,0,1"; // magenta background: no lit grey surface is near it

inline std::string bin(const std::string& name) {
    return limn::test::tool(name).string();
}

inline RunResult limnRender(std::vector<std::string> args, const std::string& input = {}) {
    args.insert(args.begin(), bin("limn-render"));
    args.push_back("--validate");
    return limn::test::run(args, input);
}

inline Image readPng(const std::filesystem::path& path) {
    return decodePng(limn::test::readBytes(path));
}

// limn-classify MODEL [| limn-tables -d DEPTH] into DIR/NAME.limn.
inline std::string prepare(const ScratchDir& dir, const std::string& model, const std::string& name,
                    int depth) {
    const std::string out = (dir / (name + ".limn")).string();
    auto r = limn::test::run({bin("limn-classify"), model, "-q", "-o", out});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    if (depth >= 0) {
        r = limn::test::run({bin("limn-tables"), out, "-q", "-d", std::to_string(depth), "-o", out});
        EXPECT_EQ(r.exitCode, 0) << r.err;
    }
    return out;
}


} // namespace limn::look_test
