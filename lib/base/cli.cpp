#include "base/cli.h"

#include "base/error.h"
#include "base/io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <set>
#include <charconv>
#include <clocale>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <new>
#include <sstream>
#include <fcntl.h>
#include <unistd.h>

#ifndef LIMN_VERSION
#define LIMN_VERSION "0.1.0"
#endif

namespace limn::cli {

const char* const kDefaultExitCodes = "Exit codes:\n"
                                      "  0  success\n"
                                      "  1  bad input or failed processing\n"
                                      "  2  usage error\n"
                                      "  3  missing capability (for example no Vulkan device)\n";

namespace {

std::string g_tool = "limn";
bool g_quiet = false;
bool g_verbose = false;

[[noreturn]] void usageError(const std::string& message) {
    throw Error(ErrorKind::Usage, message + " (see --help)");
}

std::string formatNumber(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

double parseDouble(const std::string& option, const std::string& text) {
    double value = 0;
    const char* begin = text.data();
    const char* end = begin + text.size();
    auto [ptr, ec] = std::from_chars(begin, end, value);
    if (ec != std::errc() || ptr != end || !std::isfinite(value))
        usageError(option + ": '" + text + "' is not a number");
    return value;
}

} // namespace

Parser::Parser(std::string tool, std::string synopsis, std::string summary, Common& common,
               bool hasOutput, bool hasDepfile)
    : tool_(std::move(tool)), synopsis_(std::move(synopsis)), summary_(std::move(summary)),
      exitCodes_(kDefaultExitCodes), common_(common) {
    if (hasOutput)
        text("-o, --output", "FILE", &common.output, "output file; - for standard output");
    if (hasDepfile)
        text("--depfile", "FILE",
             &common.depfile, "also write a Make rule 'OUTPUT: INPUTS...' to FILE");
    flag("-q, --quiet", &common.quiet, "silence warnings");
    flag("-v, --verbose", &common.verbose, "print details on stderr");
    flag("-h, --help", &showHelp_, "print this help and exit");
    flag("--version", &showVersion_, "print the version and exit");
}

Parser::Option& Parser::add(const std::string& names) {
    Option o;
    std::stringstream ss(names);
    std::string part;
    while (std::getline(ss, part, ',')) {
        auto first = part.find_first_not_of(' ');
        part = part.substr(first);
        if (part.rfind("--", 0) == 0)
            o.longName = part;
        else
            o.shortName = part;
    }
    options_.push_back(std::move(o));
    return options_.back();
}

Parser& Parser::flag(const std::string& names, bool* out, const std::string& help) {
    Option& o = add(names);
    o.help = help;
    o.flagOut = out;
    return *this;
}

Parser& Parser::text(const std::string& names, const std::string& metavar, std::string* out,
                     const std::string& help) {
    Option& o = add(names);
    o.metavar = metavar;
    o.help = help;
    o.defaultText = *out;
    o.set = [out](const std::string& v) { *out = v; };
    return *this;
}

Parser& Parser::integer(const std::string& names, const std::string& metavar, int* out, int lo,
                        int hi, const std::string& help) {
    Option& o = add(names);
    std::string name = o.longName.empty() ? o.shortName : o.longName;
    o.metavar = metavar;
    o.help = help + " (" + std::to_string(lo) + " to " + std::to_string(hi) + ")";
    o.defaultText = std::to_string(*out);
    o.set = [out, lo, hi, name](const std::string& v) {
        int value = 0;
        auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), value);
        if (ec != std::errc() || ptr != v.data() + v.size())
            usageError(name + ": '" + v + "' is not an integer");
        if (value < lo || value > hi)
            usageError(name + ": " + v + " is out of range " + std::to_string(lo) + " to " +
                       std::to_string(hi));
        *out = value;
    };
    return *this;
}

Parser& Parser::real(const std::string& names, const std::string& metavar, double* out, double lo,
                     double hi, const std::string& help) {
    Option& o = add(names);
    std::string name = o.longName.empty() ? o.shortName : o.longName;
    o.metavar = metavar;
    o.help = help + " (" + formatNumber(lo) + " to " + formatNumber(hi) + ")";
    o.defaultText = formatNumber(*out);
    o.set = [out, lo, hi, name](const std::string& v) {
        double value = parseDouble(name, v);
        if (value < lo || value > hi)
            usageError(name + ": " + v + " is out of range " + formatNumber(lo) + " to " +
                       formatNumber(hi));
        *out = value;
    };
    return *this;
}

Parser& Parser::choice(const std::string& names, std::string* out,
                       std::vector<std::string> choices, const std::string& help) {
    Option& o = add(names);
    std::string name = o.longName.empty() ? o.shortName : o.longName;
    std::string list;
    for (const auto& c : choices) list += (list.empty() ? "" : "|") + c;
    o.metavar = list;
    o.help = help;
    o.defaultText = *out;
    o.set = [out, choices, name, list](const std::string& v) {
        for (const auto& c : choices)
            if (c == v) {
                *out = v;
                return;
            }
        usageError(name + ": '" + v + "' is not one of " + list);
    };
    return *this;
}

Parser& Parser::custom(const std::string& names, const std::string& metavar,
                       std::function<void(const std::string&)> set,
                       const std::string& defaultText, const std::string& help) {
    Option& o = add(names);
    o.metavar = metavar;
    o.help = help;
    o.defaultText = defaultText;
    o.set = std::move(set);
    return *this;
}

Parser& Parser::positional(const std::string& metavar, std::string* out, const std::string& help) {
    positionals_.emplace_back(metavar, out);
    positionalHelp_.push_back(help);
    return *this;
}

Parser& Parser::notes(const std::string& text) {
    notes_ += text;
    return *this;
}

Parser& Parser::exitCodes(const std::string& table) {
    exitCodes_ = table;
    return *this;
}

const Parser::Option* Parser::find(const std::string& name) const {
    for (const auto& o : options_)
        if (o.longName == name || o.shortName == name) return &o;
    return nullptr;
}

namespace {

// Option texts are reflowed into the column after the option names (28) up to 100 characters:
// tools write them as prose, line breaks in them are only hints.
std::string wrapped(const std::string& text) {
    constexpr size_t kIndent = 28, kWidth = 100;
    std::istringstream words(text);
    std::string out, line;
    for (std::string w; words >> w;) {
        if (!line.empty() && kIndent + line.size() + 1 + w.size() > kWidth) {
            out += line + "\n" + std::string(kIndent, ' ');
            line.clear();
        }
        line += (line.empty() ? "" : " ") + w;
    }
    out += line;
    std::replace(out.begin(), out.end(), '\x01', ' ');
    return out;
}

} // namespace

std::string Parser::help() const {
    std::ostringstream out;
    out << "Usage: " << tool_ << " " << synopsis_ << "\n\n" << summary_ << "\n";
    if (!positionals_.empty()) {
        out << "\nArguments:\n";
        for (size_t i = 0; i < positionals_.size(); ++i) {
            std::string left = "  " + positionals_[i].first;
            out << left << std::string(left.size() < 28 ? 28 - left.size() : 1, ' ')
                << positionalHelp_[i] << " [default: -]\n";
        }
    }
    out << "\nOptions:\n";
    for (const auto& o : options_) {
        std::string left = "  ";
        left += o.shortName.empty() ? "    " : o.shortName + ", ";
        left += o.longName;
        if (!o.metavar.empty()) left += " " + o.metavar;
        out << left;
        if (left.size() + 2 > 28) // keep two spaces between an option and its text
            out << "\n" << std::string(28, ' ');
        else
            out << std::string(28 - left.size(), ' ');
        // Every option that takes a value shows its default (--help lists them all); one whose
        // help text already explains its default says so itself.
        std::string text = o.help;
        if (o.set && !o.defaultText.empty())
            text += " [default:\x01" + o.defaultText + "]"; // \x01: a space not to break at
        else if (o.set && o.help.find("[default:") == std::string::npos)
            text += " [default:\x01none]";
        out << wrapped(text) << "\n";
    }
    if (!notes_.empty()) out << "\n" << notes_;
    if (!notes_.empty() && notes_.back() != '\n') out << "\n";
    out << "\n" << exitCodes_;
    return out.str();
}

namespace {

size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = up;
        }
    }
    return row[b.size()];
}

} // namespace

// "; did you mean --wire?" for the closest long option: one that the unknown name starts with
// or that starts with it (--wireframe, --sha), else the nearest within 3 edits; "" when none is.
std::string Parser::suggest(const std::string& unknown) const {
    std::string word = unknown;
    while (!word.empty() && word[0] == '-') word.erase(0, 1);
    std::string best;
    size_t bestDistance = 4;
    for (const Option& o : options_) {
        if (o.longName.empty()) continue;
        const std::string name = o.longName.substr(2);
        size_t d = editDistance(word, name);
        if (word.size() >= 3 && (word.rfind(name, 0) == 0 || name.rfind(word, 0) == 0)) d = 1;
        if (d < bestDistance) bestDistance = d, best = o.longName;
    }
    return best.empty() ? "" : "; did you mean " + best + "?";
}

bool Parser::parse(int argc, char** argv) {
    size_t nextPositional = 0;
    std::set<const Option*> seen;
    bool onlyPositionals = false;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        if (!onlyPositionals && arg == "--") {
            onlyPositionals = true;
            continue;
        }
        if (!onlyPositionals && arg.size() > 1 && arg[0] == '-') {
            std::string name = arg, value;
            bool hasValue = false;
            if (arg.rfind("--", 0) == 0) {
                auto eq = arg.find('=');
                if (eq != std::string::npos) {
                    name = arg.substr(0, eq);
                    value = arg.substr(eq + 1);
                    hasValue = true;
                }
            } else if (arg.size() > 2) { // -oFILE
                name = arg.substr(0, 2);
                value = arg.substr(2);
                hasValue = true;
            }
            const Option* o = find(name);
            if (!o) usageError("unknown option '" + name + "'" + suggest(name));
            // An option given twice is a mistake, not "the last one wins" (-o a -o b).
            if (o->flagOut == nullptr && !seen.insert(o).second)
                usageError((o->longName.empty() ? o->shortName : o->longName) +
                           " given more than once");
            if (o->flagOut) {
                if (hasValue) usageError(name + " takes no value");
                *o->flagOut = true;
                continue;
            }
            if (!hasValue) {
                if (i + 1 >= argc) usageError(name + " needs a value (" + o->metavar + ")");
                value = argv[++i];
            }
            // "" is never a value (an unset make variable): as a path it would mean standard
            // input or output, or no depfile, without a word.
            if (value.empty()) usageError(name + ": the value is empty; give " + o->metavar);
            o->set(value);
            continue;
        }
        if (arg.empty())
            usageError(nextPositional < positionals_.size()
                           ? "an empty argument where " + positionals_[nextPositional].first +
                                 " goes (use - for standard input)"
                           : std::string("an empty argument"));
        if (nextPositional >= positionals_.size()) usageError("unexpected argument '" + arg + "'");
        *positionals_[nextPositional++].second = arg;
    }
    if (showHelp_) {
        std::cout << help();
        std::cout.flush();
        return false;
    }
    if (showVersion_) {
        std::cout << tool_ << " " << LIMN_VERSION << "\n";
        std::cout.flush();
        return false;
    }
    setVerbosity(common_.quiet, common_.verbose);
    return true;
}

uint64_t defaultMemoryBudget() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), size = ::sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || size <= 0) return uint64_t(8) << 30;
    return uint64_t(pages) * uint64_t(size) / 2;
}

uint64_t parseByteSize(const std::string& option, const std::string& value) {
    std::string number = value;
    double unit = 1;
    if (!number.empty()) {
        const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(number.back())));
        const std::string units = "KMGT";
        if (auto k = units.find(c); k != std::string::npos) {
            unit = std::pow(1024.0, double(k + 1));
            number.pop_back();
        }
    }
    const double v = parseDouble(option, number);
    if (!(v * unit >= 1) || v * unit > 1e18) // 0.5 (bytes) would be a limit of 0
        usageError(option + ": '" + value + "' is not a size like 512M or 8G");
    return static_cast<uint64_t>(v * unit);
}

std::string shortNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

std::string formatBytes(uint64_t bytes) {
    char buf[32];
    const double b = double(bytes);
    if (b >= double(1ull << 30)) std::snprintf(buf, sizeof buf, "%.1f GiB", b / double(1ull << 30));
    else if (b >= double(1ull << 20)) std::snprintf(buf, sizeof buf, "%.0f MiB", b / double(1ull << 20));
    else if (b >= 1024) std::snprintf(buf, sizeof buf, "%.0f KiB", b / 1024); // --max-memory 1K is not "0 MiB"
    else std::snprintf(buf, sizeof buf, "%.0f bytes", b);
    return buf;
}

std::vector<double> parseNumberList(const std::string& option, const std::string& value,
                                    size_t count) {
    std::vector<double> out;
    std::stringstream ss(value);
    std::string part;
    while (std::getline(ss, part, ',')) out.push_back(parseDouble(option, part));
    if (out.size() != count)
        usageError(option + ": expected " + std::to_string(count) +
                   " comma-separated numbers, got '" + value + "'");
    return out;
}

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
