// The conventions every limn tool follows (docs/contributing.md, brief "Conventions"): --help on
// stdout listing every option with its default and the exit-code table, a one-line --version,
// exit codes, the error format, atomic outputs, --depfile, binary output refused on a terminal,
// -q/-v, and the same bytes from the same command.
#include "test_support.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include <set>
#include <sstream>

using namespace limn;

namespace {

struct Tool {
    std::string name;
    std::set<std::string> options; // every option the tool must list
};

const std::vector<Tool> kTools = {
    {"limn-classify",
     {"-o", "--output", "--depfile", "-q", "--quiet", "-v", "--verbose", "-h", "--help",
      "--version", "--boundary", "--fvar", "--quads", "--quad-face-angle", "--quad-shape-angle"}},
    {"limn-info", {"-q", "--quiet", "-v", "--verbose", "-h", "--help", "--version", "--json"}},
    {"limn-examples",
     {"-o", "--output", "--only", "--list", "--list-sequences", "-q", "--quiet", "-v", "--verbose", "-h", "--help",
      "--version"}},
};

std::string bin(const std::string& tool) {
    return test::tool(tool).string();
}

const std::string kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

TEST(Cli, HelpListsEveryOptionWithDefaultAndTheExitCodes) {
    for (const auto& t : kTools) {
        SCOPED_TRACE(t.name);
        for (const char* flag : {"--help", "-h"}) {
            auto r = test::run({bin(t.name), flag});
            EXPECT_EQ(r.exitCode, 0);
            EXPECT_EQ(r.err, "");
            EXPECT_EQ(r.out.rfind("Usage: " + t.name + " ", 0), 0u) << r.out;
        }
        std::string help = test::run({bin(t.name), "--help"}).out;
        // Option lines: "  -x, --long METAVAR   text", the text possibly on the next line.
        std::istringstream in(help.substr(help.find("\nOptions:\n")));
        std::vector<std::string> lines;
        for (std::string l; std::getline(in, l);) lines.push_back(l);
        std::set<std::string> listed;
        for (size_t i = 0; i < lines.size(); ++i) {
            const std::string& line = lines[i];
            if (line.rfind("  -", 0) != 0 && line.rfind("      --", 0) != 0) continue;
            size_t start = line.find('-'), gap = line.find("  ", start);
            std::istringstream left(line.substr(start, gap - start));
            bool takesValue = false;
            for (std::string word; left >> word;) {
                if (word[0] == '-')
                    listed.insert(word.back() == ',' ? word.substr(0, word.size() - 1) : word);
                else
                    takesValue = true;
            }
            std::string text = gap == std::string::npos ? lines.at(i + 1) : line.substr(gap);
            if (takesValue) { // its default must be shown
                EXPECT_NE(text.find("[default: "), std::string::npos) << line;
            }
        }
        EXPECT_EQ(listed, t.options);
        for (const char* code : {"\nExit codes:\n", "\n  0  success\n", "\n  1  bad input",
                                 "\n  2  usage error\n", "\n  3  missing capability"})
            EXPECT_NE(help.find(code), std::string::npos) << code;
    }
}

TEST(Cli, VersionIsOneLine) {
    for (const auto& t : kTools) {
        auto r = test::run({bin(t.name), "--version"});
        EXPECT_EQ(r.exitCode, 0);
        EXPECT_EQ(r.err, "");
        // "limn-x 1.2.3\n": the name, a space and a dotted version, one line.
        ASSERT_EQ(r.out.rfind(t.name + " ", 0), 0u) << r.out;
        std::string version = r.out.substr(t.name.size() + 1);
        EXPECT_EQ(version.find_first_not_of("0123456789."), version.size() - 1) << r.out;
        EXPECT_EQ(std::count(version.begin(), version.end(), '.'), 2) << r.out;
        EXPECT_EQ(version.back(), '\n');
    }
}

TEST(Cli, UsageErrorsExitWith2) {
    for (const auto& t : kTools) {
        SCOPED_TRACE(t.name);
        auto r = test::run({bin(t.name), "--frobnicate"});
        EXPECT_EQ(r.exitCode, 2);
        EXPECT_EQ(r.out, "");
        EXPECT_EQ(r.err, t.name + ": error: unknown option '--frobnicate' (see --help)\n");
        EXPECT_EQ(test::run({bin(t.name), "-q=1"}).exitCode, 2);
    }
    auto value = test::run({bin("limn-classify"), "--boundary", "sideways"});
    EXPECT_EQ(value.exitCode, 2);
    EXPECT_NE(value.err.find("--boundary: 'sideways' is not one of none|edge|edge-corner"),
              std::string::npos)
        << value.err;
    auto missing = test::run({bin("limn-classify"), "-o"});
    EXPECT_EQ(missing.exitCode, 2);
    EXPECT_NE(missing.err.find("-o needs a value"), std::string::npos) << missing.err;
    auto extra = test::run({bin("limn-info"), "a.limn", "b.limn"});
    EXPECT_EQ(extra.exitCode, 2);
    EXPECT_NE(extra.err.find("unexpected argument 'b.limn'"), std::string::npos) << extra.err;
    // An empty value (an unset make variable) is an error, not standard input or output or no
    // depfile: in every form, for every tool that takes -o.
    for (const char* tool : {"limn-classify", "limn-tables", "limn-seams", "limn-render", "limn-loop", "limn-heightmap",
                             "limn-trim", "limn-blend"}) {
        SCOPED_TRACE(tool);
        for (std::vector<std::string> args : {std::vector<std::string>{"-o", ""}, {"--output="}, {"--depfile", ""}, {""}}) {
            args.insert(args.begin(), bin(tool));
            auto r = test::run(args, "");
            EXPECT_EQ(r.exitCode, 2) << args[1] << ": " << r.err;
            EXPECT_NE(r.err.find("empty"), std::string::npos) << r.err;
            EXPECT_EQ(r.out, "");
        }
    }
    auto info = test::run({bin("limn-info"), ""}, "");
    EXPECT_EQ(info.exitCode, 2) << info.err;
    EXPECT_NE(info.err.find("an empty argument where"), std::string::npos) << info.err;
}

TEST(Cli, MissingInputExitsWith1NamingTheFile) {
    test::ScratchDir dir;
    const std::string input = (dir / "no-such-mesh.obj").string();
    for (const std::string tool : {"limn-classify", "limn-info"}) {
        auto r = test::run({bin(tool), input});
        EXPECT_EQ(r.exitCode, 1);
        EXPECT_EQ(r.out, "");
        EXPECT_EQ(r.err, tool + ": error: " + input + ": cannot open: No such file or directory\n");
    }
    auto directory = test::run({bin("limn-info"), dir.path().string()});
    EXPECT_EQ(directory.exitCode, 1);
    EXPECT_NE(directory.err.find("is a directory"), std::string::npos) << directory.err;
    // Inputs are read whole: one over 4 GiB is refused by its size (a sparse file here, so the
    // test writes nothing), not read until memory runs out.
    const std::string huge = (dir / "huge.obj").string();
    test::writeFile(huge, "");
    std::filesystem::resize_file(huge, uint64_t(5) << 30);
    auto big = test::run({bin("limn-classify"), huge, "-o", (dir / "h.limn").string()});
    EXPECT_EQ(big.exitCode, 1);
    EXPECT_EQ(big.err, "limn-classify: error: " + huge + ": larger than 4 GiB, more than limn reads as one input\n");
    EXPECT_FALSE(std::filesystem::exists(dir / "h.limn"));
}

TEST(Cli, AFailureLeavesNoOutputAndKeepsAnOldOne) {
    test::ScratchDir dir;
    const std::string good = (dir / "good.obj").string(), bad = (dir / "bad.obj").string();
    const std::string out = (dir / "out.limn").string(), dep = (dir / "out.d").string();
    test::writeFile(good, kTriangleObj);
    test::writeFile(bad, kTriangleObj + "f 1 2 9\n");
    auto failed = test::run({bin("limn-classify"), bad, "-o", out, "--depfile", dep});
    EXPECT_EQ(failed.exitCode, 1);
    EXPECT_EQ(test::filesIn(dir.path()), (std::vector<std::string>{"bad.obj", "good.obj"}));
    auto missing = test::run({bin("limn-classify"), (dir / "nothing.obj").string(), "-o", out});
    EXPECT_EQ(missing.exitCode, 1);
    EXPECT_EQ(test::filesIn(dir.path()), (std::vector<std::string>{"bad.obj", "good.obj"}));

    ASSERT_EQ(test::run({bin("limn-classify"), good, "-o", out}).exitCode, 0);
    std::string before = test::readFile(out);
    EXPECT_EQ(test::run({bin("limn-classify"), bad, "-o", out}).exitCode, 1);
    EXPECT_EQ(test::readFile(out), before); // not truncated, not replaced
    EXPECT_EQ(test::filesIn(dir.path()), (std::vector<std::string>{"bad.obj", "good.obj", "out.limn"}));

    // An output directory that cannot be written: error, exit 1, nothing created.
    auto unwritable =
        test::run({bin("limn-classify"), good, "-o", (dir / "no/such/dir.limn").string()});
    EXPECT_EQ(unwritable.exitCode, 1);
    EXPECT_NE(unwritable.err.find("cannot create output"), std::string::npos) << unwritable.err;
}

TEST(Cli, DepfileIsAMakeRule) {
    test::ScratchDir dir;
    // Spaces and '$' are escaped as Make needs them.
    const std::string input = (dir / "my mesh$1.obj").string(), out = (dir / "out.limn").string();
    test::writeFile(input, kTriangleObj);
    auto r =
        test::run({bin("limn-classify"), input, "-o", out, "--depfile", (dir / "out.d").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::string escaped;
    for (char c : input) escaped += c == ' ' ? "\\ " : c == '$' ? "$$" : std::string(1, c);
    EXPECT_EQ(test::readFile(dir / "out.d"), out + ": " + escaped + "\n");
}

TEST(Cli, BinaryOutputIsRefusedOnATerminal) {
    if (!std::filesystem::exists("/usr/bin/script")) GTEST_SKIP() << "no script(1) for a pty";
    // A chroot without /dev/pts (a debootstrapped test machine) has no pseudo-terminals at all.
    const int pty = ::posix_openpt(O_RDWR | O_NOCTTY);
    const char* slave = pty >= 0 && ::grantpt(pty) == 0 && ::unlockpt(pty) == 0 ? ::ptsname(pty)
                                                                                 : nullptr;
    const int slaveFd = slave ? ::open(slave, O_RDWR | O_NOCTTY) : -1;
    if (slaveFd >= 0) ::close(slaveFd);
    if (pty >= 0) ::close(pty);
    if (slaveFd < 0) GTEST_SKIP() << "no pseudo-terminal can be opened (is /dev/pts mounted?)";
    test::ScratchDir dir;
    test::writeFile(dir / "t.obj", kTriangleObj);
    // script(1) runs the tool with a pseudo-terminal as stdout; -e passes its exit code on.
    auto r = test::run({"/usr/bin/script", "-qec",
                        bin("limn-classify") + " " + (dir / "t.obj").string(), "/dev/null"});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.out.find("limn-classify: error: refusing to write binary output to a terminal"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("LIMN"), std::string::npos); // no container bytes reached the terminal
    // Text output is fine on a terminal.
    auto text = test::run({"/usr/bin/script", "-qec",
                           bin("limn-info") + " " + (dir / "t.obj").string(), "/dev/null"});
    EXPECT_EQ(text.exitCode, 0);
    EXPECT_NE(text.out.find("vertices"), std::string::npos);
}

TEST(Cli, QuietAndVerbose) {
    test::ScratchDir dir;
    const std::string input = (dir / "warn.obj").string();
    test::writeFile(input, kTriangleObj + "frobnicate 1 2\n");
    auto normal = test::run({bin("limn-classify"), input, "-o", (dir / "a.limn").string()});
    EXPECT_EQ(normal.exitCode, 0);
    EXPECT_EQ(normal.err, "limn-classify: warning: " + input +
                              ": line 5: unknown statement 'frobnicate' ignored\n");
    auto quiet = test::run({bin("limn-classify"), "-q", input, "-o", (dir / "b.limn").string()});
    EXPECT_EQ(quiet.err, "");
    auto verbose =
        test::run({bin("limn-classify"), "-q", "-v", input, "-o", (dir / "c.limn").string()});
    EXPECT_NE(verbose.err.find("limn-classify: classified 3 vertices, 1 faces"), std::string::npos)
        << verbose.err;
    EXPECT_EQ(test::readFile(dir / "a.limn"), test::readFile(dir / "c.limn"));
}

TEST(Cli, SameCommandSameBytes) {
    for (const std::string model :
         {"quad/spot_control_mesh.obj", "osd/catmark/catmark_cubes_semisharp.obj",
          "gltf/BoxTextured/BoxTextured.glb", "osd/catmark/catmark_hole_test3.obj"}) {
        SCOPED_TRACE(model);
        const std::string path = test::modelPath(model).string();
        auto a = test::run({bin("limn-classify"), "-q", path});
        auto b = test::run({bin("limn-classify"), "-q", path});
        ASSERT_EQ(a.exitCode, 0) << a.err;
        EXPECT_EQ(a.out, b.out);
        // Standard input (format sniffed) gives the same container as the file.
        if (model.find(".obj") != std::string::npos) {
            EXPECT_EQ(test::run({bin("limn-classify"), "-q"}, test::readFile(path)).out, a.out);
        }
        auto j1 = test::run({bin("limn-info"), "--json"}, a.out);
        auto j2 = test::run({bin("limn-info"), "--json"}, b.out);
        ASSERT_EQ(j1.exitCode, 0) << j1.err;
        EXPECT_EQ(j1.out, j2.out);
        EXPECT_EQ(test::run({bin("limn-info")}, a.out).out,
                  test::run({bin("limn-info")}, b.out).out);
    }
}

} // namespace
