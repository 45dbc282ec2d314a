// Side files and outputs that never lie, checked by running the tools:
// a run leaves all of its outputs or none (depfile included); a depfile never names an output or
// an input, and names what make can read or is refused; signals leave no temporary file; an
// overwritten output keeps its mode and its symbolic link; an output never destroys an input; a
// failed write to standard output is a failure; an option given twice is refused.
#include "test_support.h"

#include <gtest/gtest.h>

#include <csignal>
#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

using namespace limn;

extern char** environ;

namespace {

std::string bin(const std::string& tool) { return test::tool(tool).string(); }

const std::string kQuadObj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\n"
                             "v 0 1 1\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n"
                             "f 4 1 5 8\n";

bool anyTemporary(const std::filesystem::path& dir) {
    for (const auto& name : test::filesIn(dir))
        if (name.find("limn-tmp") != std::string::npos) return true;
    return false;
}

// A classified cube in `dir`: cube.obj and cube.limn.
std::string cubeContainer(const test::ScratchDir& dir) {
    test::writeFile(dir / "cube.obj", kQuadObj);
    const std::string limn = (dir / "cube.limn").string();
    auto r = test::run({bin("limn-classify"), (dir / "cube.obj").string(), "-o", limn});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return limn;
}

TEST(SideFiles, AnUnwritableDepfileLeavesNoOutput) {
    test::ScratchDir dir;
    const std::string cube = cubeContainer(dir), out = (dir / "t.limn").string();
    auto r = test::run({bin("limn-tables"), cube, "-o", out, "--depfile",
                        (dir / "nodir/t.d").string()});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("nodir/t.d"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << "the output was written although the run failed";
    EXPECT_FALSE(anyTemporary(dir.path()));
    // A depfile whose write fails late (/dev/full: ENOSPC on write, not on open), once for a
    // tool with one output and once for a sequence, whose frames are written as they are done.
    if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
    r = test::run({bin("limn-tables"), cube, "-o", out, "--depfile", "/dev/full"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << "the output was written although its depfile failed";
    r = test::run({bin("limn-render"), cube, "--size", "32x24", "--turntable", "2", "-o",
                   (dir / "tt_%d.png").string(), "--depfile", "/dev/full"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "tt_0.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "tt_1.png"));
    r = test::run({bin("limn-render"), cube, "--size", "32x24", "-o", (dir / "one.png").string(), "--depfile",
                   "/dev/full"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "one.png"));
    EXPECT_FALSE(anyTemporary(dir.path()));
}

TEST(SideFiles, ADepfileNamingAnOutputOrAnInputIsAUsageError) {
    test::ScratchDir dir;
    const std::string cube = cubeContainer(dir), before = test::readFile(cube);
    const std::string out = (dir / "x.limn").string();
    auto r = test::run({bin("limn-tables"), cube, "-o", out, "--depfile", out});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    r = test::run({bin("limn-tables"), cube, "-o", out, "--depfile", cube});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(test::readFile(cube), before) << "the input was overwritten by the depfile";
    // The same file under another name is the same file.
    r = test::run({bin("limn-tables"), cube, "-o", out, "--depfile",
                   (dir.path() / "." / "cube.limn").string()});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    // Relative names of a file not there yet: "x.limn" and "./x.limn" are the same output (the
    // depfile was once written over the output, exit 0).
    for (const auto& [o, d] : {std::pair<std::string, std::string>{"./x.limn", "x.limn"}, {"x.limn", "./x.limn"},
                               {"sub/../x.limn", "x.limn"}}) {
        std::filesystem::create_directories(dir / "sub");
        r = test::run({"/bin/sh", "-c",
                       "cd '" + dir.path().string() + "' && '" + bin("limn-tables") + "' cube.limn -o " + o +
                           " --depfile " + d});
        EXPECT_EQ(r.exitCode, 2) << o << " " << d << ": " << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << o << " " << d;
    }
    // limn-render: the image and the mesh output are both outputs.
    const std::string ply = (dir / "m.ply").string();
    r = test::run({bin("limn-render"), cube, "-o", (dir / "i.png").string(), "--mesh-out", ply,
                   "--depfile", ply});
    EXPECT_EQ(r.exitCode, 2) << r.err;
}

// GNU make reads the depfile back: the output is out of date exactly when the input is newer.
void expectMakeReads(const test::ScratchDir& dir, const std::string& inputName,
                     const std::string& outputName) {
    const std::string input = (dir / inputName).string(), output = (dir / outputName).string();
    test::writeFile(input, kQuadObj);
    auto r = test::run({bin("limn-classify"), input, "-o", output, "--depfile",
                        (dir / "deps.d").string()});
    ASSERT_EQ(r.exitCode, 0) << inputName << ": " << r.err;
    // The depfile's rule is the first, so the default goal; a match-anything rule gives it a
    // recipe, so that make -q can say whether it would run one.
    test::writeFile(dir / "Makefile", "include deps.d\n%:\n\t@:\n");
    auto q = test::run({"/usr/bin/make", "-q", "-C", dir.path().string()});
    EXPECT_EQ(q.exitCode, 0) << inputName << ": " << q.err << test::readFile(dir / "deps.d");
    std::filesystem::last_write_time(
        output, std::filesystem::last_write_time(input) - std::chrono::seconds(5));
    q = test::run({"/usr/bin/make", "-q", "-C", dir.path().string()});
    EXPECT_EQ(q.exitCode, 1) << inputName << ": make does not see the input\n"
                             << q.err << test::readFile(dir / "deps.d");
}

TEST(SideFiles, DepfileNamesAreWhatMakeReads) {
    if (!std::filesystem::exists("/usr/bin/make")) GTEST_FAIL() << "make is not installed";
    for (const char* name : {"plain.obj", "a b.obj", "a#b.obj", "a$b.obj", "a:b.obj",
                                   "a%b.obj", "a*b.obj", "a[1]b.obj", "a?b.obj"}) {
        test::ScratchDir dir;
        expectMakeReads(dir, name, "out.limn");
    }
    test::ScratchDir dir;
    expectMakeReads(dir, "in.obj", "out put:1.limn");
}

TEST(SideFiles, NamesMakeCannotReadAreRefusedBeforeAnyWork) {
    for (const char* name : {"a;b.obj", "a|b.obj", "a=b.obj", "a\tb.obj", "a\nb.obj"}) {
        test::ScratchDir dir;
        const std::string input = (dir / name).string();
        test::writeFile(input, kQuadObj);
        auto r = test::run({bin("limn-classify"), input, "-o", (dir / "out.limn").string(),
                            "--depfile", (dir / "out.d").string()});
        EXPECT_EQ(r.exitCode, 2) << name << ": " << r.err;
        EXPECT_NE(r.err.find("make cannot name"), std::string::npos) << r.err;
        EXPECT_EQ(test::filesIn(dir.path()), std::vector<std::string>{name}) << "left files behind";
    }
    // '%' in the target would make a pattern rule.
    test::ScratchDir dir;
    test::writeFile(dir / "in.obj", kQuadObj);
    auto r = test::run({bin("limn-classify"), (dir / "in.obj").string(), "-o",
                        (dir / "out%.limn").string(), "--depfile", (dir / "out.d").string()});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(test::filesIn(dir.path()), std::vector<std::string>{"in.obj"});
}

TEST(SideFiles, GltfDepfileListsItsBuffers) {
    test::ScratchDir dir;
    const std::string gltf = test::modelPath("gltf/Avocado/Avocado.gltf").string();
    auto r = test::run({bin("limn-classify"), gltf, "-o", (dir / "a.limn").string(), "--depfile",
                        (dir / "a.d").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string rule = test::readFile(dir / "a.d");
    EXPECT_NE(rule.find(gltf), std::string::npos) << rule;
    EXPECT_NE(rule.find(test::modelPath("gltf/Avocado/Avocado.bin").string()), std::string::npos)
        << rule;
}

// Starts `argv` with stdout/stderr to /dev/null (or stderr to a closed pipe), waits until a
// temporary output file exists in `dir`, sends `sig`, and returns the wait status.
// Signals the tool once a temporary file shows in `dir` (or, with `landed`, once that file is
// there), or, with `closedStderr`, lets its next write to stderr raise SIGPIPE.
int runAndSignal(const std::vector<std::string>& argv, const std::filesystem::path& dir, int sig,
                 bool closedStderr = false, const std::filesystem::path& landed = {}) {
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    int pipeFds[2] = {-1, -1};
    if (closedStderr) {
        if (pipe(pipeFds) != 0) return -1;
        posix_spawn_file_actions_adddup2(&fa, pipeFds[1], 2);
        posix_spawn_file_actions_addclose(&fa, pipeFds[0]);
    } else {
        posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
    }
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_t pid = -1;
    if (posix_spawn(&pid, args[0], &fa, nullptr, args.data(), environ) != 0) return -1;
    posix_spawn_file_actions_destroy(&fa);
    if (closedStderr) {
        ::close(pipeFds[0]); // the reader goes away: the tool's next write to stderr is SIGPIPE
        ::close(pipeFds[1]);
    } else {
        for (int i = 0; i < 500 && (landed.empty() ? !anyTemporary(dir) : !std::filesystem::exists(landed)); ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        ::kill(pid, sig);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    return status;
}

TEST(SideFiles, SignalsLeaveNoTemporaryFile) {
    test::ScratchDir dir;
    const std::string sphere = (dir / "sphere.limn").string();
    auto r = test::run({bin("limn-classify"), test::modelPath("tri/sphere.obj").string(), "-o",
                        sphere});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
        // Depth 6 uniform on 1,280 triangles runs for seconds (its memory estimate is lifted):
        // the signal comes mid-run, long before it has allocated much.
        const int status = runAndSignal({bin("limn-tables"), "--depth", "6", "--uniform", sphere,
                                         "--max-memory", "100000G", "-o",
                                         (dir / "big.limn").string()},
                                        dir.path(), sig);
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig)
            << "signal " << sig << ": status " << status;
        EXPECT_FALSE(anyTemporary(dir.path())) << "signal " << sig << " left a temporary file";
        EXPECT_FALSE(std::filesystem::exists(dir / "big.limn"));
    }
    // SIGPIPE from a closed stderr (limn-render -v ... 2>&1 | head -1).
    const int status = runAndSignal({bin("limn-render"), "-v", sphere, "--size", "32x24", "-o",
                                     (dir / "s.png").string()},
                                    dir.path(), SIGPIPE, /*closedStderr=*/true);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGPIPE) << "status " << status;
    EXPECT_FALSE(anyTemporary(dir.path()));
    EXPECT_FALSE(std::filesystem::exists(dir / "s.png"));
}

// An interrupted sequence removes the frames it had written, as a failed one does (they once
// stayed: 51 of a 2,000-frame turntable after SIGTERM).
TEST(SideFiles, SignalsRemoveASequencesFrames) {
    test::ScratchDir dir;
    const std::string cube = cubeContainer(dir);
    for (int sig : {SIGINT, SIGTERM}) {
        const int status = runAndSignal({bin("limn-render"), cube, "--size", "32x24", "--turntable", "2000", "-o",
                                         (dir / "f_%04d.png").string(), "--mesh-out", (dir / "f_%04d.ply").string()},
                                        dir.path(), sig, false, dir / "f_0002.png");
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "signal " << sig << ": status " << status;
        EXPECT_EQ(test::filesIn(dir.path()), (std::vector<std::string>{"cube.limn", "cube.obj"}))
            << "signal " << sig << " left frames or temporary files";
    }
}

// Many instances writing into one shared folder (a Slurm array on NFS, make -j) never pick the
// same temporary name: it carries the host and the process, as hostname and the pid give them.
TEST(SideFiles, TemporaryNamesCarryTheHostAndTheProcess) {
    test::ScratchDir dir;
    const std::string sphere = (dir / "sphere.limn").string();
    auto r = test::run({bin("limn-classify"), test::modelPath("tri/sphere.obj").string(), "-o", sphere});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
    // As SignalsLeaveNoTemporaryFile: a run of seconds, its temporary output there all along.
    std::vector<std::string> argv = {bin("limn-tables"), "--depth", "6", "--uniform", sphere, "--max-memory",
                                     "100000G", "-o", (dir / "big.limn").string()};
    std::vector<char*> args;
    for (auto& a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    pid_t pid = -1;
    ASSERT_EQ(posix_spawn(&pid, args[0], &fa, nullptr, args.data(), environ), 0);
    posix_spawn_file_actions_destroy(&fa);
    std::string temporary;
    for (int i = 0; i < 500 && temporary.empty(); ++i) {
        for (const auto& name : test::filesIn(dir.path()))
            if (name.find("limn-tmp") != std::string::npos) temporary = name;
        if (temporary.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ::kill(pid, SIGTERM);
    int status = 0;
    ::waitpid(pid, &status, 0);
    char host[256] = {};
    ASSERT_EQ(::gethostname(host, sizeof host - 1), 0);
    const std::string expected = ".limn-tmp-" + std::string(host).substr(0, 32) + "-" + std::to_string(pid) + "-";
    EXPECT_EQ(temporary.rfind(expected, 0), 0u) << temporary << " does not start with " << expected;
    EXPECT_EQ(temporary.size(), expected.size() + 6) << temporary;
    EXPECT_FALSE(anyTemporary(dir.path()));
}

// A part of a sequence (--shard) that is interrupted removes its own frames only: the frames
// other parts wrote into the same folder stay (a cancelled Slurm array task).
TEST(SideFiles, ASignalledPartRemovesOnlyItsOwnFrames) {
    test::ScratchDir dir;
    const std::string cube = cubeContainer(dir);
    const std::vector<std::string> others = {"f_0000.png", "f_0001.png", "f_0999.png"};
    for (const auto& name : others) test::writeFile(dir / name, "another part's frame");
    const int status = runAndSignal({bin("limn-render"), cube, "--size", "32x24", "--turntable", "2000", "--shard",
                                     "1/2", "-o", (dir / "f_%04d.png").string()},
                                    dir.path(), SIGTERM, false, dir / "f_1002.png");
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << "status " << status;
    std::vector<std::string> expected = {"cube.limn", "cube.obj"};
    expected.insert(expected.end(), others.begin(), others.end());
    EXPECT_EQ(test::filesIn(dir.path()), expected);
    for (const auto& name : others) EXPECT_EQ(test::readFile(dir / name), "another part's frame");
}

TEST(SideFiles, OverwritingKeepsTheModeAndWritesThroughALink) {
    test::ScratchDir dir;
    const std::string cube = cubeContainer(dir);
    const auto out = dir / "t.limn";
    test::writeFile(out, "old");
    ::chmod(out.c_str(), 0600);
    auto r = test::run({bin("limn-tables"), cube, "-o", out.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    struct stat st {};
    ASSERT_EQ(::stat(out.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0600u);
    EXPECT_NE(test::readFile(out), "old");

    std::filesystem::create_directory(dir / "real");
    test::writeFile(dir / "real/target.limn", "old");
    std::filesystem::create_symlink("real/target.limn", dir / "link.limn");
    r = test::run({bin("limn-tables"), cube, "-o", (dir / "link.limn").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(std::filesystem::is_symlink(dir / "link.limn"));
    EXPECT_EQ(test::readFile(dir / "real/target.limn"), test::readFile(out));
    EXPECT_FALSE(anyTemporary(dir.path()) || anyTemporary(dir / "real"));
}

TEST(SideFiles, AnOutputNeverDestroysAnInput) {
    test::ScratchDir dir;
    test::writeFile(dir / "m.obj", kQuadObj);
    auto r = test::run({bin("limn-classify"), (dir / "m.obj").string(), "-o",
                        (dir / "m.obj").string()});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(test::readFile(dir / "m.obj"), kQuadObj);
    // A map given to limn-render is no place for its image.
    const std::string cube = cubeContainer(dir), tables = (dir / "t.limn").string();
    ASSERT_EQ(test::run({bin("limn-tables"), cube, "-o", tables}).exitCode, 0);
    const std::string map = (dir / "h.png").string();
    ASSERT_EQ(test::run({bin("limn-heightmap"), "--kind", "uv", "--size", "16", "-o", map}).exitCode,
              0);
    const std::string mapBytes = test::readFile(map);
    r = test::run({bin("limn-render"), tables, "--displace", map, "-o", map});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(test::readFile(map), mapBytes);
    r = test::run({bin("limn-render"), tables, "-o", tables});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    // A container updated in place stays allowed.
    r = test::run({bin("limn-tables"), tables, "-o", tables, "--depth", "2"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

TEST(SideFiles, AFailedWriteToStandardOutputIsAFailure) {
    if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
    test::ScratchDir dir;
    const std::string cube = cubeContainer(dir);
    // test::run has no redirection of its own: a shell sends stdout to /dev/full.
    for (const std::string& cmd : {bin("limn-info") + " " + cube, bin("limn-info") + " --json " + cube,
                                  bin("limn-info") + " --help", bin("limn-examples") + " --list",
                                  bin("limn-classify") + " " + (dir / "cube.obj").string()}) {
        auto r = test::run({"/bin/sh", "-c", cmd + " > /dev/full"});
        EXPECT_EQ(r.exitCode, 1) << cmd << ": " << r.err;
        EXPECT_NE(r.err.find("<stdout>"), std::string::npos) << cmd << ": " << r.err;
        EXPECT_EQ(r.err.find("<stdin>"), std::string::npos) << cmd << ": " << r.err;
    }
}

// A closed standard stream's descriptor would be taken by the output file: -v lines and warnings
// landed inside the PNG or container (exit 0). Closed stderr: the outputs are what they should
// be; closed stdout: what goes there fails the run.
TEST(SideFiles, AClosedStandardStreamNeverWritesIntoAnOutput) {
    test::ScratchDir dir;
    const std::string cube = cubeContainer(dir), png = (dir / "v.png").string(), limn = (dir / "c.limn").string();
    auto r = test::run({"/bin/sh", "-c", bin("limn-render") + " " + cube + " --size 32x24 -v -o " + png + " 2>&-"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(test::readFile(png).substr(0, 4), "\x89PNG");
    r = test::run({"/bin/sh", "-c",
                   bin("limn-classify") + " -v " + (dir / "cube.obj").string() + " -o " + limn + " 2>&-"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(test::run({bin("limn-info"), limn}).exitCode, 0) << "the container is not one";
    std::filesystem::remove(png);
    r = test::run({"/bin/sh", "-c", bin("limn-render") + " " + cube + " --size 32x24 --bench 1 -o " + png + " >&-"});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("<stdout>"), std::string::npos) << r.err;
    if (std::filesystem::exists(png)) {
        EXPECT_EQ(test::readFile(png).substr(0, 4), "\x89PNG");
    }
}

TEST(SideFiles, LibpngSpeaksThroughLimnsError) {
    // A PNG limn's own decoder leaves to OpenImageIO (interlaced) with too little image data.
    test::ScratchDir dir;
    const std::string cube = cubeContainer(dir), tables = (dir / "t.limn").string();
    ASSERT_EQ(test::run({bin("limn-tables"), cube, "-o", tables}).exitCode, 0);
    // 4x4 RGB, Adam7, CRCs valid, but IDAT holds 3 bytes of image data.
    const unsigned char png[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
        0x52, 0x00, 0x00, 0x00, 0x04, 0x00, 0x00, 0x00, 0x04, 0x08, 0x02, 0x00, 0x00, 0x01, 0x51,
        0x94, 0x39, 0xbf, 0x00, 0x00, 0x00, 0x0b, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x60,
        0x60, 0x00, 0x00, 0x00, 0x03, 0x00, 0x01, 0xb8, 0xad, 0x3a, 0x63, 0x00, 0x00, 0x00, 0x00,
        0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    test::writeFile(dir / "bad.png", std::string(reinterpret_cast<const char*>(png), sizeof png));
    auto r = test::run({bin("limn-render"), tables, "--texture", (dir / "bad.png").string(), "-o",
                        (dir / "o.png").string()});
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(r.err.find("libpng"), std::string::npos) << "libpng printed on its own:\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("limn-render: error: ", 0), 0u) << r.err;
}

TEST(SideFiles, OutputFormatAndRepeatedOptions) {
    test::ScratchDir dir;
    test::writeFile(dir / "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\n"
                                   "f 2 3 4\nf 3 1 4\n");
    auto r = test::run({bin("limn-loop"), (dir / "t.obj").string(), "-o", (dir / "x.stl").string()});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find(".obj, .ply, .off"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.stl"));
    r = test::run({bin("limn-loop"), (dir / "t.obj").string(), "-o", (dir / "a.obj").string(), "-o",
                   (dir / "b.obj").string()});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("more than once"), std::string::npos) << r.err;
    EXPECT_EQ(test::filesIn(dir.path()), std::vector<std::string>{"t.obj"});
    // limn-heightmap writes PNG only: another extension is refused, not PNG bytes in "map.jpg".
    for (const char* name : {"map.jpg", "map.exr", "map"}) {
        r = test::run({bin("limn-heightmap"), "--kind", "uv", "--size", "16", "-o", (dir / name).string()});
        EXPECT_EQ(r.exitCode, 2) << name << ": " << r.err;
        EXPECT_NE(r.err.find("this tool writes PNG (.png, or - for standard output)"), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir / name));
    }
    r = test::run({bin("limn-heightmap"), "--kind", "uv", "--size", "16", "-o", (dir / "map.PNG").string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

TEST(SideFiles, UnknownOptionsSuggestTheNearest) {
    for (const auto& [wrong, right] : std::vector<std::pair<std::string, std::string>>{
             {"--wireframe", "--wire"}, {"--shading", "--shade"}, {"--textur", "--texture"}}) {
        auto r = test::run({bin("limn-render"), wrong});
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_NE(r.err.find("did you mean " + right + "?"), std::string::npos) << r.err;
    }
    auto r = test::run({bin("limn-render"), "--zzzzzzzz"});
    EXPECT_EQ(r.err.find("did you mean"), std::string::npos) << r.err;
}

} // namespace
