#include "blend/blend_chunk.h"

#include "base/bytes.h"
#include "base/error.h"
#include "mesh/mesh_chunks.h"

#include <cmath>
#include <numbers>
#include <string>

namespace limn::blend {

uint64_t meshPayloadHash(const Container& container) {
    const Chunk* mesh = container.find(kMeshChunk);
    if (!mesh) throwBadInput("the container has no MESH chunk (was it made by limn-classify?)");
    return hashBytes(mesh->payload);
}

Chunk encodeBlendChunk(const BlendSurface& s, uint64_t meshHash) {
    ByteWriter w;
    w.write<uint8_t>(static_cast<uint8_t>(s.weights));
    w.write<uint8_t>(static_cast<uint8_t>(s.chartType));
    w.write<uint16_t>(0);
    w.write<uint32_t>(static_cast<uint32_t>(s.vertices.size()));
    w.write<uint32_t>(static_cast<uint32_t>(s.faces.size()));
    w.write<uint32_t>(0);
    w.write<uint64_t>(meshHash);
    for (const BlendVertex& v : s.vertices) {
        w.write<uint32_t>(v.chart.k);
        w.write<uint32_t>(static_cast<uint32_t>(v.chart.kind));
        w.write<float>(static_cast<float>(v.chart.theta));
        w.write<float>(static_cast<float>(v.chart.p));
        w.write<float>(static_cast<float>(v.chart.q));
        for (int c = 0; c < 3; ++c) // component-major: one 3×3 block per coordinate (A.9)
            for (const glm::dvec3& cab : v.coef) w.write<float>(static_cast<float>(cab[c]));
    }
    for (const BlendFace& f : s.faces) {
        for (uint32_t id : f.vertex) w.write<uint32_t>(id);
        for (uint32_t j : f.ring) w.write<uint32_t>(j);
    }
    return {kBlendChunk, kBlendChunkVersion, w.take()};
}

namespace {

bool near(double a, double b) { return std::abs(a - b) <= 1e-6 * std::abs(b); }

void checkChart(ByteReader& r, uint32_t v, const Chart& c) {
    const double pi = std::numbers::pi;
    std::string what = "vertex " + std::to_string(v);
    if (!std::isfinite(c.theta) || !std::isfinite(c.p) || !std::isfinite(c.q))
        r.fail(what + ": chart parameters are not finite");
    if (c.k == 0) return; // used by no face; never evaluated
    double theta = 0;
    switch (c.kind) {
    case VertexKind::Interior: theta = 2 * pi; break;
    case VertexKind::Boundary: theta = pi; break;
    case VertexKind::Corner: theta = pi / 2; break;
    }
    if ((c.kind == VertexKind::Corner) != (c.k == 1))
        r.fail(what + ": a corner chart has exactly one face, other charts at least two (k = " +
               std::to_string(c.k) + ")");
    if (!near(c.theta, theta)) r.fail(what + ": chart angle does not match its kind");
    if (!near(c.q, 2 * theta / (pi * c.k))) r.fail(what + ": q is not 2Θ/(πk)");
    if (!(c.p > 0 && c.p <= 4)) r.fail(what + ": p is out of range (0, 4]");
}

} // namespace

DecodedBlend decodeBlendChunk(const Chunk& chunk) {
    if (chunk.version > kBlendChunkVersion)
        throwBadInput("chunk BLND version " + std::to_string(chunk.version) +
                      " is newer than this limn reads (1); upgrade limn");
    ByteReader r(chunk.payload, "chunk BLND");
    DecodedBlend out;
    BlendSurface& s = out.surface;
    uint8_t weights = r.read<uint8_t>(), chartType = r.read<uint8_t>();
    if (weights > 1) r.fail("weights kind " + std::to_string(weights) + " is out of range");
    if (chartType > 2) r.fail("chart type " + std::to_string(chartType) + " is out of range");
    s.weights = static_cast<WeightKind>(weights);
    s.chartType = static_cast<ChartType>(chartType);
    if (r.read<uint16_t>() != 0) r.fail("reserved field is not zero");
    uint32_t V = r.read<uint32_t>(), F = r.read<uint32_t>();
    if (r.read<uint32_t>() != 0) r.fail("reserved field is not zero");
    out.meshHash = r.read<uint64_t>();
    if (V > r.remaining() / kBlendVertexBytes)
        r.fail(std::to_string(V) + " vertex records do not fit in the " +
               std::to_string(r.remaining()) + " bytes left");
    if (r.remaining() - uint64_t(V) * kBlendVertexBytes != uint64_t(F) * kBlendFaceBytes)
        r.fail("payload length is not 24 + 128·V + 32·F for V = " + std::to_string(V) +
               ", F = " + std::to_string(F));
    s.vertices.resize(V);
    for (uint32_t v = 0; v < V; ++v) {
        BlendVertex& bv = s.vertices[v];
        bv.chart.k = r.read<uint32_t>();
        uint32_t kind = r.read<uint32_t>();
        if (kind > 2) r.fail("vertex " + std::to_string(v) + ": chart kind " +
                             std::to_string(kind) + " is out of range");
        bv.chart.kind = static_cast<VertexKind>(kind);
        bv.chart.theta = r.read<float>();
        bv.chart.p = r.read<float>();
        bv.chart.q = r.read<float>();
        checkChart(r, v, bv.chart);
        for (int c = 0; c < 3; ++c)
            for (glm::dvec3& cab : bv.coef) {
                float value = r.read<float>();
                if (!std::isfinite(value))
                    r.fail("vertex " + std::to_string(v) + ": coefficient is not finite");
                cab[c] = value;
            }
    }
    // Every (face, corner) naming vertex v carries a distinct ring index below k_v, and together
    // they use all k_v of them (A.2): the per-vertex fans are then permutations, as built.
    std::vector<uint64_t> first(size_t(V) + 1, 0);
    for (uint32_t v = 0; v < V; ++v) first[v + 1] = first[v] + s.vertices[v].chart.k;
    if (first[V] != 4ull * F)
        r.fail("the vertices' k add up to " + std::to_string(first[V]) + ", but " +
               std::to_string(F) + " quads have " + std::to_string(4ull * F) + " corners");
    std::vector<uint8_t> seen(first[V], 0);
    s.faces.resize(F);
    for (uint32_t f = 0; f < F; ++f) {
        BlendFace& bf = s.faces[f];
        for (auto& id : bf.vertex) id = r.read<uint32_t>();
        for (auto& j : bf.ring) j = r.read<uint32_t>();
        std::string what = "face " + std::to_string(f);
        for (uint32_t i = 0; i < 4; ++i) {
            if (bf.vertex[i] >= V)
                r.fail(what + " refers to vertex " + std::to_string(bf.vertex[i]) +
                       " but there are only " + std::to_string(V));
            for (uint32_t i2 = 0; i2 < i; ++i2)
                if (bf.vertex[i2] == bf.vertex[i])
                    r.fail(what + " uses vertex " + std::to_string(bf.vertex[i]) + " twice");
            const uint32_t k = s.vertices[bf.vertex[i]].chart.k;
            if (bf.ring[i] >= k)
                r.fail(what + " corner " + std::to_string(i) + ": ring index " +
                       std::to_string(bf.ring[i]) + " is not below k = " + std::to_string(k));
            uint8_t& mark = seen[first[bf.vertex[i]] + bf.ring[i]];
            if (mark)
                r.fail(what + " corner " + std::to_string(i) + ": ring index " +
                       std::to_string(bf.ring[i]) + " of vertex " +
                       std::to_string(bf.vertex[i]) + " is used twice");
            mark = 1;
        }
    }
    if (!r.atEnd()) r.fail(std::to_string(r.remaining()) + " unexpected bytes after the last field");
    return out;
}

BlendSurface loadBlendSurface(const Container& container, const Mesh& mesh) {
    const Chunk* chunk = container.find(kBlendChunk);
    if (!chunk) throwBadInput("the container has no BLND chunk (run limn-blend first)");
    DecodedBlend d = decodeBlendChunk(*chunk);
    if (d.surface.vertices.size() != mesh.vertexCount() || d.surface.faces.size() != mesh.faceCount())
        throwBadInput("BLND describes " + std::to_string(d.surface.vertices.size()) +
                          " vertices and " + std::to_string(d.surface.faces.size()) +
                          " faces, the mesh has " + std::to_string(mesh.vertexCount()) + " and " +
                          std::to_string(mesh.faceCount()),
                      "chunk BLND");
    if (d.meshHash != meshPayloadHash(container))
        throwBadInput("BLND was built for a different MESH (hash differs); run limn-blend again",
                      "chunk BLND");
    for (uint32_t f = 0; f < mesh.faceCount(); ++f) {
        auto vs = mesh.face(f);
        const auto& bf = d.surface.faces[f];
        if (vs.size() != 4 || vs[0] != bf.vertex[0] || vs[1] != bf.vertex[1] ||
            vs[2] != bf.vertex[2] || vs[3] != bf.vertex[3])
            throwBadInput("face " + std::to_string(f) + " has other corners than in MESH",
                          "chunk BLND");
    }
    return std::move(d.surface);
}

} // namespace limn::blend
