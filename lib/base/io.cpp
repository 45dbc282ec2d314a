#include "base/io.h"

#include "base/error.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fcntl.h>
#include <stdio.h>
#include <csignal>
#include <filesystem>
#include <memory>
#include <sys/stat.h>
#include <unistd.h>
#include <unordered_map>

namespace limn {

namespace {

constexpr size_t kMaxInputBytes = size_t(4) << 30;

[[noreturn]] void throwIo(const std::string& what, const std::string& path) {
    Error e(ErrorKind::BadInput, what + ": " + std::strerror(errno));
    e.setFile(displayName(path));
    throw e;
}

} // namespace

std::vector<uint8_t> readInput(const std::string& path) {
    int fd = isStdio(path) ? STDIN_FILENO : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throwIo("cannot open", path);
    struct stat st {};
    if (::fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) {
        if (fd != STDIN_FILENO) ::close(fd);
        Error e(ErrorKind::BadInput, "is a directory, not a file");
        e.setFile(path);
        throw e;
    }
    std::vector<uint8_t> data;
    // Inputs are read whole; an endless one (/dev/zero, a runaway pipe) would take all the
    // memory and end in "out of memory" without a name. The largest input limn writes (the
    // car's uniform tables at depth 6) is 2 GB.
    auto tooLarge = [&] {
        if (fd != STDIN_FILENO) ::close(fd);
        Error e(ErrorKind::BadInput, "larger than 4 GiB, more than limn reads as one input");
        e.setFile(displayName(path));
        return e;
    };
    if (S_ISREG(st.st_mode) && uint64_t(st.st_size) > kMaxInputBytes) throw tooLarge();
    if (S_ISREG(st.st_mode) && st.st_size > 0) data.reserve(static_cast<size_t>(st.st_size));
    uint8_t buffer[1 << 16];
    for (;;) {
        ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0) {
            if (errno == EINTR) continue;
            int saved = errno;
            if (fd != STDIN_FILENO) ::close(fd);
            errno = saved;
            throwIo("cannot read", path);
        }
        if (n == 0) break;
        if (data.size() + size_t(n) > kMaxInputBytes) throw tooLarge();
        data.insert(data.end(), buffer, buffer + n);
    }
    if (fd != STDIN_FILENO) ::close(fd);
    // Nothing on standard input is nearly always a failed command earlier in the pipe (its error
    // is on the terminal above); "the mesh has no vertices" would blame the wrong stage.
    if (data.empty() && isStdio(path))
        throw Error(ErrorKind::BadInput,
                    "empty input on <stdin> (did the command before it in the pipe fail?)");
    return data;
}

std::string extensionOf(const std::string& path) {
    if (isStdio(path)) return {};
    auto slash = path.find_last_of('/');
    auto dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    std::string ext = path.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

std::string directoryOf(const std::string& path) {
    if (isStdio(path)) return {};
    auto slash = path.find_last_of('/');
    return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

bool stdoutIsTerminal() { return ::isatty(STDOUT_FILENO) == 1; }
bool stderrIsTerminal() { return ::isatty(STDERR_FILENO) == 1; }

// Temporary files not yet renamed into place, so a signal handler can remove them: a run
// stopped by SIGINT, SIGTERM, SIGHUP or SIGPIPE leaves no .limn-tmp-HOST-PID-XXXXXX behind. Fixed-size
// storage, because a handler may only touch async-signal-safe state.
namespace {

constexpr int kMaxTemps = 16;
constexpr size_t kMaxTempPath = 4096;
char g_temps[kMaxTemps][kMaxTempPath];
volatile sig_atomic_t g_tempUsed[kMaxTemps];

int registerTemp(const std::string& path) {
    if (path.size() >= kMaxTempPath) return -1;
    for (int i = 0; i < kMaxTemps; ++i)
        if (!g_tempUsed[i]) {
            std::memcpy(g_temps[i], path.c_str(), path.size() + 1);
            g_tempUsed[i] = 1;
            return i;
        }
    return -1;
}
void unregisterTemp(int slot) {
    if (slot >= 0) g_tempUsed[slot] = 0;
}

// prepareRemovalOnSignal's paths: one buffer of NUL-terminated names, built before g_landedCount
// says how many the handler may read; a flag per name, set once it is in place.
std::vector<char> g_landedNames;
std::vector<size_t> g_landedOffsets;
std::unique_ptr<volatile sig_atomic_t[]> g_landedFlags;
std::unordered_map<std::string, size_t> g_landedIndex;
volatile sig_atomic_t g_landedCount = 0;

extern "C" void removeTempsAndDie(int sig) {
    for (int i = 0; i < kMaxTemps; ++i)
        if (g_tempUsed[i]) ::unlink(g_temps[i]);
    for (sig_atomic_t i = 0; i < g_landedCount; ++i)
        if (g_landedFlags[i]) ::unlink(&g_landedNames[g_landedOffsets[i]]);
    ::signal(sig, SIG_DFL);
    ::raise(sig);
}

[[noreturn]] void throwOutputError(const std::string& what, const std::string& path) {
    Error e(ErrorKind::BadInput, what + ": " + std::strerror(errno));
    e.setFile(isStdio(path) ? "<stdout>" : path);
    throw e;
}

// Where writing `path` really goes: through a symbolic link (or a chain of them) to its target,
// so that overwriting a link updates the file it names instead of replacing the link.
std::string resolveLinks(const std::string& path) {
    std::string p = path;
    for (int hops = 0; hops < 40; ++hops) {
        struct stat st {};
        if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p;
        std::vector<char> buf(kMaxTempPath);
        ssize_t n = ::readlink(p.c_str(), buf.data(), buf.size() - 1);
        if (n < 0) return p;
        std::string target(buf.data(), static_cast<size_t>(n));
        p = (!target.empty() && target[0] == '/') ? target : directoryOf(p) + target;
    }
    errno = ELOOP;
    throwOutputError("cannot resolve output", path);
}

} // namespace

void prepareRemovalOnSignal(const std::vector<std::string>& paths) {
    clearRemovalOnSignal();
    g_landedIndex.clear();
    g_landedNames.clear();
    g_landedOffsets.clear();
    for (const auto& p : paths) {
        if (isStdio(p) || !g_landedIndex.emplace(p, g_landedOffsets.size()).second) continue;
        g_landedOffsets.push_back(g_landedNames.size());
        g_landedNames.insert(g_landedNames.end(), p.begin(), p.end());
        g_landedNames.push_back('\0');
    }
    g_landedFlags.reset(new volatile sig_atomic_t[g_landedOffsets.size()]());
    g_landedCount = static_cast<sig_atomic_t>(g_landedOffsets.size());
}

namespace {
void setLandedFlag(const std::string& path, sig_atomic_t landed) {
    if (auto it = g_landedIndex.find(path); it != g_landedIndex.end() && g_landedCount > 0)
        g_landedFlags[it->second] = landed;
}
} // namespace

void markLandedForRemovalOnSignal(const std::string& path) { setLandedFlag(path, 1); }

void clearRemovalOnSignal() { g_landedCount = 0; }

void installOutputCleanupOnSignals() {
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
        struct sigaction current {};
        if (::sigaction(sig, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
        struct sigaction sa {};
        sa.sa_handler = removeTempsAndDie;
        sigemptyset(&sa.sa_mask);
        ::sigaction(sig, &sa, nullptr);
    }
}

OutputFile::OutputFile(std::string path, Kind kind) : path_(std::move(path)) {
    if (isStdio(path_)) {
        if (kind == Kind::Binary && stdoutIsTerminal()) {
            throw Error(ErrorKind::Usage,
                        "refusing to write binary output to a terminal; use -o FILE or a pipe");
        }
        return;
    }
    // A link to a device or pipe (/dev/stdout -> /proc/self/fd/1 -> "pipe:[N]") is written
    // through the link itself: resolving it by hand gave a name that is no file.
    struct stat direct {};
    if (::stat(path_.c_str(), &direct) == 0 && !S_ISREG(direct.st_mode) && !S_ISDIR(direct.st_mode))
        target_ = path_;
    else
        target_ = resolveLinks(path_);
    // An existing target that is not a regular file (/dev/null, a FIFO, a terminal device) is
    // written in place: renaming a temporary file over it would replace the device or pipe with
    // a plain file (as root, /dev/null itself).
    struct stat st {};
    const bool exists = ::stat(target_.c_str(), &st) == 0;
    if (exists && !S_ISREG(st.st_mode)) {
        if (S_ISDIR(st.st_mode)) {
            Error e(ErrorKind::BadInput, "is a directory, not a file");
            e.setFile(path_);
            throw e;
        }
        fd_ = ::open(target_.c_str(), O_WRONLY | O_CLOEXEC);
        if (fd_ < 0) {
            Error e(ErrorKind::BadInput, std::string("cannot open output: ") + std::strerror(errno));
            e.setFile(path_);
            throw e;
        }
        if (kind == Kind::Binary && ::isatty(fd_) == 1) {
            ::close(fd_);
            fd_ = -1;
            throw Error(ErrorKind::Usage,
                        "refusing to write binary output to a terminal; use -o FILE or a pipe");
        }
        return;
    }
    // The temporary file's name is registered for the signal handler before the file exists
    // (O_EXCL makes it ours or fails): a signal at any moment finds the name, and unlinking a
    // name not created yet does nothing. (Blocking the signals while mkstemp ran protected only
    // the creating thread: a signal taken by another thread, lavapipe's or the frame writer's,
    // left the file behind; SideFiles.SignalsRemoveASequencesFrames hit it.)
    // The name carries the host and the process: many instances writing into one shared folder
    // (a Slurm array on NFS, make -j) never pick the same name, and a leftover says who left it.
    // The random part still decides between threads and retries; O_EXCL decides the rest.
    static const std::string owner = [] {
        char host[256] = {};
        if (::gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
        std::string name;
        for (const char* c = host; *c && name.size() < 32; ++c)
            name += std::isalnum(static_cast<unsigned char>(*c)) || *c == '-' || *c == '.' ? *c : '_';
        return (name.empty() ? std::string("host") : name) + "-" + std::to_string(::getpid()) + "-";
    }();
    static std::atomic<uint64_t> counter{0};
    const std::string directory = directoryOf(target_);
    int createErrno = EEXIST;
    for (int attempt = 0; attempt < 100 && fd_ < 0 && createErrno == EEXIST; ++attempt) {
        uint64_t x = (uint64_t(::getpid()) << 32) ^
                     uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()) ^
                     (counter.fetch_add(1) + 1) * 0x9E3779B97F4A7C15ull;
        std::string name = directory + ".limn-tmp-" + owner;
        for (int i = 0; i < 6; ++i, x /= 62)
            name += "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"[x % 62];
        tempSlot_ = registerTemp(name);
        fd_ = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
        createErrno = errno;
        if (fd_ >= 0) {
            tempPath_ = name;
        } else {
            unregisterTemp(tempSlot_);
            tempSlot_ = -1;
        }
    }
    if (fd_ < 0) {
        errno = createErrno;
        Error e(ErrorKind::BadInput, std::string("cannot create output: ") + std::strerror(errno));
        e.setFile(path_);
        throw e;
    }
    // An existing file keeps its permissions; a new one gets what a plain creat() would give
    // (0666 & ~umask), where it was created 0600.
    if (exists) {
        ::fchmod(fd_, st.st_mode & 07777);
    } else {
        mode_t mask = ::umask(0);
        ::umask(mask);
        ::fchmod(fd_, 0666 & ~mask);
    }
}

OutputFile::~OutputFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!committed_ && !tempPath_.empty()) ::unlink(tempPath_.c_str());
    unregisterTemp(tempSlot_);
}

void OutputFile::write(std::span<const uint8_t> bytes) {
    const uint8_t* data = bytes.data();
    size_t size = bytes.size();
    const int fd = fd_ >= 0 ? fd_ : STDOUT_FILENO;
    while (size > 0) {
        ssize_t n = ::write(fd, data, size);
        if (n < 0) {
            if (errno == EINTR) continue;
            throwOutputError("cannot write", path_);
        }
        data += n;
        size -= static_cast<size_t>(n);
    }
}

void OutputFile::write(const std::string& text) {
    write(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

void OutputFile::finishWriting() {
    if (fd_ < 0) return;
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) throwOutputError("cannot write", path_);
}

void OutputFile::commit() {
    if (committed_) return;
    finishWriting();
    if (tempPath_.empty()) { // standard output, or written in place (a device or pipe)
        committed_ = true;
        return;
    }
    // A prepared sequence frame is flagged before it lands, not after: a signal between the
    // rename and a later flag left the frame behind (a --shard part's frame under SIGTERM). The
    // handler then removes the temporary file or the frame, whichever exists at that moment.
    setLandedFlag(path_, 1);
    if (::rename(tempPath_.c_str(), target_.c_str()) != 0) {
        setLandedFlag(path_, 0);
        throwOutputError("cannot rename into place", path_);
    }
    committed_ = true;
    unregisterTemp(tempSlot_);
    tempSlot_ = -1;
}

void writeOutput(const std::string& path, std::span<const uint8_t> bytes, OutputFile::Kind kind) {
    OutputFile out(path, kind);
    out.write(bytes);
    out.commit();
}

bool isStreamPath(const std::string& path) {
    struct stat st {};
    return !isStdio(path) && ::stat(path.c_str(), &st) == 0 && (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode));
}

void requireOutputExtension(const std::string& path, const std::string& extension, const std::string& format) {
    if (isStdio(path) || extensionOf(path) == extension || isStreamPath(path)) return;
    Error e(ErrorKind::Usage, "unknown extension; this tool writes " + format + " (" + extension +
                                  ", or - for standard output)");
    e.setFile(path);
    throw e;
}

bool sameFile(const std::string& a, const std::string& b) {
    if (isStdio(a) || isStdio(b)) return false;
    struct stat sa {}, sb {};
    if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0)
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    // Not both there yet: compare the names. Made absolute first: weakly_canonical leaves a
    // relative name whose first part does not exist relative, so "b.limn" and "./b.limn" differed
    // and a depfile could be written over the output.
    std::error_code ec1, ec2;
    auto ca = std::filesystem::weakly_canonical(std::filesystem::absolute(a, ec1), ec1),
         cb = std::filesystem::weakly_canonical(std::filesystem::absolute(b, ec2), ec2);
    return !ec1 && !ec2 && ca.lexically_normal() == cb.lexically_normal();
}

void refuseOverwritingInputs(const std::string& output, const std::vector<std::string>& inputs,
                             bool (*inPlace)(const std::string&)) {
    for (const auto& in : inputs)
        if (sameFile(output, in) && !(inPlace && inPlace(in)))
            throw Error(ErrorKind::Usage, "the output " + output +
                                              " is an input of this run and would be destroyed; "
                                              "write to another file");
}

// Make's escaping (GNU make 4): a backslash before space, '#', ':' and the glob
// characters, '$' doubled. What no escaping can express is refused: ';' and '|' (recipe and
// order-only separators), '=' (a target-specific variable), a tab or a newline, a '%' in the
// target (a pattern rule) and a trailing backslash (a line continuation).
std::string makeEscapedName(const std::string& path, bool isTarget) {
    auto refuse = [&](const std::string& why) {
        return Error(ErrorKind::Usage, "--depfile: make cannot name '" + path + "' (" + why +
                                           "); rename it or leave out --depfile");
    };
    if (path.empty()) throw refuse("an empty name");
    if (path.back() == '\\') throw refuse("it ends in a backslash");
    std::string out;
    for (char c : path) {
        if (c == ';' || c == '|' || c == '=') throw refuse(std::string("it contains '") + c + "'");
        if (c == '\t') throw refuse("it contains a tab");
        if (c == '\n' || c == '\r') throw refuse("it contains a line break");
        if (c == '%' && isTarget) throw refuse("a '%' in the target makes a pattern rule");
        if (c == '$') {
            out += "$$";
            continue;
        }
        if (std::strchr(" #:*?[]", c)) out += '\\';
        out += c;
    }
    return out;
}

Depfile::Depfile(const std::string& path, const std::vector<std::string>& outputs,
                 const std::vector<std::string>& inputs)
    : path_(path) {
    if (path_.empty()) return;
    if (isStdio(path_))
        throw Error(ErrorKind::Usage, "--depfile needs a file name, not standard output");
    for (const auto& o : outputs)
        if (sameFile(path_, o) || path_ == o)
            throw Error(ErrorKind::Usage, "--depfile " + path_ +
                                              " names an output of this run; give it its own name");
    for (const auto& i : inputs)
        if (sameFile(path_, i))
            throw Error(ErrorKind::Usage, "--depfile " + path_ +
                                              " names an input of this run; give it its own name");
    // Names make cannot express are refused now, before the run does its work.
    for (const auto& o : outputs) makeEscapedName(o, true);
    for (const auto& i : inputs)
        if (!isStdio(i)) makeEscapedName(i, false);
    file_.emplace(path_, OutputFile::Kind::Text);
}

void Depfile::setRule(const std::string& output, const std::vector<std::string>& inputs) {
    setRule(std::vector<std::string>{output}, inputs);
}

void Depfile::setRule(const std::vector<std::string>& outputs,
                      const std::vector<std::string>& inputs) {
    if (!file_) return;
    for (const auto& i : inputs)
        if (sameFile(path_, i))
            throw Error(ErrorKind::Usage, "--depfile " + path_ +
                                              " names an input of this run; give it its own name");
    // Appended piece by piece: GCC 12 at -O3 reports a false -Wrestrict for `string + ":"`
    // (GCC bug 105651) here.
    std::string rule;
    for (const auto& output : outputs) {
        if (!rule.empty()) rule.push_back(' ');
        rule.append(makeEscapedName(isStdio(output) ? "-" : output, true));
    }
    rule.push_back(':');
    for (const auto& in : inputs) {
        if (isStdio(in)) continue;
        rule.push_back(' ');
        rule.append(makeEscapedName(in, false));
    }
    rule.push_back('\n');
    rule_ = std::move(rule);
}

void Depfile::prepare() {
    if (!file_ || prepared_) return;
    file_->write(rule_);
    file_->finishWriting();
    prepared_ = true;
}

void Depfile::commit() {
    if (!file_) return;
    prepare();
    file_->commit();
}

} // namespace limn
