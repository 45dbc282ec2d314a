#include "render/sequence.h"

#include "base/cli.h"
#include "base/error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>

namespace limn::render {

namespace {

[[noreturn]] void usage(const std::string& option, const std::string& message) {
    throw Error(ErrorKind::Usage, option + ": " + message);
}

// Decimal digits only: no sign, space or exponent, at most 18 digits (no wrap-around).
bool decimal(const std::string& text, uint64_t& value) {
    if (text.empty() || text.size() > 18 || text.find_first_not_of("0123456789") != std::string::npos) return false;
    std::from_chars(text.data(), text.data() + text.size(), value);
    return true;
}

} // namespace

bool hasFrameNumber(const std::string& text) {
    for (size_t i = 0; i < text.size(); ++i) {
        if (text[i] != '%') continue;
        if (i + 1 < text.size() && text[i + 1] == '%') {
            ++i;
            continue;
        }
        const size_t j = i + 1;
        if (j < text.size() && text[j] == 'd') return true;
        if (j + 2 < text.size() && text[j] == '0' && text[j + 1] >= '1' && text[j + 1] <= '9' && text[j + 2] == 'd')
            return true;
    }
    return false;
}

FramePattern parseFramePattern(const std::string& option, const std::string& text) {
    FramePattern p;
    bool found = false;
    std::string* out = &p.prefix;
    const std::string expected = "'" + text + "' needs one frame number: %d or %04d (%% for a literal %)";
    for (size_t i = 0; i < text.size(); ++i) {
        if (text[i] != '%') {
            *out += text[i];
            continue;
        }
        if (i + 1 < text.size() && text[i + 1] == '%') {
            *out += '%';
            ++i;
            continue;
        }
        if (found) usage(option, "'" + text + "' has more than one frame number (%...d)");
        size_t j = i + 1;
        int width = 0;
        if (j < text.size() && text[j] == '0') {
            ++j;
            if (j >= text.size() || text[j] < '1' || text[j] > '9') usage(option, expected);
            width = text[j++] - '0';
        }
        if (j >= text.size() || text[j] != 'd') usage(option, expected);
        p.width = width;
        found = true;
        out = &p.suffix;
        i = j;
    }
    if (!found) usage(option, expected);
    return p;
}

std::string framePath(const FramePattern& p, uint64_t frame) {
    std::string digits = std::to_string(frame);
    if (digits.size() < size_t(p.width)) digits.insert(0, size_t(p.width) - digits.size(), '0');
    return p.prefix + digits + p.suffix;
}

std::vector<FrameFile> findFrameFiles(const FramePattern& p) {
    namespace fs = std::filesystem;
    // The number sits in the file name: the folder part of the prefix is fixed.
    const fs::path prefix(p.prefix);
    const std::string namePrefix = p.prefix.empty() || p.prefix.back() == '/' ? "" : prefix.filename().string();
    const fs::path folder = p.prefix.empty() || p.prefix.back() == '/' ? fs::path(p.prefix) : prefix.parent_path();
    if (p.suffix.find('/') != std::string::npos)
        throw Error(ErrorKind::Usage, "--frames: the frame number must be in the file name, not in a folder name");
    const fs::path dir = folder.empty() ? fs::path(".") : folder;
    std::error_code ec;
    fs::directory_iterator it(dir, ec);
    if (ec) throwBadInput("cannot list the folder " + dir.string() + ": " + ec.message());
    std::vector<FrameFile> found;
    for (; it != fs::directory_iterator(); it.increment(ec)) {
        if (ec) throwBadInput("cannot list the folder " + dir.string() + ": " + ec.message());
        const std::string name = it->path().filename().string();
        if (name.size() <= namePrefix.size() + p.suffix.size() || name.compare(0, namePrefix.size(), namePrefix) != 0 ||
            name.compare(name.size() - p.suffix.size(), p.suffix.size(), p.suffix) != 0)
            continue;
        const std::string digits = name.substr(namePrefix.size(), name.size() - namePrefix.size() - p.suffix.size());
        if (digits.size() > 18 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
        uint64_t n = 0;
        std::from_chars(digits.data(), digits.data() + digits.size(), n);
        FramePattern named{namePrefix, p.suffix, p.width};
        if (framePath(named, n) != name) continue; // walk_7.obj is not walk_%04d.obj
        if (!it->is_regular_file(ec)) continue;
        found.push_back({n, (folder.empty() ? fs::path(name) : folder / name).string()});
        if (found.size() > kMaxFrames)
            throwBadInput("more than " + std::to_string(kMaxFrames) + " files match the frame pattern");
    }
    if (found.empty())
        throwBadInput("no file matches the frame pattern (e.g. " + framePath(p, 1) + ")");
    std::sort(found.begin(), found.end(), [](const FrameFile& a, const FrameFile& b) { return a.number < b.number; });
    return found;
}

std::vector<ViewSpec> turntableViews(const ViewSpec& base, uint32_t n) {
    std::vector<ViewSpec> views;
    views.reserve(n);
    for (uint32_t k = 0; k < n; ++k) {
        ViewSpec v = base;
        // Exact multiples of the step, wrapped into [0, 360): frame k's camera is the one a
        // single render with --view (its azimuth),EL gets.
        v.azimuthDeg = std::fmod(base.azimuthDeg + 360.0 * k / n, 360.0);
        views.push_back(v);
    }
    return views;
}

std::vector<ViewSpec> parseCameraFile(const std::string& text, double defaultFovDeg) {
    std::vector<ViewSpec> views;
    size_t lineNumber = 0, start = 0;
    while (start <= text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::string line = text.substr(start, end - start);
        start = end + 1;
        ++lineNumber;
        if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
        for (char& c : line)
            if (c == ',' || c == '\t' || c == '\r') c = ' ';
        std::vector<double> v;
        const std::string where = "line " + std::to_string(lineNumber);
        for (size_t i = 0; i < line.size();) {
            if (line[i] == ' ') {
                ++i;
                continue;
            }
            size_t j = line.find(' ', i);
            if (j == std::string::npos) j = line.size();
            double x = 0;
            const auto [ptr, errc] = std::from_chars(line.data() + i, line.data() + j, x);
            if (errc != std::errc() || ptr != line.data() + j || !std::isfinite(x))
                throwBadInput("'" + line.substr(i, j - i) + "' is not a finite number", where);
            v.push_back(x);
            i = j;
        }
        if (v.empty()) continue;
        if (v.size() != 9 && v.size() != 10)
            throwBadInput("a camera is 9 or 10 numbers (eye, target, up, [fov]); this line has " +
                              std::to_string(v.size()),
                          where);
        // The --eye/--target limit (limn-render's vec3Option): float carries a camera no further.
        for (size_t i = 0; i < 9; ++i)
            if (std::abs(v[i]) > 1e18)
                throwBadInput(cli::shortNumber(v[i]) + " is beyond the 1e18 a camera may lie from the origin", where);
        ViewSpec s;
        s.eye = glm::dvec3(v[0], v[1], v[2]);
        s.target = glm::dvec3(v[3], v[4], v[5]);
        s.up = glm::dvec3(v[6], v[7], v[8]);
        s.fovDeg = v.size() == 10 ? v[9] : defaultFovDeg;
        const glm::dvec3 forward = *s.target - *s.eye;
        if (glm::length(forward) == 0) throwBadInput("eye and target are the same point", where);
        if (glm::length(*s.up) == 0) throwBadInput("the up vector is zero", where);
        if (glm::length(glm::cross(glm::normalize(forward), glm::normalize(*s.up))) < 1e-9)
            throwBadInput("the up vector is parallel to the view direction", where);
        if (!(s.fovDeg >= 1 && s.fovDeg <= 170)) throwBadInput("the field of view must be 1 to 170 degrees", where);
        views.push_back(s);
        if (views.size() > kMaxFrames) throwBadInput("more than " + std::to_string(kMaxFrames) + " cameras", where);
    }
    if (views.empty()) throwBadInput("no camera in the file (one per line: eye, target, up, [fov])");
    return views;
}

Shard parseShard(const std::string& option, const std::string& text) {
    const size_t slash = text.find('/');
    uint64_t index = 0, count = 0;
    if (slash == std::string::npos || !decimal(text.substr(0, slash), index) ||
        !decimal(text.substr(slash + 1), count) || count < 1 || count > kMaxFrames || index >= count)
        usage(option, "'" + text + "' is not I/N, part I of N counted from 0 (0 <= I < N <= " +
                          std::to_string(kMaxFrames) + "), e.g. 0/4 to 3/4");
    return {uint32_t(index), uint32_t(count)};
}

FrameRange parseFrameRange(const std::string& option, const std::string& text) {
    const size_t dash = text.find('-');
    FrameRange r;
    if (dash == std::string::npos || !decimal(text.substr(0, dash), r.first) ||
        !decimal(text.substr(dash + 1), r.last) || r.first > r.last)
        usage(option, "'" + text + "' is not A-B, the frame numbers A to B with A <= B, e.g. 0-11");
    return r;
}

std::vector<size_t> framesOfPart(const std::vector<uint64_t>& numbers, const FrameRange& range, const Shard& shard) {
    std::vector<size_t> inRange;
    for (size_t k = 0; k < numbers.size(); ++k)
        if (numbers[k] >= range.first && numbers[k] <= range.last) inRange.push_back(k);
    if (inRange.empty())
        usage("--frame-range", "no frame of the sequence is numbered " + std::to_string(range.first) + " to " +
                                   std::to_string(range.last) + " (its frames are " + std::to_string(numbers.front()) +
                                   " to " + std::to_string(numbers.back()) + ")");
    const uint64_t n = inRange.size();
    if (shard.count > n)
        usage("--shard", std::to_string(shard.index) + "/" + std::to_string(shard.count) + ": " + std::to_string(n) +
                             " frames make at most " + std::to_string(n) + " parts, and part " +
                             std::to_string(shard.index) + " would have none; give N <= " + std::to_string(n));
    const size_t begin = size_t(n * shard.index / shard.count), end = size_t(n * (shard.index + 1) / shard.count);
    return {inRange.begin() + ptrdiff_t(begin), inRange.begin() + ptrdiff_t(end)};
}

} // namespace limn::render
