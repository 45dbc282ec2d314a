// limn::cli::Parser's --help text (options reflowed, defaults shown) and its "did you mean"
// suggestion for an unknown option.
#include "base/cli.h"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

namespace limn::cli {

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

} // namespace limn::cli
