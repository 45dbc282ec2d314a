#include "subdiv/fvar_chunk.h"

#include "base/bytes.h"
#include "base/error.h"
#include "subdiv/tables.h"
#include "subdiv/tables_chunk.h"
#include "subdiv/tables_stream.h"
#include "subdiv/tables_surface_records.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <cstring>
#include <unordered_map>
#include <string>

namespace limn {

uint64_t fvarUVHash(const Mesh& mesh) {
    uint64_t h = hashBytes({reinterpret_cast<const uint8_t*>(mesh.uvs.data()), mesh.uvs.size() * sizeof(mesh.uvs[0])});
    return hashBytes({reinterpret_cast<const uint8_t*>(mesh.uvIndices.data()), mesh.uvIndices.size() * 4}, h);
}

FvarSurfaceChunk makeFvarSurfaceChunk(const Mesh& mesh, const SchemeOptions& options, uint32_t depth,
                                      uint32_t irregularLevels, Warnings& warnings) {
    FvarSurfaceChunk c;
    c.depth = depth;
    c.topologyHash = topologyHash(mesh, options);
    c.uvHash = fvarUVHash(mesh);
    c.ptexCount = ptexFaceCount(mesh);
    c.surface = FaceVaryingSurface(mesh, options, depth, irregularLevels, warnings).compactGpu();
    c.elementCount = static_cast<uint32_t>(c.surface.records.size() / 9);
    return c;
}

// Layout (formats/limn.md): u32 depth, u32 ptex count, u64 topology hash, u64 UV hash, u32 node
// count, u32 element count, u32 nodes[node count], f32 records[element count * 9 * 4]; version
// 2: u32 bases, each as TBLS version 5 stores it (writeBasisProgram), u32 values, f32
// values[2 * values], u32 smooth faces, a stream of their corners, valences and value indices.
// Version 3: each basis with its configuration and support size, then its program; a smooth
// face names its basis by index.
Chunk encodeFvarSurfaceChunk(const FvarSurfaceChunk& c) {
    ByteWriter w;
    w.reserve(40 + 4 * c.surface.nodes.size() + 16 * c.surface.records.size());
    w.write<uint32_t>(c.depth);
    w.write<uint32_t>(c.ptexCount);
    w.write<uint64_t>(c.topologyHash);
    w.write<uint64_t>(c.uvHash);
    w.write<uint32_t>(static_cast<uint32_t>(c.surface.nodes.size()));
    w.write<uint32_t>(static_cast<uint32_t>(c.surface.records.size() / 9));
    w.writeArray(c.surface.nodes);
    static_assert(sizeof(glm::vec4) == 16);
    w.writeArray(c.surface.records); // four f32 each, little-endian like every field here
    w.write<uint32_t>(static_cast<uint32_t>(c.surface.bases.size()));
    // Each basis as its configuration (version 3: interior valences and the configurations of
    // UV boundary vertices) and its one-level program (TBLS version 5's codec, a few hundred
    // bytes whatever k), which the reader expands to the same weights, bit for bit.
    for (const FaceVaryingSurface::Basis& b : c.surface.bases) {
        if (b.program.rows() == 0) throw std::logic_error("FVSF: a basis without its program");
        writeConfigurationBasis(w, b);
    }
    // The support UVs and limit UVs, each distinct value once (the n faces around a vertex
    // share most of theirs), and per smooth face in a stream its corner and valence, then its
    // limit's and its 2n + 8 support points' values as differences from the previous value.
    std::unordered_map<uint64_t, uint32_t> valueOf; // the value's bits
    valueOf.reserve(c.surface.points.size() / 2);
    std::vector<float> values;
    auto value = [&](glm::vec2 x) {
        uint64_t bits;
        std::memcpy(&bits, &x, 8);
        auto [it, added] = valueOf.emplace(bits, uint32_t(valueOf.size()));
        if (added) values.push_back(x.x), values.push_back(x.y);
        return it->second;
    };
    std::vector<uint8_t> stream;
    uint32_t previous = 0;
    auto index = [&](glm::vec2 x) {
        const uint32_t v = value(x);
        writeVarint(stream, zigzag(int64_t(v) - int64_t(previous)));
        previous = v;
    };
    for (const FaceVaryingSurface::SmoothFace& f : c.surface.smoothFaces) {
        writeVarint(stream, f.corner | uint64_t(f.basis) << 2);
        index(f.limit);
        for (uint32_t i = 0; i < c.surface.bases[f.basis].supportSize(); ++i) index(c.surface.points[f.firstPoint + i]);
    }
    w.write<uint32_t>(static_cast<uint32_t>(values.size() / 2));
    w.writeArray(values);
    w.write<uint32_t>(static_cast<uint32_t>(c.surface.smoothFaces.size()));
    writeStream(w, stream);
    return Chunk{kFvarSurfaceChunk, kFvarSurfaceChunkVersion, w.take()};
}

namespace {

// Version 2: per valence, as TBLS version 5 stores one.
FaceVaryingSurface::Basis readValenceBasis(ByteReader& r, uint32_t b, const FaceVaryingSurface::Gpu& g) {
    // TBLS version 5's reader: its checks bound the program and its expansion, and refuse a
    // valence twice.
    FaceVaryingSurface::Basis x = readBasisProgram(r, b, g.bases);
    // limn-tables builds no basis of valence 4 (a regular vertex).
    if (x.valence == 4) r.fail("basis " + std::to_string(b) + " has valence 4");
    return x;
}

// Version 2 and 3's smooth faces, their support UVs and the bases, each count checked against
// the bytes left before anything is allocated.
void readSmoothFaces(ByteReader& r, FaceVaryingSurface::Gpu& g, uint32_t version) {
    const uint32_t bases = r.read<uint32_t>();
    if (bases > r.remaining() / 8) r.fail("basis count is too large");
    for (uint32_t b = 0; b < bases; ++b) {
        // Version 3: with its configuration (TBLS version 7's codec, which checks the weights'
        // range); version 2: per valence.
        FaceVaryingSurface::Basis x = version >= 3 ? readConfigurationBasis(r, "basis " + std::to_string(b), g.bases)
                                                   : readValenceBasis(r, b, g);
        if (version < 3) // Catmull-Clark's smooth weights are convex (irregular_basis.h)
            for (float w : x.weights)
                if (!(w >= 0.0f && w <= 1.0f)) r.fail("basis " + std::to_string(b) + " has a weight outside [0, 1]");
        g.bases.push_back(std::move(x));
    }
    const uint32_t valueCount = r.read<uint32_t>();
    const std::vector<float> values = r.readArray<float>(uint64_t(valueCount) * 2, "values");
    for (float x : values)
        if (!std::isfinite(x) || std::fabs(x) > 1e18f) r.fail("a value is not finite");
    const uint32_t faces = r.read<uint32_t>();
    StreamReader s(r, "smooth faces");
    // Each face takes at least 2 + support >= 6 bytes of the stream (2n + 10 >= 16 for an
    // interior one), and gives 8 bytes a point.
    if (faces > s.size() / (version >= 3 ? 6 : 16)) r.fail("smooth face count is too large");
    g.smoothFaces.resize(faces);
    uint32_t previous = 0;
    auto next = [&](uint32_t face) {
        previous = s.after(previous, "a value index");
        if (previous >= valueCount) r.fail("smooth face " + std::to_string(face) + " names a missing value");
        return glm::vec2(values[2 * size_t(previous)], values[2 * size_t(previous) + 1]);
    };
    for (uint32_t i = 0; i < faces; ++i) {
        FaceVaryingSurface::SmoothFace& f = g.smoothFaces[i];
        const uint64_t packed = s.varint();
        f.corner = uint32_t(packed & 3u);
        // Version 2 names the basis by its valence, version 3 by its index.
        uint64_t b = packed >> 2;
        if (version < 3)
            b = std::find_if(g.bases.begin(), g.bases.end(), [&](const FaceVaryingSurface::Basis& x) { return x.valence == b; }) -
                g.bases.begin();
        if (b >= g.bases.size()) r.fail("smooth face " + std::to_string(i) + " has no basis");
        f.basis = uint32_t(b);
        f.firstPoint = static_cast<uint32_t>(g.points.size());
        f.limit = next(i);
        for (uint32_t k = 0; k < g.bases[b].supportSize(); ++k) g.points.push_back(next(i));
    }
    s.finish();
}

} // namespace

FvarSurfaceChunk decodeFvarSurfaceChunk(const Chunk& chunk, const Mesh* mesh, const SchemeOptions* options) {
    if (chunk.version > kFvarSurfaceChunkVersion)
        throwBadInput("version " + std::to_string(chunk.version) + " is newer than this reader (3)", "chunk FVSF");
    ByteReader r(chunk.payload, "chunk FVSF");
    FvarSurfaceChunk c;
    c.depth = r.read<uint32_t>();
    if (c.depth > uint32_t(kMaxDepth)) r.fail("depth " + std::to_string(c.depth) + " is out of range");
    c.ptexCount = r.read<uint32_t>();
    c.topologyHash = r.read<uint64_t>();
    c.uvHash = r.read<uint64_t>();
    const uint32_t nodes = r.read<uint32_t>();
    c.elementCount = r.read<uint32_t>();
    if (nodes < c.ptexCount) r.fail("fewer nodes than ptex faces");
    c.surface.nodes = r.readArray<uint32_t>(nodes, "nodes");
    if (c.elementCount > r.remaining() / (9 * 16)) r.fail("element count is too large");
    const std::vector<float> f = r.readArray<float>(uint64_t(c.elementCount) * 36, "records");
    if (chunk.version >= 2) readSmoothFaces(r, c.surface, chunk.version);
    if (!r.atEnd()) r.fail("trailing bytes");
    const uint64_t named = uint64_t(c.elementCount) + c.surface.smoothFaces.size();
    for (uint32_t i = 0; i < nodes; ++i) {
        const uint32_t v = c.surface.nodes[i];
        if (v == 0xFFFFFFFFu) continue;
        if (v & 0x80000000u) {
            if ((v & 0x7FFFFFFFu) >= named) r.fail("node " + std::to_string(i) + " names a missing element");
        } else if (v <= i || v < c.ptexCount || uint64_t(v) + 4 > nodes) {
            // Children after their parent: the quadtree has no cycle, and a walk ends.
            r.fail("node " + std::to_string(i) + " has a bad child index");
        }
    }
    for (float x : f)
        if (!std::isfinite(x) || std::fabs(x) > 1e18f) r.fail("a record is not finite");
    c.surface.records.resize(size_t(c.elementCount) * 9);
    for (uint32_t e = 0; e < c.elementCount; ++e) {
        const float* h = &f[size_t(36) * e];
        if (!(h[2] > 0 && h[2] <= 1 && h[0] >= 0 && h[1] >= 0 && h[0] + h[2] <= 1 && h[1] + h[2] <= 1) ||
            (h[3] != 0 && h[3] != 1))
            r.fail("element " + std::to_string(e) + " has a bad domain");
        for (uint32_t k = 0; k < 9; ++k)
            c.surface.records[size_t(9) * e + k] = {f[36 * e + 4 * k], f[36 * e + 4 * k + 1], f[36 * e + 4 * k + 2], f[36 * e + 4 * k + 3]};
    }
    // Each node's square of its ptex face, from its parent's (children follow their parent): a
    // leaf's record must cover exactly its square, or a walk that ends there evaluates the
    // element far outside its domain (a size of 1e-30 gave Inf UVs and NaN displaced points); a
    // node reached twice or deeper than the GPU's walk (24 levels, fvar_eval.glsl) is refused.
    struct Square {
        uint32_t level = kNone, i = 0, j = 0;
    };
    std::vector<Square> squares(nodes);
    for (uint32_t p = 0; p < c.ptexCount; ++p) squares[p] = {0, 0, 0};
    for (uint32_t n = 0; n < nodes; ++n) {
        const Square q = squares[n];
        const uint32_t v = c.surface.nodes[n];
        if (q.level == kNone || v == 0xFFFFFFFFu) continue; // unreached, or a hole
        if ((v & 0x7FFFFFFFu) >= c.elementCount && (v & 0x80000000u)) { // a smooth face
            FaceVaryingSurface::SmoothFace& sf = c.surface.smoothFaces[(v & 0x7FFFFFFFu) - c.elementCount];
            if (sf.size != 0) r.fail("node " + std::to_string(n) + " names a smooth face named before");
            const uint32_t levels = c.surface.bases[sf.basis].levels;
            if (q.level + levels > 24) r.fail("node " + std::to_string(n) + "'s smooth face is deeper than 24 levels");
            sf.node = n;
            sf.size = std::ldexp(1.0f, -int(q.level));
            sf.u0 = float(q.i) * sf.size, sf.v0 = float(q.j) * sf.size;
            continue;
        }
        if (v & 0x80000000u) {
            const glm::vec4 h = c.surface.records[size_t(9) * (v & 0x7FFFFFFFu)];
            const float size = std::ldexp(1.0f, -int(q.level));
            if (h.x != float(q.i) * size || h.y != float(q.j) * size || h.z != size)
                r.fail("node " + std::to_string(n) + " names element " + std::to_string(v & 0x7FFFFFFFu) +
                       ", whose domain is not the node's square");
            continue;
        }
        if (q.level >= 24) r.fail("node " + std::to_string(n) + " is deeper than 24 levels");
        for (uint32_t k = 0; k < 4; ++k) {
            if (squares[v + k].level != kNone) r.fail("node " + std::to_string(v + k) + " has two parents");
            squares[v + k] = {q.level + 1, 2 * q.i + (k & 1), 2 * q.j + (k >> 1)};
        }
    }
    for (const FaceVaryingSurface::SmoothFace& sf : c.surface.smoothFaces)
        if (sf.size == 0) r.fail("a smooth face is named by no node");
    if (mesh) {
        if (!mesh->hasUVs()) throwBadInput("the mesh has no UVs (no FVUV chunk) for its smooth UV surface", "chunk FVSF");
        if (c.ptexCount != ptexFaceCount(*mesh)) r.fail("ptex face count differs from the mesh's");
        if (options && c.topologyHash != topologyHash(*mesh, *options))
            throwBadInput("the smooth UV surface was built for a different mesh topology or tags; re-run limn-tables",
                          "chunk FVSF");
        if (c.uvHash != fvarUVHash(*mesh))
            throwBadInput("the smooth UV surface was built from other UVs; re-run limn-tables", "chunk FVSF");
    }
    return c;
}

void checkFvarSurfaceCoverage(const FvarSurfaceChunk& fvar, const Tables& tables) {
    // Children follow their parent: one backward pass knows for every node whether a hole lies
    // below it (a walk toward a drawn point would end there; shaders/fvar_eval.glsl gives (0, 0)).
    const std::vector<uint32_t>& nodes = fvar.surface.nodes;
    std::vector<uint8_t> holeBelow(nodes.size());
    for (size_t i = nodes.size(); i-- > 0;) {
        const uint32_t v = nodes[i];
        holeBelow[i] = v == 0xFFFFFFFFu ? 1
                       : (v & 0x80000000u) ? 0
                                           : holeBelow[v] | holeBelow[v + 1] | holeBelow[v + 2] | holeBelow[v + 3];
    }
    auto check = [&](uint32_t ptex, float u0, float v0, float size) {
        if (ptex >= fvar.ptexCount) throwBadInput("the tables draw ptex face " + std::to_string(ptex) + ", which it lacks", "chunk FVSF");
        uint32_t node = ptex;
        double ou = 0, ov = 0, s = 1;
        for (;;) {
            const uint32_t v = nodes[node];
            if (v != 0xFFFFFFFFu && (v & 0x80000000u)) return;
            if (v == 0xFFFFFFFFu || s <= size) {
                if (holeBelow[node])
                    throwBadInput("no UV element where the tables draw ptex face " + std::to_string(ptex), "chunk FVSF");
                return;
            }
            s /= 2;
            const uint32_t i = u0 >= ou + s ? 1 : 0, j = v0 >= ov + s ? 1 : 0;
            ou += i * s, ov += j * s;
            node = v + i + 2 * j;
        }
    };
    for (const Patch& p : tables.patches) check(p.ptex, p.u0, p.v0, p.size);
    for (const IrregularFace& f : tables.irregular) check(f.ptex, f.u0, f.v0, f.size);
}

} // namespace limn
