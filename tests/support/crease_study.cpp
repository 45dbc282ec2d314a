// studyCreaseBases (crease_study.h): the chains against the tables' own quadtrees.
#include "base/bytes.h"
#include "crease_study.h"
#include "crease_tree.h"
#include "subdiv/evaluate.h"
#include "subdiv/tables_build.h"
#include "subdiv/tables_chunk.h"
#include "subdiv/tables_surface_records.h"

#include <chrono>
#include <cmath>
#include <list>
#include <map>
#include <set>
#include <span>
#include <string>

namespace limn {

namespace {

// The positions of levels 0..n of the refinement, with evaluateVertices' arithmetic.
std::vector<std::vector<glm::dvec3>> levelPositions(const AdaptiveLevels& a, const Mesh& mesh, uint32_t n) {
    std::vector<std::vector<glm::dvec3>> P(n + 1);
    P[0] = mesh.positions;
    for (uint32_t l = 1; l <= n; ++l) {
        const Level& L = a.levels[l];
        const LevelStencils& st = a.stencils[l];
        std::vector<glm::dvec3>& out = P[l];
        out.assign(L.topo.vertexCount(), glm::dvec3(0.0));
        for (uint32_t i = 0; i < L.facePointCount; ++i) {
            glm::dvec3 sum(0.0);
            for (uint32_t k = st.faceStart[i]; k < st.faceStart[i + 1]; ++k) sum += P[l - 1][st.faceVertices[k]];
            out[i] = sum / double(st.faceStart[i + 1] - st.faceStart[i]);
        }
        auto rows = [&](uint32_t first, uint32_t count, const std::vector<uint32_t>& start,
                        const std::vector<StencilEntry>& e) {
            for (uint32_t i = 0; i < count; ++i) {
                glm::dvec3 sum(0.0);
                for (uint32_t k = start[i]; k < start[i + 1]; ++k)
                    sum += double(static_cast<float>(e[k].weight)) * (e[k].fromFacePoint ? out : P[l - 1])[e[k].index];
                out[first + i] = sum;
            }
        };
        rows(L.facePointCount, L.edgePointCount, st.edgeStart, st.edgeEntries);
        rows(L.facePointCount + L.edgePointCount, L.vertexPointCount, st.vertexStart, st.vertexEntries);
    }
    return P;
}

uint8_t rotateBits(uint8_t b, int c) { return uint8_t(((b << c) | (b >> (4 - c))) & 15); }

// Canonical control point (i, j) of a sub-patch is the real patch's (i', j') for a face whose
// feature corner is its ptex corner c: c quarter turns counter-clockwise.
void rotateIndex(int i, int j, int c, int& ri, int& rj) {
    ri = i, rj = j;
    for (int k = 0; k < c; ++k) {
        const int t = ri;
        ri = 3 - rj;
        rj = t;
    }
}

constexpr int kQuadrantAtCorner[4] = {0, 1, 3, 2}; // ptex corner -> quadrant code

struct Comparison {
    size_t points = 0, bitwise = 0, structure = 0;
    double maxDifference = 0;
    // A leaf end: its corners away from the feature corner, evaluated on the last band's
    // sub-patches that share them, against the quadtree leaf's limit points.
    size_t leafCorners = 0;
    double leafMaxDifference = 0;
};

// The chain run over one face's support values, against its quadtree from root `node`.
void compareChain(const CreaseChain& chain, std::span<const glm::dvec3> supportValues, int c, const Tables& t,
                  uint32_t node, std::span<const glm::dvec3> V, std::span<const LimitPoint> limits, double diagonal,
                  Comparison& out) {
    std::vector<glm::dvec3> input(supportValues.begin(), supportValues.end());
    auto compare = [&](const glm::dvec3& mine, const glm::dvec3& theirs) {
        ++out.points;
        if (mine == theirs) ++out.bitwise;
        for (int k = 0; k < 3; ++k) out.maxDifference = std::max(out.maxDifference, std::abs(mine[k] - theirs[k]) / diagonal);
    };
    auto comparePatch = [&](uint32_t code, const uint32_t* rows, const CreaseBandKind& kind,
                            const std::vector<glm::dvec3>& values) {
        if ((code & ~kNodeIndexMask) != kNodeSubPatch) {
            ++out.structure;
            return;
        }
        const Patch& p = t.subPatches[code & kNodeIndexMask];
        if (p.boundary != rotateBits(kind.boundary, c) || p.crease != rotateBits(kind.crease, c) ||
            p.sharpness != kind.sharpness) {
            ++out.structure;
            return;
        }
        glm::dvec3 P[4][4];
        gatherControlPoints(p, V, P);
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                if (rows[4 * j + i] == kNone) continue; // a phantom: the evaluator's, from the bits
                int ri = 0, rj = 0;
                rotateIndex(i, j, c, ri, rj);
                compare(values[rows[4 * j + i]], P[ri][rj]);
            }
    };
    for (size_t b = 0; b < chain.bands.size(); ++b) {
        const CreaseBand& band = chain.bands[b];
        const std::vector<glm::dvec3> values = runBandProgram(band.program, input);
        const std::array<uint32_t, 4>& codes = t.irregularNodes[node];
        static constexpr int kCanonicalCorner[3] = {1, 2, 3}; // quadrants 1, 3, 2
        for (size_t q = 0; q < 3; ++q)
            comparePatch(codes[size_t(kQuadrantAtCorner[(c + kCanonicalCorner[q]) % 4])], &band.program.controlRow[16 * q],
                         band.kind[q], values);
        const uint32_t centre = codes[size_t(kQuadrantAtCorner[c])];
        const uint32_t kind = centre & ~kNodeIndexMask, index = centre & kNodeIndexMask;
        if (b + 1 < chain.bands.size()) {
            if (kind != kNodeChild) {
                ++out.structure;
                return;
            }
            node = index;
            input.clear();
            for (uint32_t r : band.program.nextSupport) input.push_back(values[r]);
            continue;
        }
        if (chain.end == CreaseEnd::Regular) {
            comparePatch(centre, band.centreRow.data(), band.centreKind, values);
        } else if (chain.end == CreaseEnd::Smooth) {
            if (kind != kNodeBasis || t.irregularBases[t.smoothIrregular[index].basis].valence != chain.valence) {
                ++out.structure;
                return;
            }
            const uint32_t first = t.smoothIrregular[index].first;
            for (size_t i = 0; i < band.program.nextSupport.size(); ++i)
                compare(values[band.program.nextSupport[i]], V[t.smoothPoints[first + i]]);
        } else if (kind != kNodeLeaf) {
            ++out.structure;
        } else if (!limits.empty()) {
            const IrregularFace& leaf = t.irregularLeaves[index];
            static constexpr double kCornerU[4] = {0, 1, 1, 0}, kCornerV[4] = {0, 0, 1, 1};
            for (int k = 0; k < 4; ++k) {
                if (k == c) continue; // the feature corner: its limit point, as today
                const double u = leaf.u0 + kCornerU[k] * leaf.size, v = leaf.v0 + kCornerV[k] * leaf.size;
                for (uint32_t code : codes) {
                    if ((code & ~kNodeIndexMask) != kNodeSubPatch) continue;
                    const Patch& p = t.subPatches[code & kNodeIndexMask];
                    const double ps = (u - p.u0) / p.size, pt = (v - p.v0) / p.size;
                    if (ps < 0 || ps > 1 || pt < 0 || pt > 1) continue;
                    const glm::dvec3 x = evaluatePatch(p, V, ps, pt).position, y = limits[leaf.corner[k]].position;
                    ++out.leafCorners;
                    for (int a = 0; a < 3; ++a)
                        out.leafMaxDifference = std::max(out.leafMaxDifference, std::abs(x[a] - y[a]) / diagonal);
                }
            }
        }
    }
}

// A band program's bytes in TBLS version 5's program encoding, and three kinds (bits, sharpness).
size_t bandBytes(const CreaseBand& band) {
    BasisProgram p = band.program;
    for (uint32_t& x : p.controlRow) x = x == kNone ? 0 : x;
    ByteWriter w;
    writeProgram(w, p);
    return w.size() + 15;
}

// What a format would share a band's program by: its programKey (sharpness from 2 on clamped),
// and, for the last band of a chain, how the chain ends (a smooth face's next support comes in
// smoothSupport's order, a leaf or regular end has none).
std::vector<uint32_t> sharedKey(const CreaseChain& chain, const CreaseBand& band) {
    std::vector<uint32_t> key = programKey(band.key, kProgramSharpness);
    key.push_back(&band == &chain.bands.back() ? 1u + uint32_t(chain.end) : 0u);
    return key;
}

// A tree node's program with its control rows as next-support rows (a phantom as row 0), in
// TBLS version 5's program encoding, plus 20 bytes of child codes and kinds.
size_t treeNodeBytes(const CreaseTreeNode& n) {
    BasisProgram p = n.program;
    p.controlRow.fill(0);
    std::vector<uint32_t> rows;
    for (size_t q = 0; q < 4; ++q)
        if (n.child[q] == CreaseTreeChild::Patch)
            for (uint32_t r : n.rows[q]) rows.push_back(r == kNone ? 0 : r);
    rows.insert(rows.end(), p.nextSupport.begin(), p.nextSupport.end());
    p.nextSupport = rows;
    ByteWriter w;
    writeProgram(w, p);
    return w.size() + 20;
}

// Whether two tree nodes are the same function: the same children and, from the same
// (arbitrary) support values, their rows within 1e-12.
bool sameTreeNode(const CreaseTreeNode& x, const CreaseTreeNode& y) {
    if (x.support != y.support || x.child != y.child || x.nextCount != y.nextCount) return false;
    std::vector<glm::dvec3> in(x.support);
    for (size_t i = 0; i < in.size(); ++i)
        in[i] = glm::dvec3(std::sin(1.0 + double(i)), std::cos(3.0 * double(i)), 0.1 * double(i));
    const std::vector<glm::dvec3> px = runBandProgram(x.program, in), py = runBandProgram(y.program, in);
    auto same = [&](uint32_t r, uint32_t q) {
        if (r == kNone || q == kNone) return r == q;
        for (int k = 0; k < 3; ++k)
            if (std::abs(px[r][k] - py[q][k]) > 1e-12) return false;
        return true;
    };
    for (size_t q = 0; q < 4; ++q)
        if (x.child[q] == CreaseTreeChild::Patch)
            for (size_t i = 0; i < 16; ++i)
                if (!same(x.rows[q][i], y.rows[q][i])) return false;
    for (size_t i = 0; i < x.program.nextSupport.size(); ++i)
        if (!same(x.program.nextSupport[i], y.program.nextSupport[i])) return false;
    return true;
}

// A face's tree run over its support values, against its quadtree from root `node` (ptex
// frame: no turn).
void compareTree(const CreaseTree& tree, uint32_t at, std::vector<glm::dvec3> input, const Tables& t, uint32_t node,
                 std::span<const glm::dvec3> V, double diagonal, CreaseBasisStudy& s) {
    const CreaseTreeNode& n = tree.nodes[at];
    const std::vector<glm::dvec3> values = runBandProgram(n.program, input);
    const std::array<uint32_t, 4>& codes = t.irregularNodes[node];
    auto compare = [&](const glm::dvec3& mine, const glm::dvec3& theirs) {
        ++s.treePoints;
        if (mine == theirs) ++s.treeBitwise;
        for (int k = 0; k < 3; ++k)
            s.treeMaxDifference = std::max(s.treeMaxDifference, std::abs(mine[k] - theirs[k]) / diagonal);
    };
    for (size_t q = 0; q < 4; ++q) {
        const uint32_t kind = codes[q] & ~kNodeIndexMask, index = codes[q] & kNodeIndexMask;
        std::vector<glm::dvec3> next;
        for (uint32_t i = 0; i < n.nextCount[q]; ++i) next.push_back(values[n.program.nextSupport[n.nextFirst[q] + i]]);
        switch (n.child[q]) {
        case CreaseTreeChild::Patch: {
            if (kind != kNodeSubPatch) {
                ++s.treeStructure;
                break;
            }
            const Patch& p = t.subPatches[index];
            if (p.boundary != n.kind[q].boundary || p.crease != n.kind[q].crease || p.sharpness != n.kind[q].sharpness) {
                ++s.treeStructure;
                break;
            }
            glm::dvec3 P[4][4];
            gatherControlPoints(p, V, P);
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i)
                    if (n.rows[q][size_t(4 * j + i)] != kNone) compare(values[n.rows[q][size_t(4 * j + i)]], P[i][j]);
            break;
        }
        case CreaseTreeChild::Node:
            if (kind != kNodeChild)
                ++s.treeStructure;
            else
                compareTree(tree, n.next[q], std::move(next), t, index, V, diagonal, s);
            break;
        case CreaseTreeChild::Smooth:
            if (kind != kNodeBasis || t.irregularBases[t.smoothIrregular[index].basis].valence != n.next[q]) {
                ++s.treeStructure;
                break;
            }
            for (size_t i = 0; i < next.size(); ++i) compare(next[i], V[t.smoothPoints[t.smoothIrregular[index].first + i]]);
            break;
        case CreaseTreeChild::Leaf:
            s.treeStructure += kind != kNodeLeaf;
            break;
        }
    }
}

double seconds(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace

CreaseBasisStudy studyCreaseBases(const Mesh& mesh, const SchemeOptions& options, const TablesOptions& opts,
                                  Warnings& warnings) {
    checkTablesOptions(mesh, opts);
    Topology baseTopo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices);
    checkTablesTopology(baseTopo, opts);
    const AdaptiveLevels a = refineAdaptive(mesh, std::move(baseTopo), options, opts, warnings);
    const Tables t = assembleTables(mesh, options, opts, a);
    const std::vector<glm::dvec3> V = evaluateVertices(t, mesh.positions);
    const std::vector<LimitPoint> limits = evaluateLimitPoints(t, V);
    const uint32_t N = a.N;
    const std::vector<std::vector<glm::dvec3>> P = levelPositions(a, mesh, N);
    const Level& L = a.levels[N];
    const double diagonal = boundingBox(mesh).diagonal();
    CreaseBasisStudy s;
    std::map<std::vector<uint32_t>, CreaseChain> configurations;
    std::set<std::vector<uint32_t>> bandKeys;
    std::map<std::vector<uint32_t>, const CreaseBand*> shared;
    std::map<std::string, size_t> failures;
    std::vector<uint32_t> support, key;
    std::list<CreaseTree> trees; // every face's (their nodes outlive the maps)
    std::map<std::vector<uint32_t>, const CreaseTreeNode*> treeKeys;
    std::map<std::vector<uint32_t>, std::vector<const CreaseTreeNode*>> treeShared;
    std::vector<size_t> treeLevels;
    std::set<std::vector<uint32_t>> treeClasses, treeTurned;
    // Two bands' programs as functions: the points they give from the same (arbitrary) support
    // values. Rows come in each level's vertex order, which differs between the face's copy
    // (band 1) and its refined levels, so the arrays differ where the functions do not.
    double sharedMax = 0; // the largest difference between two bands' points where they differ
    double* difference = nullptr; // where sameProgram records the largest difference
    auto sameProgram = [&difference](const CreaseBand& x, const CreaseBand& y) { return sameBandFunction(x, y, difference); };
    uint32_t root = 0;
    Comparison own, deduped;
    for (uint32_t f = 0; f < L.topo.faceCount(); ++f) {
        if (!a.irregularSets[N][f]) continue;
        const uint32_t node = root++;
        const IrregularFace& face = t.irregular[node];
        for (int k = 0; k < 4; ++k) {
            const uint32_t v = L.topo.vertex(L.topo.faceHalfedge(f) + (L.frames[f].rotation + k) % 4);
            s.levelNMismatches += P[N][v] != V[t.limitVertex[face.corner[k]]];
        }
        if (node >= t.irregularNodes.size() || t.irregularNodes[node][0] == kNodeNone || smoothRoot(t.irregularNodes[node]))
            continue;
        ++s.quadtreeFaces;
        // The feature corner: the one whose chain exists (a face has at most one).
        const auto t0 = std::chrono::steady_clock::now();
        CreaseChain chain;
        int corner = -1;
        for (int c = 0; c < 4 && corner < 0; ++c)
            if (buildCreaseChain(L, f, c, a.K, options, opts, chain)) corner = c;
        const double built = seconds(t0);
        if (corner < 0) {
            // Why not: the corners that are extraordinary (e) or sharp (s), and the band at
            // which the best corner's chain met an irregular quadrant away from its corner.
            size_t best = 0;
            for (int c = 0; c < 4; ++c) {
                CreaseChain partial;
                buildCreaseChain(L, f, c, a.K, options, opts, partial);
                best = std::max(best, partial.bands.size() + 1);
            }
            int e = 0, sharp = 0;
            for (uint32_t v : L.topo.faceVertices(f)) {
                if (L.topo.vertexFaceCount(v) != (L.topo.vertexIsBoundary(v) ? 2u : 4u))
                    ++e;
                else {
                    bool x = L.vertexSharpness[v] != 0;
                    for (uint32_t h : L.topo.vertexOutgoing(v)) x |= L.edgeSharpness[L.topo.edge(h)] != 0;
                    sharp += x;
                }
            }
            ++failures["e" + std::to_string(e) + "s" + std::to_string(sharp) + "b" + std::to_string(best)];
            const auto t2 = std::chrono::steady_clock::now();
            trees.emplace_back();
            if (!buildCreaseTree(L, f, a.K, options, opts, trees.back())) {
                trees.pop_back();
                continue;
            }
            const CreaseTree& tree = trees.back();
            s.treeSeconds += seconds(t2);
            ++s.treeFaces;
            creaseSupport(L, f, 0, support, key);
            s.treeFaceBytes += 2 + 2 * support.size();
            // Nodes per level: the root's level N, then by depth (a node's children follow it).
            std::vector<uint32_t> depthOf(tree.nodes.size(), 0);
            for (size_t i = 0; i < tree.nodes.size(); ++i) {
                const CreaseTreeNode& n = tree.nodes[i];
                if (treeLevels.size() <= depthOf[i]) treeLevels.resize(depthOf[i] + 1, 0);
                ++treeLevels[depthOf[i]];
                for (size_t q = 0; q < 4; ++q)
                    if (n.child[q] == CreaseTreeChild::Node) depthOf[n.next[q]] = depthOf[i] + 1;
                // Its key with each sharpness as a class (0, below 1, from 1 on): a program
                // whose weights were functions of the sharpness below 1 would be per class.
                treeClasses.insert(programKey(programKey(n.key, kProgramSharpness), 0.5f));
                if (treeTurned.insert(n.turnedKey).second) s.treeTurnedProgramBytes += treeNodeBytes(n);
                auto [k, fresh] = treeKeys.try_emplace(n.key, &n);
                if (!fresh) continue;
                s.treeProgramBytes += treeNodeBytes(n);
                std::vector<uint32_t> clamped = programKey(n.key, kProgramSharpness);
                for (CreaseTreeChild c : n.child) clamped.push_back(uint32_t(c));
                std::vector<const CreaseTreeNode*>& alike = treeShared[clamped];
                bool found = false;
                for (const CreaseTreeNode* other : alike) found = found || sameTreeNode(*other, n);
                if (!found) {
                    alike.push_back(k->second);
                    s.treeSharedProgramBytes += treeNodeBytes(n);
                    ++s.treeSharedPrograms;
                }
            }
            s.treeNodes += tree.nodes.size();
            std::vector<glm::dvec3> values;
            for (uint32_t v : support) values.push_back(P[N][v]);
            compareTree(tree, 0, values, t, node, V, diagonal, s);
            continue;
        }
        ++s.qualifying;
        const auto t1 = std::chrono::steady_clock::now();
        creaseSupport(L, f, corner, support, key);
        auto [it, added] = configurations.try_emplace(key, CreaseChain{});
        s.keySeconds += seconds(t1);
        if (added) {
            s.chainSeconds += built;
            it->second = chain;
            const CreaseBand* previous = nullptr;
            for (const CreaseBand& band : it->second.bands) {
                s.bandKindBytes += 15;
                auto [at, first] = shared.try_emplace(sharedKey(it->second, band), &band);
                if (first) {
                    s.sharedProgramBytes += bandBytes(band) - 15;
                } else {
                    difference = &sharedMax;
                    s.sharedMismatches += !sameProgram(*at->second, band);
                    difference = nullptr;
                }
                s.repeatedBands += previous && sameProgram(*previous, band);
                previous = &band;
                if (!bandKeys.insert(band.key).second) continue;
                s.programBytes += bandBytes(band);
                for (const CreaseBandKind& k : band.kind)
                    ++(k.crease ? s.kindsCrease : k.boundary ? s.kindsBoundary : s.kindsBSpline);
            }
        }
        s.endLeaf += chain.end == CreaseEnd::Leaf;
        s.endSmooth += chain.end == CreaseEnd::Smooth;
        s.endRegular += chain.end == CreaseEnd::Regular;
        s.bands += chain.bands.size();
        s.maxBands = std::max(s.maxBands, chain.bands.size());
        s.supportPoints += support.size();
        s.faceBytes += 2 + 2 * support.size();
        std::vector<glm::dvec3> values;
        for (uint32_t v : support) values.push_back(P[N][v]);
        compareChain(chain, values, corner, t, node, V, limits, diagonal, own);
        compareChain(it->second, values, corner, t, node, V, {}, diagonal, deduped);
    }
    s.configurations = configurations.size();
    s.bandPrograms = bandKeys.size();
    for (const auto& [why, n] : failures) s.failures += (s.failures.empty() ? "" : " ") + why + ":" + std::to_string(n);
    s.sharedPrograms = shared.size();
    s.treeNodeKeys = treeKeys.size();
    s.treeNodeClasses = treeClasses.size();
    s.treeTurnedKeys = treeTurned.size();
    for (size_t n : treeLevels) s.treeLevelNodes += (s.treeLevelNodes.empty() ? "" : "/") + std::to_string(n);
    s.sharedMaxDifference = sharedMax;
    s.leafCorners = own.leafCorners;
    s.leafMaxDifference = own.leafMaxDifference;
    s.pointsCompared = own.points;
    s.pointsBitwise = own.bitwise;
    s.maxDifference = own.maxDifference;
    s.dedupedBitwise = deduped.bitwise;
    s.dedupedMaxDifference = deduped.maxDifference;
    s.structureMismatches = own.structure + deduped.structure;
    return s;
}

CreaseTablesEstimate estimateCreaseTables(const Mesh& mesh, const SchemeOptions& options, const TablesOptions& opts,
                                          Warnings& warnings) {
    checkTablesOptions(mesh, opts);
    Topology baseTopo(static_cast<uint32_t>(mesh.vertexCount()), mesh.faceOffsets, mesh.faceVertices);
    checkTablesTopology(baseTopo, opts);
    AdaptiveLevels a = refineAdaptive(mesh, std::move(baseTopo), options, opts, warnings);
    CreaseTablesEstimate e;
    e.faces = a.creaseFaces.size();
    e.chains = a.creaseChains.size();
    // Programs once per programKey (the study checks that they are the same functions), three
    // kinds per band of each chain.
    std::set<std::vector<uint32_t>> programKeys;
    for (const CreaseChain& chain : a.creaseChains)
        for (const CreaseBand& band : chain.bands) {
            e.programBytes += 15;
            if (programKeys.insert(sharedKey(chain, band)).second) e.programBytes += bandBytes(band) - 15;
        }
    e.bandPrograms = programKeys.size();
    for (const SmoothIrregularFace& f : a.creaseFaces) e.faceBytes += 2 + 2 * f.support.size();
    const Tables t = assembleTables(mesh, options, opts, std::move(a));
    e.tablesBytes = encodeTablesChunk(t).payload.size();
    return e;
}

} // namespace limn
