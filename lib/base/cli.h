// The command-line conventions every limn tool shares (brief, "Conventions every tool follows"):
// `limn-<name> [options] [INPUT|-] [-o OUTPUT|-]`, --help with every option, its default and range
// and the exit-code table, --version, -q/-v, --depfile, exit codes 0/1/2/3, and the error format
// `limn-<name>: error: <file>[:<where>]: <message>`.
#pragma once

#include "base/warnings.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace limn::cli {

// Options every tool has. Tools that write no file leave hasOutput false.
struct Common {
    std::string output = "-";
    std::string depfile;
    bool quiet = false;
    bool verbose = false;
};

class Parser {
public:
    // `synopsis` is the part after the tool name, e.g. "[options] [INPUT|-] [-o OUTPUT|-]".
    Parser(std::string tool, std::string synopsis, std::string summary, Common& common,
           bool hasOutput = true, bool hasDepfile = true);

    // `names` is "--long" or "-s, --long". Defaults shown in --help are taken from *out.
    Parser& flag(const std::string& names, bool* out, const std::string& help);
    Parser& text(const std::string& names, const std::string& metavar, std::string* out,
                 const std::string& help);
    Parser& integer(const std::string& names, const std::string& metavar, int* out, int lo, int hi,
                    const std::string& help);
    Parser& real(const std::string& names, const std::string& metavar, double* out, double lo,
                 double hi, const std::string& help);
    Parser& choice(const std::string& names, std::string* out, std::vector<std::string> choices,
                   const std::string& help);
    // Anything else: `set` parses the value and throws Error(Usage) on a bad one.
    Parser& custom(const std::string& names, const std::string& metavar,
                   std::function<void(const std::string&)> set, const std::string& defaultText,
                   const std::string& help);
    // An optional positional argument (default "-", standard input).
    Parser& positional(const std::string& metavar, std::string* out, const std::string& help);
    // Free text printed in --help after the options (formats, examples).
    Parser& notes(const std::string& text);
    // Replaces the default exit-code table in --help.
    Parser& exitCodes(const std::string& table);

    // Returns false when --help or --version was handled (the tool then exits 0). Otherwise
    // applies -q / -v to the diagnostics (setVerbosity). Throws Error(Usage) for anything malformed.
    bool parse(int argc, char** argv);

    std::string help() const;

private:
    struct Option {
        std::string shortName, longName, metavar, help, defaultText;
        std::function<void(const std::string&)> set; // null for flags
        bool* flagOut = nullptr;
    };
    Option& add(const std::string& names);
    const Option* find(const std::string& name) const;
    std::string suggest(const std::string& unknown) const;

    std::string tool_, synopsis_, summary_, notes_, exitCodes_;
    Common& common_;
    std::vector<Option> options_;
    std::vector<std::pair<std::string, std::string*>> positionals_;
    std::vector<std::string> positionalHelp_;
    bool showHelp_ = false, showVersion_ = false;
};

// Half of the machine's physical memory: the default --max-memory of the tools whose output can
// grow exponentially with an option (limn-tables --depth, limn-loop --levels).
uint64_t defaultMemoryBudget();
// "512M", "8G", "1.5G", "100000" (bytes); K/M/G/T are powers of 1024. Throws Error(Usage).
uint64_t parseByteSize(const std::string& option, const std::string& value);
std::string formatBytes(uint64_t bytes); // "1.5 GiB"
std::string shortNumber(double v);       // three significant digits for messages: "1e+39", "0.25"

// Parse helpers for option values; each throws Error(Usage) naming the option.
std::vector<double> parseNumberList(const std::string& option, const std::string& value,
                                    size_t count);

// Diagnostics on stderr, honouring -q / -v.
void setTool(const std::string& tool);
void setVerbosity(bool quiet, bool verbose);
void warn(const std::string& message);
void info(const std::string& message); // only with -v
void printWarnings(const Warnings& warnings, const std::string& file);

// Runs a tool body: sets the C locale, catches limn::Error and other exceptions, prints them in
// the standard format and returns the exit code. `body` returns the exit code on success (0).
// A tool's main only: first it starts the process again, once, with glibc's huge-page tunable
// set (cli.cpp, preferHugePages), so it must come before any thread or output.
int run(const std::string& tool, int argc, char** argv,
        const std::function<int(int, char**)>& body);

extern const char* const kDefaultExitCodes;

} // namespace limn::cli
