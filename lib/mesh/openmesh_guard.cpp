#include "mesh/openmesh_guard.h"

#include "base/error.h"

#include <cctype>
#include <charconv>
#include <cstdint>
#include <set>
#include <sstream>
#include <string>
#include <vector>

// What OpenMesh 9 does with hostile input, and which check below prevents it. Besides these
// checks, openmesh_io.cpp makes the stream throw on the first failed read, which ends every loop
// that would otherwise run on after the data is exhausted (OFF faces, PLY lists).
//
// OFF, read from a stream:
//  - the header keyword is ignored (OFF BINARY is parsed as text, COFF face colours as vertex
//    indices): only OFF, NOFF, STOFF and STNOFF, whose extra vertex values are skipped, pass;
//  - a missing face count is read into an uninitialized variable, and the face loop does not
//    stop at the end of the data: the counts must be present and fit the bytes.
// PLY:
//  - the header is read as a stream of words: a "property" word before any element line writes
//    through elements_.back() of an empty vector (SEGV), including one hidden in an obj_info
//    line or after a mangled element line; an unknown property type indexes past a table;
//    so only the strict line grammar passes;
//  - face properties declared before the vertex list are dropped from the layout, and the data
//    is then misread: the vertex list must come first;
//  - a custom list (per-corner "texcoord") has its length reserved before it is read: binary
//    lists need a uchar or uint16 count, and text lists a length the remaining data can hold,
//    where every word must be one number of its property's kind so that OpenMesh's operator>>
//    (which reads "6-5" as two numbers) stays in step with the layout;
//  - element counts drive loops that add a vertex or face per entry: they must fit the bytes.

namespace limn {

namespace {

std::string_view nextLine(std::string_view& text) {
    size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back())))
        line.remove_suffix(1);
    return line;
}

std::vector<std::string> words(std::string_view line) {
    std::istringstream in{std::string(line)};
    std::vector<std::string> out;
    for (std::string w; in >> w;) out.push_back(w);
    return out;
}

// What OpenMesh's text reader extracts for one property: a list length (always an integer)
// followed by that many values, or one value; whole numbers are read as integers.
struct PlyProperty {
    bool list = false;
    bool integer = false; // the value(s)
};

struct PlyElement {
    std::string name;
    uint64_t count = 0;
    std::vector<PlyProperty> properties;
};

struct PlyHeader {
    bool ascii = false;
    std::string_view data; // the bytes after the end_header line
    std::vector<PlyElement> elements;
};

// OpenMesh's reader takes time quadratic in the properties of an element (100,000 property
// lines: over a minute); real files have a few elements of a few dozen properties.
constexpr size_t kMaxPlyElements = 64, kMaxPlyProperties = 256;

PlyHeader parsePlyHeader(std::string_view text) {
    // The header ends at the first line that is exactly "end_header".
    std::string_view rest = text;
    size_t end = std::string_view::npos;
    while (!rest.empty()) {
        size_t at = text.size() - rest.size();
        if (nextLine(rest) == "end_header") {
            end = at;
            break;
        }
    }
    if (end == std::string_view::npos) throwBadInput("the PLY header has no end_header line");
    for (unsigned char c : text.substr(0, end))
        if (c >= 0x7F || (c < 0x20 && c != '\n' && c != '\r' && c != '\t'))
            throwBadInput("the PLY header contains a byte that is not text");

    static const std::set<std::string> scalars = {
        "char", "uchar", "short", "ushort", "int",   "uint",   "float",   "double",
        "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
    static const std::set<std::string> listCounts = {"uchar", "uint8", "uint16", "int"};
    static const std::set<std::string> keywords = {"ply",     "format",   "comment",
                                                   "element", "property", "end_header"};
    PlyHeader h;
    h.data = rest;
    std::set<std::string> elementNames;
    std::string_view header = text.substr(0, end);
    for (int number = 1; !header.empty(); ++number) {
        std::vector<std::string> w = words(nextLine(header));
        auto bad = [&](const std::string& why) {
            throwBadInput("PLY header line " + std::to_string(number) + ": " + why);
        };
        if (number == 1) {
            if (w != std::vector<std::string>{"ply"}) bad("the file must start with 'ply'");
        } else if (number == 2) {
            if (w.size() != 3 || w[0] != "format") bad("expected 'format TYPE VERSION'");
            h.ascii = w[1] == "ascii";
        } else if (w.empty() || w[0] == "comment") {
        } else if (w[0] == "obj_info") {
            for (const auto& word : w) // OpenMesh takes these words for keywords
                if (keywords.count(word)) bad("obj_info must not contain '" + word + "'");
        } else if (w[0] == "element") {
            PlyElement e;
            auto [p, ec] = w.size() == 3
                               ? std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count)
                               : std::from_chars_result{nullptr, std::errc::invalid_argument};
            if (ec != std::errc() || p != w[2].data() + w[2].size() || e.count > 0xFFFFFFFFull)
                bad("expected 'element NAME COUNT'");
            e.name = w[1];
            if (!elementNames.insert(e.name).second) bad("element '" + e.name + "' appears twice");
            if (h.elements.size() == kMaxPlyElements)
                bad("more than " + std::to_string(kMaxPlyElements) + " elements");
            h.elements.push_back(e);
        } else if (w[0] == "property") {
            if (h.elements.empty()) bad("a property before any element");
            PlyElement& e = h.elements.back();
            if (e.properties.size() == kMaxPlyProperties)
                bad("element '" + e.name + "' has more than " + std::to_string(kMaxPlyProperties) + " properties");
            if (w.size() == 5 && w[1] == "list" && scalars.count(w[2]) && !listCounts.count(w[2]))
                bad("a list count of type '" + w[2] + "': limn reads uchar, uint8, uint16 or int counts");
            bool list =
                w.size() == 5 && w[1] == "list" && listCounts.count(w[2]) && scalars.count(w[3]);
            bool scalar = w.size() == 3 && scalars.count(w[1]);
            if (!list && !scalar)
                bad("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME' with "
                    "PLY types");
            bool faceVertices =
                list && e.name == "face" && (w[4] == "vertex_indices" || w[4] == "vertex_index");
            if (list && !faceVertices && w[2] == "int")
                bad("a list of '" + w[4] + "' needs a uchar or uint16 count");
            if (e.name == "face" && e.properties.empty() && !faceVertices)
                bad("the face element must start with its vertex_indices list");
            static const std::set<std::string> floats = {"float", "double", "float32", "float64"};
            // OpenMesh reads face vertex indices as integers whatever their declared type.
            e.properties.push_back({list, faceVertices || !floats.count(list ? w[3] : w[1])});
        } else {
            bad("unknown keyword '" + w[0].substr(0, 32) + "'");
        }
    }
    return h;
}

// In text PLY a list's length is just a number in the data, which OpenMesh reserves memory for
// before reading the list; it must fit the values that follow. And OpenMesh reads a number with
// operator>>, which stops at the first character that cannot continue it ("6-5" reads as 6 and
// -5): every word must be exactly one number of its property's kind, or a length could be read
// out of step with the layout.
void checkPlyTextData(const PlyHeader& h) {
    std::string_view data = h.data;
    size_t pos = 0;
    auto number = [&](bool integer, const PlyElement& e, uint64_t i) -> std::string_view {
        while (pos < data.size() && std::isspace(static_cast<unsigned char>(data[pos]))) ++pos;
        size_t start = pos;
        while (pos < data.size() && !std::isspace(static_cast<unsigned char>(data[pos]))) ++pos;
        std::string_view w = data.substr(start, pos - start);
        if (w.empty())
            throwBadInput("the PLY data ends early (in " + e.name + " " + std::to_string(i) + ")");
        std::string_view digits = w.substr(w[0] == '+' || (integer && w[0] == '-') ? 1 : 0);
        bool ok = !digits.empty();
        if (integer) {
            for (char c : digits) ok = ok && c >= '0' && c <= '9';
        } else {
            double v = 0;
            auto [p, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
            ok = ok && ec == std::errc() && p == digits.data() + digits.size();
        }
        if (!ok)
            throwBadInput("PLY " + e.name + " " + std::to_string(i) + ": '" +
                          std::string(w.substr(0, 24)) + "' is not " +
                          (integer ? "an integer" : "a number"));
        return w;
    };
    for (const auto& e : h.elements)
        for (uint64_t i = 0; i < e.count; ++i)
            for (const auto& p : e.properties) {
                if (!p.list) {
                    number(p.integer, e, i);
                    continue;
                }
                std::string_view w = number(true, e, i);
                uint64_t length = 0;
                auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), length);
                // Each value takes a character and a separator.
                if (ec != std::errc() || end != w.data() + w.size() ||
                    length > (data.size() - pos + 1) / 2)
                    throwBadInput("PLY " + e.name + " " + std::to_string(i) +
                                  " has a list of length '" + std::string(w.substr(0, 24)) +
                                  "', more than the data holds");
                for (uint64_t k = 0; k < length; ++k) number(p.integer, e, i);
            }
}

} // namespace

void checkOffForOpenMesh(std::string_view text, Warnings& warnings) {
    std::string_view keyword = nextLine(text);
    std::string_view layout = keyword;
    bool texcoords = layout.substr(0, 2) == "ST";
    if (texcoords) layout.remove_prefix(2);
    if (layout.substr(0, 1) == "N") layout.remove_prefix(1);
    if (layout != "OFF") {
        if (keyword.find("BINARY") != std::string_view::npos)
            throwBadInput("binary OFF is not supported; use text OFF or PLY");
        throwBadInput("OFF header '" + std::string(keyword.substr(0, 32)) +
                      "' is not supported (limn reads OFF, NOFF, STOFF and STNOFF)");
    }
    if (texcoords) warnings.add("STOFF texture coordinates are ignored; use PLY or OBJ for UVs");
    std::istringstream counts{std::string(text.substr(0, 256))};
    long long vertices = -1, faces = -1, edges = -1;
    counts >> vertices >> faces >> edges;
    if (!counts || vertices < 0 || faces < 0 || edges < 0)
        throwBadInput("the OFF header needs three counts (vertices faces edges) after '" +
                      std::string(keyword) + "'");
    // A vertex takes at least "0 0 0\n", a face "3 0 1 2\n".
    if (vertices > static_cast<long long>(text.size()) / 6 ||
        faces > static_cast<long long>(text.size()) / 8)
        throwBadInput("the OFF header promises " + std::to_string(vertices) + " vertices and " +
                      std::to_string(faces) + " faces; the " + std::to_string(text.size()) +
                      " bytes after it cannot hold them");
}

void checkPlyForOpenMesh(std::string_view text) {
    PlyHeader h = parsePlyHeader(text);
    uint64_t entries = 0;
    for (const auto& e : h.elements) {
        if (e.count > 0 && e.properties.empty())
            throwBadInput("PLY element '" + e.name + "' has " + std::to_string(e.count) +
                          " entries but no properties");
        entries += e.count;
    }
    // Every entry of an element with properties takes at least one byte.
    if (entries > h.data.size())
        throwBadInput("the PLY header promises " + std::to_string(entries) + " elements; the " +
                      std::to_string(h.data.size()) + " bytes after it cannot hold them");
    if (h.ascii) checkPlyTextData(h);
}

} // namespace limn
