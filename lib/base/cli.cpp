// limn::cli::Parser: the tools' options (flags, values with ranges, choices, positionals),
// parsed as limn's tools share them; and the value formats they share (sizes, number lists).
#include "base/cli.h"

#include "base/error.h"

#include <algorithm>
#include <cctype>
#include <set>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
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

} // namespace limn::cli
