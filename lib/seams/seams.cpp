#include "seams/seams.h"

#include "base/bytes.h"
#include "base/error.h"
#include "mesh/mesh_chunks.h"
#include "subdiv/tables_chunk.h"
#include "topology/ptex.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace limn {

namespace {

constexpr uint32_t kCornerU[4] = {0, 1, 1, 0}, kCornerV[4] = {0, 0, 1, 1};

} // namespace

uint64_t seamsSourceHash(const Container& c) {
    uint64_t h = 0x5EA45EA45EA4ull;
    for (FourCC type : {kTablesChunk, kUVChunk})
        if (const Chunk* chunk = c.find(type)) h = hashBytes(chunk->payload, h ^ type.value);
    return h;
}

Seams computeSeams(const Mesh& mesh, const Tables& t, uint64_t sourceHash) {
    if (!mesh.hasUVs())
        throwBadInput("the mesh has no texture coordinates; seams and displacement need UVs");
    Topology topo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices);
    // Resolution: one step finer than the finest element, so edge midpoints are grid points.
    const uint32_t R = 1u << (t.depth + 1);
    PtexMap ptex(mesh, topo, R);
    Seams s;
    s.sourceHash = sourceHash;
    // A point's faces and its distinct UVs in them (in face order, each UV where it first
    // appears). A base vertex's are the same from every element with a corner there, and the
    // list is as long as the vertex has faces: they are made once per base vertex, or a vertex of
    // thousands of faces (a cone, a scanned pole) would cost its whole ring per element, and its
    // distinct UVs their square per element.
    struct PointCharts {
        std::vector<PtexMap::ChartUV> charts;
        std::vector<glm::vec2> distinct;
    };
    auto describe = [](std::vector<PtexMap::ChartUV>& charts, PointCharts& out) {
        out.charts.swap(charts);
        out.distinct.clear();
        std::unordered_set<uint64_t> seen;
        for (const auto& c : out.charts) {
            const glm::vec2 uv(c.uv);
            const glm::vec2 zeroed = uv + glm::vec2(0.0f); // -0 as +0: equal UVs compare equal
            if (seen.insert(uint64_t(std::bit_cast<uint32_t>(zeroed.x)) << 32 | std::bit_cast<uint32_t>(zeroed.y)).second)
                out.distinct.push_back(uv);
        }
        if (out.distinct.size() > kMaxPointUVs)
            throwBadInput("a vertex has " + std::to_string(out.distinct.size()) +
                          " different UVs in the faces around it, more than the " +
                          std::to_string(kMaxPointUVs) + " the displacement's seam fix averages");
    };
    std::unordered_map<uint64_t, PointCharts> baseVertices;
    std::vector<PtexMap::ChartUV> scratch;
    PointCharts other[3]; // points that are not base vertices: at most 3 in use at once
    auto at = [&](uint32_t p, uint32_t U, uint32_t V, int slot) -> const PointCharts& {
        const uint64_t key = ptex.key(p, U, V);
        if (ptex.isBaseVertexKey(key)) {
            auto [it, made] = baseVertices.try_emplace(key);
            if (made) {
                ptex.charts(p, U, V, scratch);
                describe(scratch, it->second);
            }
            return it->second;
        }
        ptex.charts(p, U, V, scratch);
        describe(scratch, other[slot]);
        return other[slot];
    };
    // The UV store stays within one GPU storage buffer (WebGPU's 128 MiB), checked as it grows so
    // that a mesh past it is refused before its seams fill memory.
    constexpr uint64_t kMaxUVs = (uint64_t(128) << 20) / sizeof(glm::vec2);
    auto reserveUVs = [&](uint64_t more) {
        if (s.uvs.size() + more > kMaxUVs)
            throwBadInput("the seams need more than " + std::to_string(kMaxUVs) +
                          " UVs (128 MiB, one GPU storage buffer): each element at a vertex carries all "
                          "of the vertex's different UVs, and some vertex has UV seams between many of its faces");
    };
    auto addElement = [&](uint32_t p, float u0, float v0, float size) {
        ElementSeams e{};
        const uint32_t U0 = uint32_t(double(u0) * R), V0 = uint32_t(double(v0) * R), W = uint32_t(double(size) * R);
        auto corner = [&](int k) { return std::pair{U0 + kCornerU[k] * W, V0 + kCornerV[k] * W}; };
        for (int k = 0; k < 4; ++k) {
            e.own[k] = glm::vec2(ptex.ownUV(p, u0 + double(kCornerU[k]) * size, v0 + double(kCornerV[k]) * size));
            auto [U, V] = corner(k);
            const PointCharts& c = at(p, U, V, 0);
            reserveUVs(c.distinct.size());
            e.cornerFirst[k] = static_cast<uint32_t>(s.uvs.size());
            e.cornerCount[k] = static_cast<uint32_t>(c.distinct.size());
            s.uvs.insert(s.uvs.end(), c.distinct.begin(), c.distinct.end());
        }
        for (int k = 0; k < 4; ++k) {
            auto [Ua, Va] = corner(k);
            auto [Ub, Vb] = corner((k + 1) % 4);
            const PointCharts& sides = at(p, (Ua + Ub) / 2, (Va + Vb) / 2, 0); // the faces along the edge
            const PointCharts* ends[2] = {&at(p, Ua, Va, 1), &at(p, Ub, Vb, 2)};
            e.edgeFirst[k] = static_cast<uint32_t>(s.uvs.size());
            e.edgeSides[k] = 0;
            std::vector<std::pair<glm::vec2, glm::vec2>> seenSides;
            for (const auto& side : sides.charts) {
                glm::vec2 uv[2];
                for (int end = 0; end < 2; ++end) { // each end's charts are in face order
                    const auto& list = ends[end]->charts;
                    auto it = std::upper_bound(list.begin(), list.end(), side.face,
                                               [](uint32_t f, const PtexMap::ChartUV& c) { return f < c.face; });
                    if (it != list.begin() && std::prev(it)->face == side.face) uv[end] = glm::vec2(std::prev(it)->uv);
                }
                bool seen = false;
                for (const auto& x : seenSides) seen |= x.first == uv[0] && x.second == uv[1];
                if (seen) continue;
                seenSides.push_back({uv[0], uv[1]});
                reserveUVs(2);
                s.uvs.push_back(uv[0]);
                s.uvs.push_back(uv[1]);
                ++e.edgeSides[k];
            }
        }
        s.elements.push_back(e);
    };
    for (const auto& p : t.patches) addElement(p.ptex, p.u0, p.v0, p.size);
    for (const auto& q : t.irregular) addElement(q.ptex, q.u0, q.v0, q.size);
    return s;
}

Chunk encodeSeamsChunk(const Seams& s) {
    ByteWriter w;
    w.write<uint64_t>(s.sourceHash);
    w.write<uint32_t>(static_cast<uint32_t>(s.elements.size()));
    w.write<uint32_t>(static_cast<uint32_t>(s.uvs.size()));
    for (const auto& e : s.elements) {
        for (const auto& uv : e.own) {
            w.write<float>(uv.x);
            w.write<float>(uv.y);
        }
        for (int k = 0; k < 4; ++k) {
            w.write<uint32_t>(e.cornerFirst[k]);
            w.write<uint32_t>(e.cornerCount[k]);
        }
        for (int k = 0; k < 4; ++k) {
            w.write<uint32_t>(e.edgeFirst[k]);
            w.write<uint32_t>(e.edgeSides[k]);
        }
    }
    for (const auto& uv : s.uvs) {
        w.write<float>(uv.x);
        w.write<float>(uv.y);
    }
    return {kSeamsChunk, 1, w.take()};
}

Seams decodeSeamsChunk(const Chunk& chunk, uint32_t expectedElements, uint64_t expectedHash) {
    if (chunk.version > 1)
        throwBadInput("chunk SEAM version " + std::to_string(chunk.version) +
                      " is newer than this limn reads (1); upgrade limn");
    ByteReader r(chunk.payload, "chunk SEAM");
    Seams s;
    s.sourceHash = r.read<uint64_t>();
    if (expectedHash && s.sourceHash != expectedHash)
        throwBadInput("the seams were made for other tables or UVs; re-run limn-seams", "chunk SEAM");
    uint32_t E = r.read<uint32_t>(), U = r.read<uint32_t>();
    if (expectedElements != kNone && E != expectedElements)
        r.fail("seams for " + std::to_string(E) + " elements, the tables have " + std::to_string(expectedElements));
    if (E > r.remaining() / 96) r.fail("element count " + std::to_string(E) + " is too large");
    s.elements.resize(E);
    for (auto& e : s.elements) {
        for (auto& uv : e.own) {
            uv.x = r.read<float>();
            uv.y = r.read<float>();
        }
        for (int k = 0; k < 4; ++k) {
            e.cornerFirst[k] = r.read<uint32_t>();
            e.cornerCount[k] = r.read<uint32_t>();
        }
        for (int k = 0; k < 4; ++k) {
            e.edgeFirst[k] = r.read<uint32_t>();
            e.edgeSides[k] = r.read<uint32_t>();
        }
    }
    auto values = r.readArray<float>(uint64_t(U) * 2, "UVs");
    if (!r.atEnd()) r.fail(std::to_string(r.remaining()) + " unexpected bytes after the last field");
    s.uvs.resize(U);
    for (uint32_t i = 0; i < U; ++i) {
        s.uvs[i] = {values[2 * i], values[2 * i + 1]};
        if (!std::isfinite(s.uvs[i].x) || !std::isfinite(s.uvs[i].y)) r.fail("UV " + std::to_string(i) + " is not finite");
    }
    for (uint32_t i = 0; i < E; ++i) {
        const auto& e = s.elements[i];
        for (int k = 0; k < 4; ++k) {
            if (!std::isfinite(e.own[k].x) || !std::isfinite(e.own[k].y))
                r.fail("element " + std::to_string(i) + " has a non-finite UV");
            if (e.cornerCount[k] < 1 || e.cornerCount[k] > kMaxPointUVs || e.cornerFirst[k] > U ||
                e.cornerCount[k] > U - e.cornerFirst[k])
                r.fail("element " + std::to_string(i) + " corner " + std::to_string(k) + " UV range is out of bounds");
            if (e.edgeSides[k] < 1 || e.edgeSides[k] > 2 || e.edgeFirst[k] > U ||
                2 * e.edgeSides[k] > U - e.edgeFirst[k])
                r.fail("element " + std::to_string(i) + " edge " + std::to_string(k) + " UV range is out of bounds");
        }
    }
    return s;
}

} // namespace limn
