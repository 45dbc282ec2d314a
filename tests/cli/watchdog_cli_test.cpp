// The tests' watchdog (tests/support/test_watchdog.cpp): a test that runs past its limit is named,
// with the command line of the process it waits on, and gdb is asked for the backtraces. Checked
// by running this executable again on this test with a 1 s limit and a subprocess of 6 s.
#include "test_support.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <unistd.h>

using namespace limn;

TEST(Watchdog, NamesAHungTestAndTheProcessItWaitsOn) {
    if (std::getenv("LIMN_WATCHDOG_DEMO")) { // the run below: waits past the watchdog's limit
        test::run({"/bin/sleep", "6"});
        return;
    }
    const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
    const auto r = test::run({"/usr/bin/env", "LIMN_WATCHDOG_DEMO=1", "LIMN_TEST_WATCHDOG_S=1", self,
                              "--gtest_filter=Watchdog.NamesAHungTestAndTheProcessItWaitsOn"});
    EXPECT_EQ(r.exitCode, 0) << r.err; // the watchdog reports; it stops nothing
    EXPECT_NE(r.err.find("watchdog: Watchdog.NamesAHungTestAndTheProcessItWaitsOn has run for over 1 s"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("/bin/sleep 6"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("watchdog: backtraces of the test"), std::string::npos) << r.err;
    // Where gdb is installed (scripts/setup.sh --tests) and may attach, every thread's stack; a
    // machine that forbids ptrace gets gdb's reason in the log instead.
    if (access("/usr/bin/gdb", X_OK) == 0) {
        const bool stacks = r.err.find("Thread 1 ") != std::string::npos && r.err.find("#0 ") != std::string::npos;
        const bool refused = r.err.find("ptrace") != std::string::npos;
        EXPECT_TRUE(stacks || refused) << r.err;
        if (stacks) {
            EXPECT_NE(r.err.find("nanosleep"), std::string::npos) << r.err; // sleep's own stack
        }
    } else {
        EXPECT_NE(r.err.find("no /usr/bin/gdb"), std::string::npos) << r.err;
    }
}
