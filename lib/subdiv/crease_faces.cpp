// takeCreaseFaces (tables_build.h): at level N, the irregular faces with a decaying-crease chain
// (crease_basis.h) taken out of T as smooth faces of their chain's basis, one chain per
// configuration, its bands sharing programs by programKey (docs/irregular-tables.md, "Chains in
// the tables").
#include "subdiv/crease_basis.h"

#include "subdiv/tables_build.h"

#include <algorithm>
#include <map>
#include <memory>
#include <stdexcept>

namespace limn {

namespace {

// The first band of each programKey and end, and its points from bandProbe (made when a later
// band is first compared with it: most first bands never are).
using SharedBands = std::map<std::vector<uint32_t>, std::pair<CreaseBand, std::vector<glm::dvec3>>>;

// Gives each band of `chain` the program of the first band of its programKey and end (in
// `shared`, where the band is added if it is the first) where that is the same function to
// 1e-12. False, with `shared` as it was (and `chain` to be built again), where a borrowed band
// would keep its program.
bool shareBands(CreaseChain& chain, SharedBands& shared) {
    std::vector<SharedBands::iterator> added;
    // A band that holds the program of the band before it (a repeated band), with the same
    // entry, is that band's case again.
    std::vector<uint8_t> repeats(chain.bands.size(), 0);
    for (size_t b = 1; b < chain.bands.size(); ++b)
        repeats[b] = chain.bands[b].support == chain.bands[b - 1].support &&
                     chain.bands[b].centreRow == chain.bands[b - 1].centreRow &&
                     sameProgramBytes(chain.bands[b].program, chain.bands[b - 1].program);
    SharedBands::iterator previous = shared.end(); // the entry of the band before
    bool previousSame = false;
    for (CreaseBand& band : chain.bands) {
        std::vector<uint32_t> key = programKey(band.key, kProgramSharpness);
        key.push_back(&band == &chain.bands.back() ? 1u + uint32_t(chain.end) : 0u);
        auto [other, first] = shared.try_emplace(std::move(key), band, std::vector<glm::dvec3>{});
        if (first) added.push_back(other);
        auto compare = [&, &entry = other->second] {
            if (entry.second.empty()) entry.second = bandProbe(entry.first); // probed when first compared
            double difference = 0;
            return sameBandFunction(entry.first, band, &difference, 1e-12, &entry.second);
        };
        const bool same =
            !first && (repeats[size_t(&band - chain.bands.data())] && other == previous ? previousSame : compare());
        previous = other;
        previousSame = first || same; // a first band is its entry: a band repeating it is the same
        if (same) {
            band.program = other->second.first.program;
            band.centreRow = other->second.first.centreRow;
        } else if (band.borrowed) {
            for (auto x : added) shared.erase(x);
            return false;
        }
    }
    return true;
}

} // namespace

void takeCreaseFaces(const Level& L, const SchemeOptions& options, const TablesOptions& opts, uint32_t basisLevels,
                     std::vector<uint8_t>& T, AdaptiveLevels& a) {
    // A configuration's chain is the same for every face of its key (the study checks it), so
    // it is built once; a key without one is remembered too.
    std::map<std::vector<uint32_t>, int> chainOf;
    std::map<int, int> basisOfChain; // TablesOptions::creaseChains: into a.bases, -1 for none
    SharedBands sharedBands;
    std::vector<uint32_t> support, key;
    const Topology& topo = L.topo;
    // The feature corner is tried first: an extraordinary vertex, else a regular one with a
    // sharp vertex, a dart, or a crease that does not go straight through with one sharpness. A
    // straight crease of one sharpness through a regular vertex is no feature corner: faces along
    // such a crease that are irregular elsewhere have such corners only, and trying them cost a
    // refinement per key for nothing.
    std::vector<uint32_t> ring;
    auto rank = [&](uint32_t v) {
        if (topo.vertexFaceCount(v) != (topo.vertexIsBoundary(v) ? 2u : 4u)) return 0;
        if (L.vertexSharpness[v] != 0) return 1;
        topo.vertexRing(v, ring);
        int sharp = 0, first = -1, second = -1;
        for (int k = 0; k < int(ring.size()); ++k)
            if (L.edgeSharpness[topo.edge(ring[size_t(k)])] != 0) {
                (sharp++ == 0 ? first : second) = k;
            }
        if (sharp == 0) return 2;
        const bool straight = sharp == 2 && !topo.vertexIsBoundary(v) && second - first == 2 &&
                              L.edgeSharpness[topo.edge(ring[size_t(first)])] ==
                                  L.edgeSharpness[topo.edge(ring[size_t(second)])];
        return straight ? 2 : 1;
    };
    std::vector<int8_t> rankOf(topo.vertexCount(), -1);
    for (uint32_t f = 0; f < topo.faceCount(); ++f) {
        if (!T[f] || topo.faceSize(f) != 4) continue;
        int order[4] = {0, 1, 2, 3}, ranks[4];
        for (int c = 0; c < 4; ++c) {
            const uint32_t v = topo.vertex(topo.faceHalfedge(f) + (L.frames[f].rotation + c) % 4);
            if (rankOf[v] < 0) rankOf[v] = int8_t(rank(v)); // a vertex is met from each of its faces
            ranks[c] = rankOf[v];
        }
        std::stable_sort(order, order + 4, [&](int x, int y) { return ranks[x] < ranks[y]; });
        for (int c : order) {
            if (ranks[c] == 2) break; // a smooth regular corner has no chain
            if (!creaseSupport(L, f, c, support, key)) continue;
            auto [it, added] = chainOf.try_emplace(key, -1);
            if (added) {
                CreaseChain chain;
                if (buildCreaseChain(L, f, c, a.K, options, opts, chain, opts.creaseChains)) {
                    a.creaseChains.push_back(std::move(chain));
                    it->second = int(a.creaseChains.size() - 1);
                }
            }
            if (it->second < 0) continue;
            if (opts.creaseChains) {
                // The chain's surface as a basis of the face's own support (expandCreaseChain),
                // once per chain; a face whose chain has none is refined.
                auto [b, fresh] = basisOfChain.try_emplace(it->second, -1);
                IrregularBasis basis;
                if (fresh) {
                    // The chain moves into its basis (a.creaseChains are the prototype's).
                    auto chain = std::make_shared<CreaseChain>(std::move(a.creaseChains[size_t(it->second)]));
                    // Bands whose keys agree once every sharpness from 1 on is clamped, and that
                    // end alike, run the same function (bench_crease_bases checks it: to 1e-16),
                    // so they share one program, which TBLS then stores once; only their kinds'
                    // sharpness differs. A borrowed band that is not replaced so would keep
                    // another band's bits: its chain is built again with every band its own.
                    if (!shareBands(*chain, sharedBands)) {
                        CreaseChain own;
                        if (!buildCreaseChain(L, f, c, a.K, options, opts, own))
                            throw std::logic_error("crease basis: a chain with borrowed bands has none of its own");
                        *chain = std::move(own);
                        if (!shareBands(*chain, sharedBands)) throw std::logic_error("crease basis: own bands borrowed");
                    }
                    // A smooth end goes on with its valence's basis, which the tables hold (TBLS
                    // version 8 names it), even where no face of its own draws from it.
                    int end = -1;
                    if (chain->end == CreaseEnd::Smooth) {
                        std::vector<int>& of = a.basisOfValence;
                        if (of.size() <= chain->valence) of.resize(chain->valence + 1, -1);
                        if (of[chain->valence] == -1) {
                            try {
                                of[chain->valence] = addBasis(
                                    a, buildIrregularBasis(chain->valence, std::max(a.K, basisLevels), opts.basisWeights));
                            } catch (const std::exception&) {
                                of[chain->valence] = -2;
                            }
                        }
                        end = of[chain->valence];
                        chain->endBasis = uint32_t(end);
                    }
                    if ((chain->end != CreaseEnd::Smooth || end >= 0) &&
                        expandCreaseChain(*chain, a.K, basis, end >= 0 ? &a.bases[size_t(end)] : nullptr,
                                          opts.basisWeights)) {
                        basis.chain = std::move(chain);
                        b->second = addBasis(a, std::move(basis));
                    }
                }
                if (b->second < 0) continue;
                a.smooth.push_back({f, uint32_t(b->second), uint32_t(c), support, L.depth});
                T[f] = 0;
                break;
            }
            a.creaseFaces.push_back({f, uint32_t(it->second), uint32_t(c), support, L.depth});
            T[f] = 0;
            break;
        }
    }
}

} // namespace limn
