// File input and atomic output. Outputs go to a temporary file beside the target and are renamed
// into place only on success, so a failed run never leaves a partial or stale file that a Makefile
// could mistake for a good build (brief, "Conventions every tool follows").
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace limn {

// "-" means standard input / standard output everywhere.
inline bool isStdio(const std::string& path) { return path.empty() || path == "-"; }

// Reads a whole file (or stdin for "-"). Throws Error(BadInput) naming the file.
std::vector<uint8_t> readInput(const std::string& path);

// The extension of a path, lower-cased, with the dot (".obj"); empty for stdin or none.
std::string extensionOf(const std::string& path);

// The directory part of a path ("" for a bare file name or stdin).
std::string directoryOf(const std::string& path);

bool stdoutIsTerminal();
bool stderrIsTerminal();

// Writes to `path` atomically: bytes go to a temporary file in the same directory, which commit()
// renames over `path`. If the object is destroyed without commit() (an error was thrown), the
// temporary file is removed and `path` is left untouched. For "-" the bytes go to stdout on commit;
// binary output to a terminal is refused up front. An existing path that is not a regular file
// (/dev/null, a FIFO) is written in place, never replaced.
class OutputFile {
public:
    enum class Kind { Binary, Text };
    OutputFile(std::string path, Kind kind);
    ~OutputFile();
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    void write(std::span<const uint8_t> bytes);
    void write(const std::string& text);
    void commit();
    const std::string& path() const { return path_; }

private:
    std::string path_;
    std::string tempPath_;
    int fd_ = -1;
    bool committed_ = false;
};

// Convenience: writes the whole buffer atomically.
void writeOutput(const std::string& path, std::span<const uint8_t> bytes, OutputFile::Kind kind);

// A Make rule "OUTPUT: INPUT..." with Make's escaping of spaces, '#' and '$', written atomically
// (like a compiler's -MD). Inputs that are stdin are left out.
void writeDepfile(const std::string& depfile, const std::string& output,
                  const std::vector<std::string>& inputs);

} // namespace limn
