// A watchdog in every GoogleTest executable: a test that has run for longer than
// LIMN_TEST_WATCHDOG_S seconds (default 300; every test here takes well under a minute, under
// load too) prints, once, where it is: its name, the command line of each process it started,
// and, where gdb is installed, every thread's backtrace of the test and of those processes.
// It stops nothing: CTest ends the test at its TIMEOUT (cmake/LimnHelpers.cmake), and
// scripts/test.sh runs a test that timed out once more. A hang in CI (one left a run waiting
// for an hour) then leaves its cause in the log instead of a silent timeout.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <mutex>
#include <spawn.h>
#include <string>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace {

using Clock = std::chrono::steady_clock;

std::string procFile(pid_t pid, const char* name) {
    std::ifstream f("/proc/" + std::to_string(pid) + "/" + name, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// The processes started by `root`, and theirs, from /proc/PID/stat's parent field.
std::vector<pid_t> descendantsOf(pid_t root) {
    std::vector<std::pair<pid_t, pid_t>> parentOf; // (pid, ppid)
    if (DIR* proc = opendir("/proc")) {
        while (dirent* e = readdir(proc)) {
            const pid_t pid = static_cast<pid_t>(std::atoi(e->d_name));
            if (pid <= 0) continue;
            const std::string stat = procFile(pid, "stat");
            const size_t close = stat.rfind(')'); // the name in parentheses may hold spaces
            if (close == std::string::npos) continue;
            char state = 0;
            int ppid = 0;
            if (std::sscanf(stat.c_str() + close + 1, " %c %d", &state, &ppid) == 2)
                parentOf.emplace_back(pid, static_cast<pid_t>(ppid));
        }
        closedir(proc);
    }
    std::vector<pid_t> out = {root};
    for (size_t i = 0; i < out.size(); ++i)
        for (const auto& [pid, ppid] : parentOf)
            if (ppid == out[i]) out.push_back(pid);
    out.erase(out.begin());
    return out;
}

// gdb's backtraces of every thread of `pid` to stderr; at most a minute.
void printBacktraces(pid_t pid) {
    const char* gdb = "/usr/bin/gdb";
    if (access(gdb, X_OK) != 0) {
        std::fprintf(stderr, "watchdog: no %s, no backtraces\n", gdb);
        return;
    }
    const std::string target = std::to_string(pid);
    std::vector<std::string> argv = {gdb, "-nx", "-batch", "-p", target, "-ex", "thread apply all bt 40"};
    std::vector<char*> args;
    for (auto& a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&fa, 2, 1);
    pid_t child = -1;
    const int spawned = posix_spawn(&child, gdb, &fa, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    if (spawned != 0) return;
    int status = 0;
    for (int i = 0; i < 600 && waitpid(child, &status, WNOHANG) == 0; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (waitpid(child, &status, WNOHANG) == 0) {
        kill(child, SIGKILL);
        waitpid(child, &status, 0);
    }
}

// What the listener tells the watching thread. Never freed: GoogleTest's UnitTest is a static
// object that deletes its listeners at exit, while the detached thread may still wake.
struct WatchState {
    std::mutex mutex;
    std::string name;
    Clock::time_point start{};
    std::chrono::seconds limit{300};
    bool running = false;
    bool reported = false;
};

void report(const std::string& name, std::chrono::seconds limit) {
    std::fprintf(stderr, "watchdog: %s has run for over %ld s; where it is:\n", name.c_str(),
                 static_cast<long>(limit.count()));
    const std::vector<pid_t> children = descendantsOf(getpid());
    for (pid_t pid : children) {
        std::string cmdline = procFile(pid, "cmdline");
        for (char& c : cmdline)
            if (c == '\0') c = ' ';
        std::fprintf(stderr, "watchdog: subprocess %d: %s\n", static_cast<int>(pid), cmdline.c_str());
    }
    std::fflush(stderr);
    // gdb is our child, not our parent: let it attach where ptrace is limited to ancestors
    // (Yama's ptrace_scope 1).
    prctl(PR_SET_PTRACER, PR_SET_PTRACER_ANY, 0, 0, 0);
    std::fprintf(stderr, "watchdog: backtraces of the test (%d)\n", static_cast<int>(getpid()));
    printBacktraces(getpid());
    for (pid_t pid : children) {
        std::fprintf(stderr, "watchdog: backtraces of subprocess %d\n", static_cast<int>(pid));
        printBacktraces(pid);
    }
    std::fflush(stderr);
}

void watch(WatchState* state) {
    for (;;) {
        std::this_thread::sleep_for(std::chrono::seconds(1));
        std::string name;
        {
            std::lock_guard lock(state->mutex);
            if (!state->running || state->reported || Clock::now() - state->start < state->limit) continue;
            state->reported = true;
            name = state->name;
        }
        report(name, state->limit);
    }
}

class Watchdog : public testing::EmptyTestEventListener {
public:
    Watchdog() : state_(new WatchState) {
        const char* limit = std::getenv("LIMN_TEST_WATCHDOG_S");
        if (limit && std::atoi(limit) > 0) state_->limit = std::chrono::seconds(std::atoi(limit));
        std::thread(watch, state_).detach();
    }
    void OnTestStart(const testing::TestInfo& info) override {
        std::lock_guard lock(state_->mutex);
        state_->name = std::string(info.test_suite_name()) + "." + info.name();
        state_->start = Clock::now();
        state_->running = true;
        state_->reported = false;
    }
    void OnTestEnd(const testing::TestInfo&) override {
        std::lock_guard lock(state_->mutex);
        state_->running = false;
    }

private:
    WatchState* state_; // leaked on purpose (WatchState)
};

// Registered before main (GoogleTest's main, gtest_main) runs the tests; the listener list owns it.
[[maybe_unused]] const bool kWatchdogInstalled = [] {
    testing::UnitTest::GetInstance()->listeners().Append(new Watchdog);
    return true;
}();

} // namespace
