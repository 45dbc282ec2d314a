// Every tool starts itself again, once, with glibc's huge-page tunable in GLIBC_TUNABLES
// (lib/base/cli.cpp, preferHugePages), and leaves a user's own setting of that tunable alone.
// Seen from outside: the running tool's environment (/proc/PID/environ is the environment of the
// program image now running), while it waits for its standard input.
#include "test_support.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

// Starts `limn-classify -` with `tunables` as GLIBC_TUNABLES (none when empty) and its standard
// input a pipe held open, reads its environment once it holds `until` or after two seconds, then
// closes the pipe and reaps it. Returns the GLIBC_TUNABLES it ran with ("" when unset).
std::string tunablesSeen(const std::string& tunables, const std::string& until) {
    std::vector<std::string> env;
    for (char** e = environ; *e; ++e)
        if (std::string(*e).rfind("GLIBC_TUNABLES=", 0) != 0) env.push_back(*e);
    if (!tunables.empty()) env.push_back("GLIBC_TUNABLES=" + tunables);
    std::vector<char*> envp;
    for (auto& e : env) envp.push_back(e.data());
    envp.push_back(nullptr);
    const std::string tool = limn::test::tool("limn-classify").string();
    std::vector<char*> argv = {const_cast<char*>(tool.c_str()), const_cast<char*>("-"), nullptr};

    int in[2];
    if (pipe(in) != 0) return "pipe failed";
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, in[0], 0);
    posix_spawn_file_actions_addclose(&fa, in[1]);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid = -1;
    const int spawned = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&fa);
    ::close(in[0]);
    if (spawned != 0) {
        ::close(in[1]);
        return "spawn failed";
    }
    std::string seen;
    for (int i = 0; i < 100; ++i) {
        std::ifstream f("/proc/" + std::to_string(pid) + "/environ", std::ios::binary);
        const std::string all((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
        seen.clear();
        for (size_t at = 0; at < all.size();) {
            const size_t end = all.find('\0', at);
            const std::string var = all.substr(at, end == std::string::npos ? std::string::npos : end - at);
            if (var.rfind("GLIBC_TUNABLES=", 0) == 0) seen = var.substr(15);
            if (end == std::string::npos) break;
            at = end + 1;
        }
        if (!until.empty() && seen.find(until) != std::string::npos) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ::close(in[1]); // end of input: the tool reports an empty mesh and exits
    int status = 0;
    ::waitpid(pid, &status, 0);
    return seen;
}

TEST(HugePages, AToolRunsWithGlibcsHugePageTunable) {
    if (kSanitized) GTEST_SKIP() << "under the sanitizers malloc is not glibc's: no restart";
    EXPECT_EQ(tunablesSeen("", "hugetlb"), "glibc.malloc.hugetlb=1");
    // (With other tunables set, the restart adds this one after them; glibc 2.36 then rewrites
    // the string in the new process's memory, so /proc shows only the first part: not checked.)
}

TEST(HugePages, AUsersOwnSettingIsKept) {
    // No restart at all: the tool runs with what it was given (and the check waits the whole
    // two seconds, so a late restart would show).
    EXPECT_EQ(tunablesSeen("glibc.malloc.hugetlb=0", ""), "glibc.malloc.hugetlb=0");
}

} // namespace
