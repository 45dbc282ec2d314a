#include "mesh/obj.h"

#include "base/error.h"
#include "mesh/text_format.h"

#include <charconv>
#include <cstring>
#include <map>
#include <string_view>

namespace limn {

namespace {

struct Line {
    std::string_view text;
    size_t number;
};

class ObjParser {
public:
    ObjParser(std::span<const uint8_t> bytes, Warnings& warnings)
        : data_(reinterpret_cast<const char*>(bytes.data()), bytes.size()), warnings_(warnings) {}

    Mesh parse();

private:
    [[noreturn]] void fail(const std::string& message) const {
        throwBadInput(message, "line " + std::to_string(line_));
    }
    void warnOnce(const std::string& key, const std::string& message) {
        if (warned_[key]++ == 0) warnings_.add("line " + std::to_string(line_) + ": " + message);
    }

    static std::string_view nextToken(std::string_view& s) {
        size_t b = s.find_first_not_of(" \t");
        if (b == std::string_view::npos) {
            s = {};
            return {};
        }
        size_t e = s.find_first_of(" \t", b);
        std::string_view tok = s.substr(b, e == std::string_view::npos ? s.size() - b : e - b);
        s = e == std::string_view::npos ? std::string_view{} : s.substr(e);
        return tok;
    }

    double number(std::string_view tok, const char* what) const {
        double v = 0;
        auto [p, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
        if (ec != std::errc() || p != tok.data() + tok.size())
            fail(std::string("'") + std::string(tok) + "' is not a number (" + what + ")");
        return v;
    }
    long long integer(std::string_view tok, const char* what) const {
        long long v = 0;
        auto [p, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
        if (ec != std::errc() || p != tok.data() + tok.size())
            fail(std::string("'") + std::string(tok) + "' is not an integer (" + what + ")");
        return v;
    }
    // Resolves a 1-based or negative OBJ index against `count` elements seen so far.
    uint32_t resolve(std::string_view tok, size_t count, const char* what) const {
        long long i = integer(tok, what);
        if (i == 0) fail(std::string(what) + " index 0 is invalid (OBJ indices start at 1)");
        long long r = i > 0 ? i - 1 : static_cast<long long>(count) + i;
        if (r < 0) fail(std::string(what) + " index " + std::to_string(i) + " is before the first");
        if (r >= 0xFFFFFFFFll) fail(std::string(what) + " index " + std::to_string(i) + " too large");
        return static_cast<uint32_t>(r);
    }

    void parseVertex(std::string_view rest);
    void parseTexcoord(std::string_view rest);
    void parseFace(std::string_view rest);
    void parseTag(std::string_view rest);

    std::string_view data_;
    Warnings& warnings_;
    size_t line_ = 0;
    std::map<std::string, int> warned_;
    Mesh mesh_;
    std::vector<uint32_t> faceUV_; // per corner, or ~0 when the face has no vt
    size_t facesWithUV_ = 0, facesWithoutUV_ = 0;
    size_t firstFaceWithoutUV_ = 0;
    std::vector<uint32_t> cornerBuf_, uvBuf_;
};

void ObjParser::parseVertex(std::string_view rest) {
    double c[3];
    for (int i = 0; i < 3; ++i) {
        auto tok = nextToken(rest);
        if (tok.empty()) fail("a 'v' line needs 3 coordinates");
        c[i] = number(tok, "vertex coordinate");
    }
    // Extra values (w, or per-vertex colours) are allowed and ignored.
    mesh_.positions.push_back({c[0], c[1], c[2]});
}

void ObjParser::parseTexcoord(std::string_view rest) {
    auto tu = nextToken(rest);
    if (tu.empty()) fail("a 'vt' line needs at least 1 coordinate");
    double u = number(tu, "texture coordinate");
    auto tv = nextToken(rest);
    double v = tv.empty() ? 0.0 : number(tv, "texture coordinate");
    mesh_.uvs.push_back({u, v});
}

void ObjParser::parseFace(std::string_view rest) {
    cornerBuf_.clear();
    uvBuf_.clear();
    int withUV = 0, withoutUV = 0;
    for (auto tok = nextToken(rest); !tok.empty(); tok = nextToken(rest)) {
        size_t s1 = tok.find('/');
        std::string_view vtok = tok.substr(0, s1);
        cornerBuf_.push_back(resolve(vtok, mesh_.positions.size(), "vertex"));
        if (s1 != std::string_view::npos) {
            std::string_view after = tok.substr(s1 + 1);
            size_t s2 = after.find('/');
            std::string_view ttok = after.substr(0, s2);
            if (!ttok.empty()) {
                uvBuf_.push_back(resolve(ttok, mesh_.uvs.size(), "texture coordinate"));
                ++withUV;
                continue;
            }
        }
        ++withoutUV;
    }
    if (cornerBuf_.size() < 3)
        fail("a face needs at least 3 vertices, this one has " + std::to_string(cornerBuf_.size()));
    if (withUV && withoutUV) fail("some corners of this face have a texture coordinate, some not");
    mesh_.addFace(cornerBuf_);
    if (withUV) {
        ++facesWithUV_;
        faceUV_.insert(faceUV_.end(), uvBuf_.begin(), uvBuf_.end());
    } else {
        if (facesWithoutUV_++ == 0) firstFaceWithoutUV_ = mesh_.faceCount() - 1;
        faceUV_.insert(faceUV_.end(), cornerBuf_.size(), ~0u);
    }
}

void ObjParser::parseTag(std::string_view rest) {
    auto name = nextToken(rest);
    auto counts = nextToken(rest);
    if (name.empty() || counts.empty()) fail("a 't' line needs a name and nint/nfloat/nstring");
    size_t a = counts.find('/'), b = counts.find('/', a == std::string_view::npos ? a : a + 1);
    if (a == std::string_view::npos || b == std::string_view::npos)
        fail("tag counts must look like nint/nfloat/nstring, not '" + std::string(counts) + "'");
    long long ni = integer(counts.substr(0, a), "tag int count");
    long long nf = integer(counts.substr(a + 1, b - a - 1), "tag float count");
    long long ns = integer(counts.substr(b + 1), "tag string count");
    if (ni < 0 || nf < 0 || ns < 0 || ni > (1 << 24) || nf > (1 << 24) || ns > (1 << 24))
        fail("tag counts out of range");
    std::vector<long long> ints;
    std::vector<double> floats;
    std::vector<std::string_view> strings;
    for (long long i = 0; i < ni; ++i) {
        auto t = nextToken(rest);
        if (t.empty()) fail("tag '" + std::string(name) + "' has fewer ints than it declares");
        ints.push_back(integer(t, "tag int"));
    }
    for (long long i = 0; i < nf; ++i) {
        auto t = nextToken(rest);
        if (t.empty()) fail("tag '" + std::string(name) + "' has fewer floats than it declares");
        floats.push_back(number(t, "tag float"));
    }
    for (long long i = 0; i < ns; ++i) {
        auto t = nextToken(rest);
        if (t.empty()) fail("tag '" + std::string(name) + "' has fewer strings than it declares");
        strings.push_back(t);
    }
    auto index = [&](long long v, const char* what) -> uint32_t {
        if (v < 0 || v >= 0xFFFFFFFFll)
            fail(std::string(what) + " index " + std::to_string(v) + " is out of range");
        return static_cast<uint32_t>(v);
    };
    // One shared sharpness, or one per element (OpenSubdiv's reader uses floatargs[0] when there
    // is one float).
    auto sharpness = [&](size_t element) -> float {
        if (floats.empty()) fail("tag '" + std::string(name) + "' needs a sharpness value");
        double s = floats.size() == 1 ? floats[0] : floats.at(std::min(element, floats.size() - 1));
        return static_cast<float>(s < 0 ? 0 : s);
    };
    std::string n(name);
    if (n == "crease") {
        if (ints.size() < 2 || ints.size() % 2)
            fail("a crease tag needs pairs of vertex indices");
        for (size_t j = 0; j + 1 < ints.size(); j += 2)
            mesh_.tags.creases.push_back(
                {index(ints[j], "crease vertex"), index(ints[j + 1], "crease vertex"),
                 sharpness(j / 2)});
    } else if (n == "corner") {
        if (ints.empty()) fail("a corner tag needs vertex indices");
        for (size_t j = 0; j < ints.size(); ++j)
            mesh_.tags.corners.push_back({index(ints[j], "corner vertex"), sharpness(j)});
    } else if (n == "hole") {
        for (long long f : ints) mesh_.tags.holes.push_back(index(f, "hole face"));
    } else if (n == "interpolateboundary") {
        if (ints.size() != 1) fail("interpolateboundary needs one int");
        // OpenSubdiv's regression-corpus mapping: 0 none, 1 edge-and-corner, 2 edge-only.
        switch (ints[0]) {
        case 0: mesh_.tags.boundary = BoundaryRule::None; break;
        case 1: mesh_.tags.boundary = BoundaryRule::EdgeAndCorner; break;
        case 2: mesh_.tags.boundary = BoundaryRule::EdgeOnly; break;
        default: fail("interpolateboundary must be 0, 1 or 2, not " + std::to_string(ints[0]));
        }
    } else if (n == "facevaryinginterpolateboundary") {
        if (ints.size() != 1 || ints[0] < 0 || ints[0] > 5)
            fail("facevaryinginterpolateboundary needs one int from 0 to 5");
        mesh_.tags.fvar = static_cast<FVarRule>(ints[0]);
    } else if (n == "creasemethod") {
        if (strings.size() != 1) fail("creasemethod needs one string: normal or chaikin");
        if (strings[0] == "normal")
            mesh_.tags.creaseMethod = CreaseMethod::Uniform;
        else if (strings[0] == "chaikin")
            mesh_.tags.creaseMethod = CreaseMethod::Chaikin;
        else
            fail("creasemethod must be normal or chaikin, not '" + std::string(strings[0]) + "'");
    } else if (n == "smoothtriangles") {
        if (strings.size() != 1) fail("smoothtriangles needs one string: catmark or smooth");
        if (strings[0] == "catmark")
            mesh_.tags.triangles = TriangleSubdivision::Catmark;
        else if (strings[0] == "smooth")
            mesh_.tags.triangles = TriangleSubdivision::Smooth;
        else
            fail("smoothtriangles must be catmark or smooth, not '" + std::string(strings[0]) + "'");
    } else if (n == "vertexedit" || n == "edgeedit" || n == "faceedit") {
        warnOnce(n, "hierarchical edit tag '" + n +
                        "' ignored (OpenSubdiv 3 dropped hierarchical edits)");
    } else {
        warnOnce("tag:" + n, "unknown tag '" + n + "' ignored");
    }
    (void)rest;
}

Mesh ObjParser::parse() {
    size_t pos = 0;
    std::string joined; // for lines continued with a trailing backslash
    while (pos < data_.size()) {
        size_t end = data_.find('\n', pos);
        if (end == std::string_view::npos) end = data_.size();
        std::string_view line = data_.substr(pos, end - pos);
        pos = end + 1;
        ++line_;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        if (!line.empty() && line.back() == '\\') {
            joined.append(line.substr(0, line.size() - 1));
            joined += ' ';
            continue;
        }
        if (!joined.empty()) {
            joined.append(line);
            line = joined;
        }
        if (line.find('\0') != std::string_view::npos) fail("binary data in an OBJ file");
        size_t hash = line.find('#');
        if (hash != std::string_view::npos) line = line.substr(0, hash);
        std::string_view rest = line;
        std::string_view keyword = nextToken(rest);
        if (keyword.empty()) {
        } else if (keyword == "v") {
            parseVertex(rest);
        } else if (keyword == "vt") {
            parseTexcoord(rest);
        } else if (keyword == "f" || keyword == "fo") {
            parseFace(rest);
        } else if (keyword == "t") {
            parseTag(rest);
        } else if (keyword == "vn" || keyword == "vp" || keyword == "o" || keyword == "g" ||
                   keyword == "s" || keyword == "usemtl" || keyword == "mtllib") {
            // Normals are recomputed from the limit surface; grouping and materials do not
            // change the surface.
        } else if (keyword == "l" || keyword == "p") {
            warnOnce(std::string(keyword), "'" + std::string(keyword) +
                                               "' elements (lines, points) ignored");
        } else {
            warnOnce("kw:" + std::string(keyword),
                     "unknown statement '" + std::string(keyword) + "' ignored");
        }
        if (!joined.empty() && line.data() == joined.data()) joined.clear();
    }
    line_ = 0;
    if (facesWithUV_ > 0 && facesWithoutUV_ == 0) {
        mesh_.uvIndices = std::move(faceUV_);
    } else if (facesWithUV_ > 0) {
        warnings_.add("face " + std::to_string(firstFaceWithoutUV_) + " and " +
                      std::to_string(facesWithoutUV_ - 1) +
                      " others have no texture coordinates while the rest do; UVs dropped");
        mesh_.uvs.clear();
    } else {
        mesh_.uvs.clear(); // vt lines that no face uses carry no information
    }
    validateMesh(mesh_);
    return std::move(mesh_);
}

} // namespace

Mesh readObj(std::span<const uint8_t> text, Warnings& warnings) {
    return ObjParser(text, warnings).parse();
}

std::string writeObj(const Mesh& m) {
    std::string out;
    out.reserve(m.vertexCount() * 40 + m.cornerCount() * 12);
    for (const auto& p : m.positions) {
        out += "v ";
        appendNumber(out, p.x);
        out += ' ';
        appendNumber(out, p.y);
        out += ' ';
        appendNumber(out, p.z);
        out += '\n';
    }
    for (const auto& uv : m.uvs) {
        out += "vt ";
        appendNumber(out, uv.x);
        out += ' ';
        appendNumber(out, uv.y);
        out += '\n';
    }
    for (size_t f = 0; f < m.faceCount(); ++f) {
        out += 'f';
        auto face = m.face(f);
        for (size_t i = 0; i < face.size(); ++i) {
            out += ' ';
            out += std::to_string(face[i] + 1);
            if (m.hasUVs()) {
                out += '/';
                out += std::to_string(m.faceUVs(f)[i] + 1);
            }
        }
        out += '\n';
    }
    const Tags& t = m.tags;
    if (t.boundary) {
        int v = *t.boundary == BoundaryRule::None ? 0 : *t.boundary == BoundaryRule::EdgeAndCorner ? 1 : 2;
        out += "t interpolateboundary 1/0/0 " + std::to_string(v) + "\n";
    }
    if (t.fvar)
        out += "t facevaryinginterpolateboundary 1/0/0 " +
               std::to_string(static_cast<int>(*t.fvar)) + "\n";
    if (t.creaseMethod)
        out += std::string("t creasemethod 0/0/1 ") +
               (*t.creaseMethod == CreaseMethod::Chaikin ? "chaikin" : "normal") + "\n";
    if (t.triangles)
        out += std::string("t smoothtriangles 0/0/1 ") +
               (*t.triangles == TriangleSubdivision::Smooth ? "smooth" : "catmark") + "\n";
    for (const auto& c : t.creases) {
        out += "t crease 2/1/0 " + std::to_string(c.v0) + " " + std::to_string(c.v1) + " ";
        appendNumber(out, c.sharpness);
        out += '\n';
    }
    for (const auto& c : t.corners) {
        out += "t corner 1/1/0 " + std::to_string(c.vertex) + " ";
        appendNumber(out, c.sharpness);
        out += '\n';
    }
    if (!t.holes.empty()) {
        out += "t hole " + std::to_string(t.holes.size()) + "/0/0";
        for (uint32_t h : t.holes) out += " " + std::to_string(h);
        out += '\n';
    }
    return out;
}

} // namespace limn
