#include "topology/classification.h"

#include "base/bytes.h"
#include "base/error.h"
#include "base/io.h"
#include "mesh/import.h"
#include "mesh/mesh_chunks.h"

namespace limn {

Classification classifyMesh(const Mesh& mesh, const Topology& topo, const SchemeOptions& options,
                            Warnings& warnings) {
    Classification c;
    c.options = options;
    const uint32_t V = topo.vertexCount(), F = topo.faceCount();
    Sharpness sharp = baseSharpness(topo, mesh.tags, options.boundary, warnings);
    std::vector<uint8_t> hole(F, 0);
    for (uint32_t f : mesh.tags.holes) hole[f] = 1;
    Regularity reg = analyzeRegularity(topo, sharp.edge, sharp.vertex, sharp.faceNoLimit);

    c.vertexValence.resize(V);
    c.vertexFlags.assign(V, 0);
    for (uint32_t v = 0; v < V; ++v) {
        uint32_t flags = 0;
        c.vertexValence[v] = topo.vertexEdgeCount(v);
        if (topo.vertexIsIsolated(v)) {
            c.vertexFlags[v] = kVertexIsolated;
            continue;
        }
        if (topo.vertexIsBoundary(v)) flags |= kVertexBoundary;
        if (topo.vertexIsNonManifold(v)) flags |= kVertexNonManifold;
        switch (vertexRule(topo, sharp, v)) {
        case VertexRule::Corner:
            flags |= kVertexCorner;
            break;
        case VertexRule::Crease:
            flags |= kVertexCrease;
            break;
        case VertexRule::Dart:
            flags |= kVertexDart;
            break;
        case VertexRule::Smooth:
            break;
        }
        bool semi = sharp.vertex[v] > 0 && sharp.vertex[v] < kInfiniteSharpness;
        for (uint32_t h : topo.vertexOutgoing(v)) {
            float s = sharp.edge[topo.edge(h)];
            if (s > 0 && s < kInfiniteSharpness) semi = true;
            if (topo.faceSize(topo.face(h)) != 4) flags |= kVertexNonQuad;
        }
        if (semi) flags |= kVertexSemiSharp;
        if (!reg.vertexRegular[v] || sharp.vertexOnUnsharpBoundary[v])
            flags |= kVertexExtraordinary;
        c.vertexFlags[v] = flags;
    }

    c.faceFlags.assign(F, 0);
    for (uint32_t f = 0; f < F; ++f) {
        uint32_t flags = 0;
        if (reg.faceRegular[f]) flags |= kFaceRegular;
        if (hole[f]) flags |= kFaceHole;
        if (sharp.faceNoLimit[f]) flags |= kFaceNoLimit;
        if (topo.faceSize(f) != 4) flags |= kFaceNonQuad;
        for (uint32_t h = topo.faceHalfedge(f); h < topo.faceHalfedge(f) + topo.faceSize(f); ++h) {
            if (topo.edgeIsBoundary(topo.edge(h))) flags |= kFaceBoundary;
            if (topo.edgeIsNonManifold(topo.edge(h)) || topo.vertexIsNonManifold(topo.vertex(h)))
                flags |= kFaceNonManifold;
        }
        c.faceFlags[f] = flags;
    }

    c.edges = topo.edgeCount();
    c.boundaryEdges = topo.boundaryEdgeCount();
    c.nonManifoldEdges = topo.nonManifoldEdgeCount();
    if (mesh.hasUVs()) {
        // A seam edge: an interior manifold edge whose two faces give either endpoint different
        // UV values. A seam vertex: a vertex with more than one UV value among its corners.
        for (uint32_t e = 0; e < topo.edgeCount(); ++e) {
            uint32_t h = topo.edgeHalfedge(e), t = topo.twin(h);
            if (t == kNone) continue;
            const auto& uv = mesh.uvs;
            const auto& ix = mesh.uvIndices;
            if (uv[ix[h]] != uv[ix[topo.next(t)]] || uv[ix[topo.next(h)]] != uv[ix[t]])
                ++c.uvSeamEdges;
        }
        for (uint32_t v = 0; v < V; ++v) {
            auto out = topo.vertexOutgoing(v);
            for (uint32_t h : out)
                if (mesh.uvs[mesh.uvIndices[h]] != mesh.uvs[mesh.uvIndices[out[0]]]) {
                    c.vertexFlags[v] |= kVertexUVSeam;
                    break;
                }
        }
    }
    return c;
}

Chunk encodeClassificationChunk(const Classification& c) {
    ByteWriter w;
    w.write<uint8_t>(static_cast<uint8_t>(c.options.boundary));
    w.write<uint8_t>(static_cast<uint8_t>(c.options.creaseMethod));
    w.write<uint8_t>(static_cast<uint8_t>(c.options.triangles));
    w.write<uint8_t>(static_cast<uint8_t>(c.options.fvar));
    w.write<uint32_t>(static_cast<uint32_t>(c.vertexFlags.size()));
    w.write<uint32_t>(static_cast<uint32_t>(c.faceFlags.size()));
    w.write<uint32_t>(c.edges);
    w.write<uint32_t>(c.boundaryEdges);
    w.write<uint32_t>(c.nonManifoldEdges);
    w.write<uint32_t>(c.uvSeamEdges);
    w.write<uint32_t>(0);
    w.writeArray(c.vertexValence);
    w.writeArray(c.vertexFlags);
    w.writeArray(c.faceFlags);
    return {kClassificationChunk, 1, w.take()};
}

Classification decodeClassificationChunk(const Chunk& chunk, const Mesh& mesh) {
    if (chunk.version > 1)
        throwBadInput("chunk CLSF version " + std::to_string(chunk.version) +
                      " is newer than this limn reads (1); upgrade limn");
    ByteReader r(chunk.payload, "chunk CLSF");
    Classification c;
    uint8_t b = r.read<uint8_t>(), m = r.read<uint8_t>(), t = r.read<uint8_t>(),
            f = r.read<uint8_t>();
    if (b > 2 || m > 1 || t > 1 || f > 5) r.fail("scheme option out of range");
    c.options = {static_cast<BoundaryRule>(b), static_cast<CreaseMethod>(m),
                 static_cast<TriangleSubdivision>(t), static_cast<FVarRule>(f)};
    uint32_t V = r.read<uint32_t>(), F = r.read<uint32_t>();
    if (V != mesh.vertexCount() || F != mesh.faceCount())
        r.fail("classification is for " + std::to_string(V) + " vertices and " + std::to_string(F) +
               " faces, the mesh has " + std::to_string(mesh.vertexCount()) + " and " +
               std::to_string(mesh.faceCount()));
    c.edges = r.read<uint32_t>();
    c.boundaryEdges = r.read<uint32_t>();
    c.nonManifoldEdges = r.read<uint32_t>();
    c.uvSeamEdges = r.read<uint32_t>();
    if (r.read<uint32_t>() != 0) r.fail("reserved field is not zero");
    c.vertexValence = r.readArray<uint32_t>(V, "vertex valences");
    c.vertexFlags = r.readArray<uint32_t>(V, "vertex flags");
    c.faceFlags = r.readArray<uint32_t>(F, "face flags");
    if (!r.atEnd())
        r.fail(std::to_string(r.remaining()) + " unexpected bytes after the last field");
    return c;
}

Container loadOrClassify(const std::string& path, Warnings& warnings,
                         std::vector<std::string>* filesRead) {
    const auto bytes = readInput(path);
    if (looksLikeContainer(bytes)) {
        try {
            return parseContainer(bytes);
        } catch (Error& e) {
            e.setFile(displayName(path));
            throw;
        }
    }
    Mesh mesh = importMesh(path, bytes, warnings, filesRead);
    try {
        const SchemeOptions options = resolveSchemeOptions(mesh.tags, {});
        Topology topo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets,
                      mesh.faceVertices);
        Classification c = classifyMesh(mesh, topo, options, warnings);
        Container container;
        storeMesh(container, mesh);
        container.set(encodeClassificationChunk(c));
        return container;
    } catch (Error& e) {
        e.setFile(displayName(path));
        throw;
    }
}

} // namespace limn
