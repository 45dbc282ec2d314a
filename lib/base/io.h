// File input and atomic output. Outputs go to a temporary file beside the target and are renamed
// into place only on success, so a failed run never leaves a partial or stale file that a Makefile
// could mistake for a good build (brief, "Conventions every tool follows").
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace limn {

// "-" means standard input / standard output everywhere.
inline bool isStdio(const std::string& path) { return path.empty() || path == "-"; }
// An input's name in messages: "<stdin>" for standard input.
inline std::string displayName(const std::string& path) { return isStdio(path) ? "<stdin>" : path; }

// Reads a whole file (or stdin for "-"). Throws Error(BadInput) naming the file, and for an empty
// standard input (a failed command upstream in a pipe).
std::vector<uint8_t> readInput(const std::string& path);

// The extension of a path, lower-cased, with the dot (".obj"); empty for stdin or none.
std::string extensionOf(const std::string& path);

// The directory part of a path ("" for a bare file name or stdin).
std::string directoryOf(const std::string& path);

bool stdoutIsTerminal();
bool stderrIsTerminal();

// Writes to `path` atomically: bytes go to a temporary file in the same directory, which commit()
// renames over `path`. If the object is destroyed without commit() (an error was thrown), or the
// process is stopped by a signal that installOutputCleanupOnSignals() handles, the temporary file
// is removed and `path` is left untouched. For "-" the bytes go to stdout; binary output to a
// terminal is refused up front. An existing path that is not a regular file (/dev/null, a FIFO)
// is written in place, never replaced. Overwriting keeps an existing file's permissions, and a
// symbolic link is written through (its target is replaced, the link stays).
class OutputFile {
public:
    enum class Kind { Binary, Text };
    OutputFile(std::string path, Kind kind);
    ~OutputFile();
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    void write(std::span<const uint8_t> bytes);
    void write(const std::string& text);
    // Closes the file, so that a write error the kernel reports late (a full disk) is thrown now;
    // commit() then only renames it into place. Called by commit() when not called before.
    void finishWriting();
    void commit();
    const std::string& path() const { return path_; }

private:
    std::string path_;
    std::string target_; // path_ with symbolic links resolved
    std::string tempPath_;
    int fd_ = -1;
    int tempSlot_ = -1; // in the signal handler's list of temporary files
    bool committed_ = false;
};

// Removes every OutputFile's temporary file on SIGINT, SIGTERM, SIGHUP and SIGPIPE, then dies of
// the same signal (cli::run installs it for every tool). Signals set to be ignored stay ignored.
void installOutputCleanupOnSignals();

// Files already in place that the cleanup signals remove too: a sequence's frames, so that an
// interrupted run leaves all of its outputs or none (README, Conventions). `prepare` takes every
// path the run may write, before the first is written (the handler may only read what is ready);
// `landed` marks one as written; `clear` forgets them all (the run has finished or cleaned up).
void prepareRemovalOnSignal(const std::vector<std::string>& paths);
void markLandedForRemovalOnSignal(const std::string& path);
void clearRemovalOnSignal();

// Convenience: writes the whole buffer atomically.
void writeOutput(const std::string& path, std::span<const uint8_t> bytes, OutputFile::Kind kind);

// Refuses (Error(Usage)) an output that names one of the inputs: the run would destroy what it
// reads. `inPlace` (optional) says which inputs this tool may rewrite in place (a .limn container
// updated by a tool that writes containers).
void refuseOverwritingInputs(const std::string& output, const std::vector<std::string>& inputs,
                             bool (*inPlace)(const std::string&) = nullptr);

// Whether `path` names an existing device or FIFO (/dev/null, a named pipe): written in place,
// like standard output, whatever its name.
bool isStreamPath(const std::string& path);

// Tools that write one format (limn-heightmap, limn-trim: PNG) refuse another extension, as
// limn-render does, instead of writing PNG bytes into "map.jpg": Error(Usage) unless `path` ends
// in `extension` (case-insensitive), is "-", or is an existing device or FIFO.
void requireOutputExtension(const std::string& path, const std::string& extension, const std::string& format);

// Whether two paths name the same file (same inode when both exist; else the same canonical
// path). Standard input/output is never the same file as anything.
bool sameFile(const std::string& a, const std::string& b);

// A name as GNU make reads it in a rule; throws Error(Usage) for names make cannot express
// (';', '|', '=', tabs, line breaks, a trailing backslash, '%' in a target).
std::string makeEscapedName(const std::string& path, bool isTarget);

// The --depfile of a run: a Make rule "OUTPUT: INPUT..." (like a compiler's -MD). Opened with the
// outputs, so an unwritable depfile fails before any work; a depfile that names an output or an
// input is a usage error. setRule() before committing the outputs (it may refuse a name), commit()
// after them, so a failed run leaves neither. Inputs that are stdin are left out. Empty path: none.
class Depfile {
public:
    Depfile(const std::string& path, const std::vector<std::string>& outputs,
            const std::vector<std::string>& inputs);
    void setRule(const std::string& output, const std::vector<std::string>& inputs);
    // Several targets made by the one run ("image.png mesh.glb: inputs").
    void setRule(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs);
    // Writes the rule and closes the file without renaming it into place: tools call it before
    // committing their outputs, so that a depfile that cannot be written (a full disk, /dev/full)
    // fails the run while none of its outputs is in place yet. commit() renames it.
    void prepare();
    void commit();

private:
    std::string path_, rule_;
    std::optional<OutputFile> file_;
    bool prepared_ = false;
};

} // namespace limn
