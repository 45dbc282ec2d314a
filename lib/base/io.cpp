#include "base/io.h"

#include "base/error.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

namespace limn {

namespace {

[[noreturn]] void throwIo(const std::string& what, const std::string& path) {
    Error e(ErrorKind::BadInput, what + ": " + std::strerror(errno));
    e.setFile(isStdio(path) ? "<stdin>" : path);
    throw e;
}

void writeAll(int fd, const uint8_t* data, size_t size, const std::string& path) {
    while (size > 0) {
        ssize_t n = ::write(fd, data, size);
        if (n < 0) {
            if (errno == EINTR) continue;
            throwIo("cannot write", path);
        }
        data += n;
        size -= static_cast<size_t>(n);
    }
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
        data.insert(data.end(), buffer, buffer + n);
    }
    if (fd != STDIN_FILENO) ::close(fd);
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

OutputFile::OutputFile(std::string path, Kind kind) : path_(std::move(path)) {
    if (isStdio(path_)) {
        if (kind == Kind::Binary && stdoutIsTerminal()) {
            throw Error(ErrorKind::Usage,
                        "refusing to write binary output to a terminal; use -o FILE or a pipe");
        }
        return;
    }
    // An existing target that is not a regular file (/dev/null, a FIFO, a terminal device) is
    // written in place: renaming a temporary file over it would replace the device or pipe with
    // a plain file (as root, /dev/null itself).
    struct stat st {};
    if (::stat(path_.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
        if (S_ISDIR(st.st_mode)) {
            Error e(ErrorKind::BadInput, "is a directory, not a file");
            e.setFile(path_);
            throw e;
        }
        fd_ = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
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
    tempPath_ = directoryOf(path_) + ".limn-tmp-XXXXXX";
    std::vector<char> name(tempPath_.begin(), tempPath_.end());
    name.push_back('\0');
    fd_ = ::mkstemp(name.data());
    if (fd_ < 0) {
        Error e(ErrorKind::BadInput, std::string("cannot create output: ") + std::strerror(errno));
        e.setFile(path_);
        throw e;
    }
    tempPath_.assign(name.data());
    // mkstemp creates 0600; give the file the permissions a plain creat() would (0666 & ~umask).
    mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd_, 0666 & ~mask);
}

OutputFile::~OutputFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!committed_ && !tempPath_.empty()) ::unlink(tempPath_.c_str());
}

void OutputFile::write(std::span<const uint8_t> bytes) {
    writeAll(fd_ >= 0 ? fd_ : STDOUT_FILENO, bytes.data(), bytes.size(), path_);
}

void OutputFile::write(const std::string& text) {
    write(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

void OutputFile::commit() {
    if (fd_ < 0) {
        committed_ = true;
        return;
    }
    if (::close(fd_) != 0) {
        fd_ = -1;
        throwIo("cannot write", path_);
    }
    fd_ = -1;
    if (tempPath_.empty()) { // written in place (a device or pipe)
        committed_ = true;
        return;
    }
    if (::rename(tempPath_.c_str(), path_.c_str()) != 0) throwIo("cannot rename into place", path_);
    committed_ = true;
}

void writeOutput(const std::string& path, std::span<const uint8_t> bytes, OutputFile::Kind kind) {
    OutputFile out(path, kind);
    out.write(bytes);
    out.commit();
}

static std::string makeEscape(const std::string& path) {
    std::string out;
    for (char c : path) {
        if (c == ' ' || c == '#') out += '\\';
        if (c == '$') out += '$';
        out += c;
    }
    return out;
}

void writeDepfile(const std::string& depfile, const std::string& output,
                  const std::vector<std::string>& inputs) {
    // Appended piece by piece: GCC 12 at -O3 reports a false -Wrestrict for `string + ":"`
    // (GCC bug 105651) here.
    std::string rule = makeEscape(isStdio(output) ? "-" : output);
    rule.push_back(':');
    for (const auto& in : inputs) {
        if (isStdio(in)) continue;
        rule.push_back(' ');
        rule.append(makeEscape(in));
    }
    rule.push_back('\n');
    OutputFile out(depfile, OutputFile::Kind::Text);
    out.write(rule);
    out.commit();
}

} // namespace limn
