// limn::cli::run, the frame of every tool's main: standard streams made safe, the huge-page
// restart, the C locale, output clean-up on signals, and exceptions turned into limn's one-line
// errors and exit codes; and the tool's warnings and -v lines on standard error.
#include "base/cli.h"

#include "base/error.h"
#include "base/io.h"

#include <cerrno>
#include <clocale>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <locale>
#include <new>
#include <fcntl.h>
#include <unistd.h>

namespace limn::cli {

namespace {

std::string g_tool = "limn";
bool g_quiet = false;
bool g_verbose = false;

} // namespace

void setTool(const std::string& tool) { g_tool = tool; }
void setVerbosity(bool quiet, bool verbose) {
    g_quiet = quiet;
    g_verbose = verbose;
}

void warn(const std::string& message) {
    if (!g_quiet) std::fprintf(stderr, "%s: warning: %s\n", g_tool.c_str(), message.c_str());
}

void info(const std::string& message) {
    if (g_verbose) std::fprintf(stderr, "%s: %s\n", g_tool.c_str(), message.c_str());
}

void printWarnings(const Warnings& warnings, const std::string& file) {
    for (const auto& w : warnings.messages) warn((file.empty() ? "" : file + ": ") + w);
}

namespace {

// Large allocations on transparent huge pages: glibc's malloc does so with the tunable
// glibc.malloc.hugetlb=1, which it reads once, at process start; so a tool starts itself again,
// once, with the tunable added to GLIBC_TUNABLES. On the 2-core virtual machines this project
// is built and tested on, a page fault costs microseconds, and the tools touch hundreds of MB of
// fresh memory (the GPU buffers are host memory on lavapipe): limn-tables on the 100,800-face car
// took 0.34x as long with the tunable, limn-render of it 0.67x, a 6-face cube the same, for about
// 2-4% more peak memory. Not again where GLIBC_TUNABLES already names the tunable (the restarted
// process; or a user's own setting, hugetlb=0 included), not under the sanitizers (their malloc
// is not glibc's), and nothing happens when /proc/self/exe cannot be read or the exec fails.
#if defined(__SANITIZE_ADDRESS__)
#define LIMN_SANITIZED_MALLOC 1 // gcc's -fsanitize=address (and clang's)
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LIMN_SANITIZED_MALLOC 1
#endif
#endif
void preferHugePages([[maybe_unused]] char** argv) {
#ifndef LIMN_SANITIZED_MALLOC
    const char* current = std::getenv("GLIBC_TUNABLES");
    if (current && std::strstr(current, "glibc.malloc.hugetlb")) return;
    char exe[4096];
    const ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0) return;
    exe[n] = '\0';
    const std::string before = current ? current : "";
    const std::string value = (before.empty() ? "" : before + ":") + "glibc.malloc.hugetlb=1";
    if (setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0) return;
    execv(exe, argv);
    if (current) setenv("GLIBC_TUNABLES", before.c_str(), 1); // the exec failed: carry on as we are
    else unsetenv("GLIBC_TUNABLES");
#endif
}

} // namespace

namespace {

// A standard stream the caller closed (`2>&-`, `>&-`) leaves its descriptor free, and the first
// file the tool opens takes it: warnings, -v lines or --bench's JSON then landed inside the
// output image or container, with exit 0. Each closed slot is filled first: standard input and
// error with /dev/null, standard output with /dev/full, so that what a tool writes there fails
// the run (exit 1) instead of going anywhere.
void fillClosedStandardStreams() {
    for (int fd = 0; fd <= 2; ++fd) {
        if (::fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
        const int opened = ::open(fd == 1 ? "/dev/full" : "/dev/null", fd == 0 ? O_RDONLY : O_WRONLY);
        if (opened >= 0 && opened != fd) {
            ::dup2(opened, fd);
            ::close(opened);
        }
    }
}

} // namespace

int run(const std::string& tool, int argc, char** argv,
        const std::function<int(int, char**)>& body) {
    fillClosedStandardStreams();
    preferHugePages(argv);
    std::setlocale(LC_ALL, "C");
    std::locale::global(std::locale::classic());
    setTool(tool);
    installOutputCleanupOnSignals();
    try {
        const int status = body(argc, argv);
        // What went to standard output through stdio (JSON, --help, --list) must have arrived:
        // a full disk or a closed pipe is a failed run, not exit 0.
        std::cout.flush();
        if (std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout) {
            std::fprintf(stderr, "%s: error: <stdout>: cannot write: %s\n", tool.c_str(),
                         std::strerror(errno ? errno : EIO));
            return 1;
        }
        return status;
    } catch (const Error& e) {
        std::string where;
        if (!e.file().empty()) where += displayName(e.file()) + ": ";
        if (!e.where().empty()) where += e.where() + ": ";
        std::fprintf(stderr, "%s: error: %s%s\n", tool.c_str(), where.c_str(), e.what());
        return static_cast<int>(e.kind());
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "%s: error: out of memory\n", tool.c_str());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: internal error: %s\n", tool.c_str(), e.what());
        return 1;
    }
}

} // namespace limn::cli
