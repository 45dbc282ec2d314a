// How far the surface limn draws is from OpenSubdiv's limit surface: per mesh, the
// tables' size and approximate limit points, and at every vertex of the fixed tessellation (the
// CPU reference of what limn-render draws, tess/tessellation.h) the position error (of the
// bounding-box diagonal) and normal angle against OpenSubdiv's adaptive patches at isolation 10
// with Gregory end caps (tests/support/osd_oracle.h); next to it, how far OpenSubdiv's own
// patches at isolation `depth` are from its isolation-10 surface at the same points. Normals are
// taken as the render test takes them (a hundred-thousandth of the element inside), and smooth
// corners' normals are left out (OpenSubdiv's end caps freeze them, tests/subdiv SmoothCorner).
// Prints one JSON object per mesh on stdout and a table on stderr.
// Usage: bench_accuracy [--depth N] [--uniform] [--osd-isolation L] [--reference-isolation R]
//        [-v: list the approximate limit points] MESH...
//        bench_accuracy --ply DRAWN.ply MESH: what limn-render --mesh-out drew (any tessellation,
//        the view-adaptive one included): every vertex, and the centroid of every triangle whose
//        corners share a ptex face (at the interpolated (ptex, u, v)), against isolation 10.
//        bench_accuracy [--depth N] --at PTEX U V MESH: limn's CPU evaluation of every element
//        holding that point (double: what the GPU should draw) against OpenSubdiv's limit there,
//        and the same evaluation from table vertices computed as the GPU computes them (float).
#include "base/error.h"
#include "drawn_ply.h"
#include "mesh/import.h"
#include "osd_oracle.h"
#include "render/gpu_origin.h"
#include "subdiv/evaluate.h"
#include "subdiv/tables.h"
#include "subdiv/tables_chunk.h"
#include "tess/tessellation.h"
#include "topology/features.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace limn;

namespace {

double angleDeg(glm::dvec3 a, glm::dvec3 b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) * 180 /
           M_PI;
}

struct Worst {
    double value = 0;
    std::string where;
    void update(double v, const std::string& w) {
        if (v > value) value = v, where = w;
    }
};

std::string readAll(const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw std::runtime_error("cannot read " + path);
    std::string out;
    char buf[1 << 16];
    for (size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) out.append(buf, n);
    std::fclose(f);
    return out;
}

// The --ply mode: a drawn mesh against OpenSubdiv's limit.
int comparePly(const std::string& plyPath, const std::string& meshPath, int refIso) {
    Warnings w;
    Mesh mesh = importMeshFile(meshPath, w);
    SchemeOptions so = resolveSchemeOptions(mesh.tags, {});
    const test::Drawn d = test::parsePly(readAll(plyPath));
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const double diag = glm::length(hi - lo);
    test::OsdLimitSurface ref(mesh, so, refIso);
    auto smooth = test::smoothCorners(mesh, so);
    // Per vertex a point just inside one of its triangles (of its ptex face): picks the side of
    // a crease as the drawn element did.
    std::vector<glm::dvec2> inside(d.vertices.size(), glm::dvec2(-1));
    auto uvOf = [&](int32_t i) { return glm::dvec2(d.vertices[i].uv[0], d.vertices[i].uv[1]); };
    for (const auto& t : d.triangles) {
        const auto &a = d.vertices[t[0]], &b = d.vertices[t[1]], &c = d.vertices[t[2]];
        if (a.ptex != b.ptex || a.ptex != c.ptex) continue;
        const glm::dvec2 m = (uvOf(t[0]) + uvOf(t[1]) + uvOf(t[2])) / 3.0;
        for (int k = 0; k < 3; ++k)
            if (inside[t[k]].x < 0) inside[t[k]] = uvOf(t[k]) + (m - uvOf(t[k])) * 1e-5;
    }
    Worst dP, dN, tP;
    size_t off = 0, offN = 0, flipped = 0, compared = 0, tris = 0, triOff = 0;
    size_t flagged = 0, offUnflagged = 0; // the PLY's `approximate` property, when it has one
    for (size_t i = 0; i < d.vertices.size(); ++i) {
        const auto& v = d.vertices[i];
        const glm::dvec2 in = inside[i].x < 0 ? uvOf(int32_t(i)) : inside[i];
        glm::dvec3 rp, rn;
        if (!ref.evaluate(v.ptex, v.uv[0], v.uv[1], in.x, in.y, rp, rn)) continue;
        char where[120];
        std::snprintf(where, sizeof where, "ptex %d (%.6g, %.6g)", v.ptex, v.uv[0], v.uv[1]);
        const double e = glm::length(glm::dvec3(v.p[0], v.p[1], v.p[2]) - rp) / diag;
        dP.update(e, where);
        off += e > 1e-5;
        flagged += v.approximate != 0;
        offUnflagged += e > 1e-5 && !v.approximate;
        const int bv = test::baseVertexAt(mesh, uint32_t(v.ptex), v.uv[0], v.uv[1]);
        const double a = angleDeg(glm::dvec3(v.n[0], v.n[1], v.n[2]), rn);
        // Flips count like the normal error, outside the smooth corners left out above.
        if (!(bv >= 0 && smooth[bv])) dN.update(a, where), offN += a > 0.5, flipped += a > 90;
        ++compared;
    }
    for (const auto& t : d.triangles) {
        const auto &a = d.vertices[t[0]], &b = d.vertices[t[1]], &c = d.vertices[t[2]];
        if (a.ptex != b.ptex || a.ptex != c.ptex) continue;
        const glm::dvec2 m = (uvOf(t[0]) + uvOf(t[1]) + uvOf(t[2])) / 3.0;
        glm::dvec3 rp, rn;
        if (!ref.evaluate(a.ptex, m.x, m.y, rp, rn)) continue;
        const glm::dvec3 p = (glm::dvec3(a.p[0], a.p[1], a.p[2]) + glm::dvec3(b.p[0], b.p[1], b.p[2]) +
                              glm::dvec3(c.p[0], c.p[1], c.p[2])) / 3.0;
        char where[120];
        std::snprintf(where, sizeof where, "ptex %d (%.6g, %.6g)", a.ptex, m.x, m.y);
        const double e = glm::length(p - rp) / diag;
        tP.update(e, where);
        triOff += e > 1e-5;
        ++tris;
    }
    std::string name = meshPath.substr(meshPath.find_last_of('/') + 1);
    std::printf("{\"mesh\":\"%s\",\"ply\":\"%s\",\"vertices\":%zu,\"vertices_off\":%zu,"
                "\"max_position_error\":%.3e,\"max_normal_degrees\":%.4g,\"normals_off\":%zu,"
                "\"flipped_normals\":%zu,\"triangles\":%zu,\"centroids_off\":%zu,"
                "\"max_centroid_error\":%.3e,\"worst_position_at\":\"%s\",\"worst_normal_at\":\"%s\","
                "\"worst_centroid_at\":\"%s\",\"vertices_flagged_approximate\":%zu,"
                "\"vertices_off_not_flagged\":%zu}\n",
                name.c_str(), plyPath.c_str(), compared, off, dP.value, dN.value, offN, flipped, tris,
                triOff, tP.value, dP.where.c_str(), dN.where.c_str(), tP.where.c_str(), flagged, offUnflagged);
    std::fprintf(stderr, "%-28s %9zu %8zu %9.2e %8.3g %6zu %9zu %8zu %9.2e\n",
                 name.substr(0, name.find('.')).c_str(), compared, off, dP.value, dN.value, flipped, tris,
                 triOff, tP.value);
    return 0;
}

// The table vertices as the GPU's subdivision passes compute them (subdiv_face_points.comp,
// subdiv_stencils.comp): float, relative to renderOrigin, each row summed in the shaders' order
// (rows of more than 64 entries relative to their first point), levels 1..`floatLevels` in float
// and the ones below in double from those (all levels: what the GPU has; through level N only:
// what an evaluation of the deeper levels from level N in double, or in a frame local to the
// face, would have). Returned in the model's coordinates.
std::vector<glm::dvec3> gpuFloatVertices(const Tables& t, const Mesh& mesh, uint32_t floatLevels) {
    const glm::dvec3 origin = render::renderOrigin(mesh);
    std::vector<glm::vec3> F(t.totalVertices);
    std::vector<glm::dvec3> D(t.totalVertices);
    for (size_t i = 0; i < t.levels[0].count(); ++i) F[i] = glm::vec3(mesh.positions[i] - origin), D[i] = F[i];
    for (uint32_t l = 1; l < t.levels.size(); ++l) {
        const bool inFloat = l <= floatLevels;
        uint32_t out = t.levels[l].first;
        const StencilTable& faces = t.facePoints[l - 1];
        for (size_t r = 0; r < faces.rows(); ++r, ++out) {
            glm::vec3 f(0.0f);
            glm::dvec3 d(0.0);
            for (uint32_t i = faces.start[r]; i < faces.start[r + 1]; ++i) f += F[faces.indices[i]], d += D[faces.indices[i]];
            const uint32_t n = faces.start[r + 1] - faces.start[r];
            D[out] = inFloat ? glm::dvec3(f / float(n)) : d / double(n);
            F[out] = glm::vec3(D[out]);
        }
        for (const StencilTable* rows : {&t.edgePoints[l - 1], &t.vertexPoints[l - 1]})
            for (size_t r = 0; r < rows->rows(); ++r, ++out) {
                const uint32_t b = rows->start[r], e = rows->start[r + 1];
                const glm::vec3 o = e - b > 64 ? F[rows->indices[b]] : glm::vec3(0.0f);
                glm::vec3 f(0.0f);
                glm::dvec3 d(0.0);
                for (uint32_t i = b; i < e; ++i)
                    f += rows->weights[i] * (F[rows->indices[i]] - o), d += double(rows->weights[i]) * D[rows->indices[i]];
                D[out] = inFloat ? glm::dvec3(f + o) : d;
                F[out] = glm::vec3(D[out]);
            }
    }
    for (glm::dvec3& p : D) p += origin;
    return D;
}

// The --at mode: which side is off at one drawn point. limn's CPU evaluation (double, the
// reference of what the GPU draws) of the element holding (ptex, u, v), next to OpenSubdiv's
// limit there; the normal is taken a hundred-thousandth towards the element's centre, as above.
int compareAt(const std::string& meshPath, int depth, int refIso, int ptex, double u, double v) {
    Warnings w;
    Mesh mesh = importMeshFile(meshPath, w);
    SchemeOptions so = resolveSchemeOptions(mesh.tags, {});
    TablesOptions to;
    to.depth = depth;
    const Tables t = buildTables(mesh, so, to, w);
    auto V = evaluateVertices(t, mesh.positions);
    auto L = evaluateLimitPoints(t, V);
    test::OsdLimitSurface ref(mesh, so, refIso);
    // The GPU's vertices (float through every level), and float through level N only.
    const auto VG = gpuFloatVertices(t, mesh, uint32_t(t.levels.size())), VN = gpuFloatVertices(t, mesh, uint32_t(depth));
    const auto LG = evaluateLimitPoints(t, VG), LN = evaluateLimitPoints(t, VN);
    const uint32_t P = uint32_t(t.patches.size());
    int found = 0;
    for (uint32_t e = 0; e < P + t.irregular.size(); ++e) {
        const bool patch = e < P;
        const uint32_t ep = patch ? t.patches[e].ptex : t.irregular[e - P].ptex;
        const double u0 = patch ? t.patches[e].u0 : t.irregular[e - P].u0;
        const double v0 = patch ? t.patches[e].v0 : t.irregular[e - P].v0;
        const double size = patch ? t.patches[e].size : t.irregular[e - P].size;
        if (int(ep) != ptex || u < u0 || u > u0 + size || v < v0 || v > v0 + size) continue;
        const double s = (u - u0) / size, tt = (v - v0) / size;
        bool exact = true;
        const SurfacePoint p = patch ? evaluatePatch(t.patches[e], V, s, tt)
                                     : evaluateIrregular(t, V, L, e - P, s, tt, &exact);
        const SurfacePoint g = patch ? evaluatePatch(t.patches[e], VG, s, tt)
                                     : evaluateIrregular(t, VG, LG, e - P, s, tt, nullptr);
        const SurfacePoint gn = patch ? evaluatePatch(t.patches[e], VN, s, tt)
                                      : evaluateIrregular(t, VN, LN, e - P, s, tt, nullptr);
        const double iu = u + (u0 + size / 2 - u) * 1e-5, iv = v + (v0 + size / 2 - v) * 1e-5;
        glm::dvec3 rp, rn;
        if (!ref.evaluate(ptex, u, v, iu, iv, rp, rn)) continue;
        std::printf("{\"element\":%u,\"kind\":\"%s\",\"level\":%d,\"s\":%.9g,\"t\":%.9g,"
                    "\"exact\":%s,\"limn_position\":[%.9g,%.9g,%.9g],\"limn_normal\":[%.9g,%.9g,%.9g],"
                    "\"osd_position\":[%.9g,%.9g,%.9g],\"osd_normal\":[%.9g,%.9g,%.9g],"
                    "\"distance\":%.3e,\"normal_degrees\":%.4g,\"du\":%.4g,\"dv\":%.4g,"
                    "\"du_dv_degrees\":%.6g,\"float_vertices_normal\":[%.7g,%.7g,%.7g],"
                    "\"float_vertices_normal_degrees\":%.4g,\"float_to_depth_normal_degrees\":%.4g}\n",
                    e, patch ? (t.patches[e].crease ? "crease patch" : "patch") : "irregular face",
                    patch ? int(t.patches[e].level) : -1, s, tt, exact ? "true" : "false",
                    p.position.x, p.position.y, p.position.z, p.normal.x, p.normal.y, p.normal.z, rp.x, rp.y,
                    rp.z, rn.x, rn.y, rn.z, glm::length(p.position - rp), angleDeg(p.normal, rn),
                    glm::length(p.du), glm::length(p.dv), angleDeg(p.du, p.dv), g.normal.x, g.normal.y, g.normal.z,
                    angleDeg(g.normal, rn), angleDeg(gn.normal, rn));
        ++found;
    }
    if (!found) std::fprintf(stderr, "bench_accuracy: no element holds ptex %d (%g, %g)\n", ptex, u, v);
    return found ? 0 : 1;
}

} // namespace

int main(int argc, char** argv) {
    int depth = 3;
    bool uniform = false;
    int osdIso = -1; // the isolation compared with the reference (default: depth)
    int refIso = 10; // the reference's isolation (OpenSubdiv's maximum)
    bool verbose = false;
    std::string ply;
    int atPtex = -1;
    double atU = 0, atV = 0;
    std::vector<std::string> meshes;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--depth") && i + 1 < argc)
            depth = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--osd-isolation") && i + 1 < argc)
            osdIso = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--reference-isolation") && i + 1 < argc)
            refIso = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--ply") && i + 1 < argc)
            ply = argv[++i];
        else if (!std::strcmp(argv[i], "--at") && i + 3 < argc)
            atPtex = std::atoi(argv[i + 1]), atU = std::atof(argv[i + 2]), atV = std::atof(argv[i + 3]), i += 3;
        else if (!std::strcmp(argv[i], "-v"))
            verbose = true;
        else if (!std::strcmp(argv[i], "--uniform"))
            uniform = true;
        else
            meshes.push_back(argv[i]);
    }
    // OpenSubdiv's patch parameters hold a patch's (u, v) index in 10 bits (Far::PatchParam), so
    // its patch tables locate points correctly only up to isolation 10: deeper, every point but a
    // ptex face's (0, 0) corner is looked up in the wrong patch.
    if (refIso < 1 || refIso > 10 || (osdIso != -1 && (osdIso < 1 || osdIso > 10)) || depth < 0 || depth > 10) {
        std::fprintf(stderr, "bench_accuracy: --reference-isolation and --osd-isolation take 1 to 10 "
                             "(OpenSubdiv's PatchParam holds 10 levels), --depth 0 to 10\n");
        return 2;
    }
    if (atPtex >= 0) {
        if (meshes.size() != 1) {
            std::fprintf(stderr, "bench_accuracy: --at needs exactly one MESH\n");
            return 2;
        }
        try {
            return compareAt(meshes[0], depth, refIso, atPtex, atU, atV);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "bench_accuracy: %s\n", e.what());
            return 1;
        }
    }
    if (!ply.empty()) {
        if (meshes.size() != 1) {
            std::fprintf(stderr, "bench_accuracy: --ply needs exactly one MESH\n");
            return 2;
        }
        std::fprintf(stderr, "%-28s %9s %8s %9s %8s %6s %9s %8s %9s\n", "mesh", "vertices", ">1e-5",
                     "max dP", "max dN", "flip", "triangles", ">1e-5", "centroid");
        try {
            return comparePly(ply, meshes[0], refIso);
        } catch (const std::exception& e) { // a missing or damaged file, a mesh limn refuses
            std::fprintf(stderr, "bench_accuracy: %s\n", e.what());
            return 1;
        }
    }
    std::fprintf(stderr, "%-28s %6s %7s %9s %8s %9s %9s %9s %8s %9s %8s\n", "mesh", "approx",
                 "limits", "bytes", "elements", "drawn", "limn dP", "limn dN", "flipped",
                 "osdL dP", "osdL dN");
    for (const std::string& path : meshes) {
        Warnings w;
        Mesh mesh;
        SchemeOptions so;
        TablesOptions to;
        to.depth = depth;
        to.uniform = uniform;
        Tables t;
        try {
            mesh = importMeshFile(path, w);
            so = resolveSchemeOptions(mesh.tags, {});
            t = buildTables(mesh, so, to, w);
        } catch (const Error& e) { // non-manifold and degenerate shapes: limn refuses them
            std::fprintf(stderr, "%s: %s\n", path.c_str(), e.what());
            continue;
        }
        const size_t bytes = encodeTablesChunk(t).payload.size();
        if (verbose) {
            std::vector<int> used(t.limitExact.size(), 0);
            for (const auto& q : t.irregular)
                for (uint32_t c : q.corner) ++used[c];
            for (size_t i = 0; i < used.size(); ++i)
                if (!t.limitExact[i])
                    std::fprintf(stderr, "  approximate limit point %zu (level-%u vertex %u): %d corners\n",
                                 i, t.depth, t.limitVertex[i] - t.levels[t.depth].first, used[i]);
        }
        auto V = evaluateVertices(t, mesh.positions);
        auto L = evaluateLimitPoints(t, V);
        Tessellation tess = buildTessellation(mesh, t, 64);
        auto drawn = evaluateTessellation(t, tess, V, L);
        glm::dvec3 lo(1e300), hi(-1e300);
        for (const auto& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
        const double diag = glm::length(hi - lo);
        test::OsdLimitSurface ref(mesh, so, refIso), same(mesh, so, osdIso >= 0 ? osdIso : std::max(depth, 1));
        auto smooth = test::smoothCorners(mesh, so);
        const uint32_t P = uint32_t(t.patches.size());
        Worst dP, dN, oP, oN;
        size_t flipped = 0, compared = 0;
        for (size_t i = 0; i < tess.vertices.size(); ++i) {
            const TessVertex& tv = tess.vertices[i];
            PtexPoint pp = ptexOf(t, tv);
            double u0, v0, size;
            if (tv.element < P)
                u0 = t.patches[tv.element].u0, v0 = t.patches[tv.element].v0,
                size = t.patches[tv.element].size;
            else
                u0 = t.irregular[tv.element - P].u0, v0 = t.irregular[tv.element - P].v0,
                size = t.irregular[tv.element - P].size;
            const double iu = pp.u + (u0 + size / 2 - pp.u) * 1e-5;
            const double iv = pp.v + (v0 + size / 2 - pp.v) * 1e-5;
            glm::dvec3 rp, rn, inside, sp, sn;
            if (!ref.evaluate(int(pp.ptex), pp.u, pp.v, iu, iv, rp, rn)) continue;
            ref.evaluate(int(pp.ptex), iu, iv, inside, rn);
            same.evaluate(int(pp.ptex), pp.u, pp.v, iu, iv, sp, sn);
            same.evaluate(int(pp.ptex), iu, iv, inside, sn);
            const int bv = test::baseVertexAt(mesh, pp.ptex, pp.u, pp.v);
            char where[160];
            std::snprintf(where, sizeof where, "ptex %u (%.6g, %.6g) %s%s", pp.ptex, pp.u, pp.v,
                          tv.element < P ? "patch" : "irregular corner",
                          bv >= 0 ? (" at base vertex " + std::to_string(bv)).c_str() : "");
            const bool smoothCorner = bv >= 0 && smooth[bv];
            if (tv.element >= P && (tv.s == 0 || tv.s == kTessParamOne) &&
                (tv.t == 0 || tv.t == kTessParamOne)) {
                const IrregularFace& q = t.irregular[tv.element - P];
                const int k = tv.s == 0 ? (tv.t == 0 ? 0 : 3) : (tv.t == 0 ? 1 : 2);
                if (!t.limitExact[q.corner[k]] && verbose)
                    std::fprintf(stderr, "  approximate limit point %u at %s: %.3g degrees\n",
                                 q.corner[k], where, angleDeg(drawn[i].normal, rn));
            }
            dP.update(glm::length(drawn[i].position - rp) / diag, where);
            oP.update(glm::length(sp - rp) / diag, where);
            const double a = angleDeg(drawn[i].normal, rn);
            if (!smoothCorner) {
                flipped += a > 90;
                dN.update(a, where);
                oN.update(angleDeg(sn, rn), where);
            }
            ++compared;
        }
        std::printf("{\"mesh\":\"%s\",\"depth\":%d,\"uniform\":%s,\"approximate_limit_points\":%u,"
                    "\"limit_points\":%zu,\"table_bytes\":%zu,\"table_vertices\":%u,\"patches\":%zu,"
                    "\"irregular_faces\":%zu,\"drawn_vertices\":%zu,\"max_position_error\":%.3e,"
                    "\"max_normal_degrees\":%.4g,\"flipped_normals\":%zu,"
                    "\"osd_same_isolation_position_error\":%.3e,"
                    "\"osd_same_isolation_normal_degrees\":%.4g,\"worst_position_at\":\"%s\","
                    "\"worst_normal_at\":\"%s\"}\n",
                    path.substr(path.find_last_of('/') + 1).c_str(), depth, uniform ? "true" : "false",
                    t.approximateLimitPoints, t.limitPosition.rows(), bytes, t.totalVertices,
                    t.patches.size(), t.irregular.size(), compared, dP.value, dN.value, flipped,
                    oP.value, oN.value, dP.where.c_str(), dN.where.c_str());
        std::fflush(stdout);
        std::string name = path.substr(path.find_last_of('/') + 1);
        std::fprintf(stderr, "%-28s %6u %7zu %9zu %8zu %9zu %9.2e %9.3g %8zu %9.2e %8.3g\n",
                     name.substr(0, name.find('.')).c_str(), t.approximateLimitPoints,
                     t.limitPosition.rows(), bytes, t.patches.size() + t.irregular.size(), compared,
                     dP.value, dN.value, flipped, oP.value, oN.value);
    }
    return 0;
}
