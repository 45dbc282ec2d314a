#include "loop/measure.h"

#include "loop/adaptive.h"
#include "loop/metric.h"
#include "loop/rules.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <thread>

namespace limn::loop {

namespace {

uint64_t splitmix64(uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}
double unit(uint64_t h) { return static_cast<double>(h >> 11) * 0x1.0p-53; }

// Whether sample i of n is kept when at most `cap` are wanted: a fixed pseudo-random choice.
bool keep(uint64_t i, uint64_t n, uint64_t cap, uint64_t stream) {
    if (n <= cap) return true;
    return unit(splitmix64(i ^ (stream << 56))) * static_cast<double>(n) < static_cast<double>(cap);
}

// Max and sum of squares of distances, accumulated over fixed chunks in a fixed order so the
// result does not depend on the number of threads.
OneSided distances(const std::vector<glm::dvec3>& points, const TriangleBvh& target, double diagonal) {
    constexpr size_t kChunk = 4096;
    const size_t chunks = (points.size() + kChunk - 1) / kChunk;
    std::vector<double> chunkMax(chunks, 0), chunkSum(chunks, 0);
    auto work = [&](size_t worker, size_t workers) {
        for (size_t c = worker; c < chunks; c += workers) {
            double mx = 0, sum = 0;
            for (size_t i = c * kChunk; i < std::min(points.size(), (c + 1) * kChunk); ++i) {
                double d2 = target.squaredDistance(points[i]);
                mx = std::max(mx, d2);
                sum += d2;
            }
            chunkMax[c] = mx;
            chunkSum[c] = sum;
        }
    };
    size_t workers = std::clamp<size_t>(std::thread::hardware_concurrency(), 1, 16);
    workers = std::min(workers, std::max<size_t>(chunks, 1));
    std::vector<std::thread> threads;
    for (size_t w = 1; w < workers; ++w) threads.emplace_back(work, w, workers);
    work(0, workers);
    for (auto& t : threads) t.join();
    OneSided r;
    double mx = 0, sum = 0;
    for (size_t c = 0; c < chunks; ++c) {
        mx = std::max(mx, chunkMax[c]);
        sum += chunkSum[c];
    }
    r.samples = points.size();
    r.max = std::sqrt(mx) / diagonal;
    r.rms = points.empty() ? 0 : std::sqrt(sum / static_cast<double>(points.size())) / diagonal;
    return r;
}

// Uniform Loop to `level`, every vertex at its limit position. The last step takes the limits
// straight from the level below (limits do not change under refinement: E5/B.3 for the even
// vertices, B.4's L(o) for the odd ones), which saves building the finest topology.
TriMesh limitReference(const TriMesh& control, int level) {
    TriMesh base = control;
    base.uvs.clear();
    base.uvTriangles.clear();
    AdaptiveOptions uniform;
    uniform.uniform = true;
    uniform.levels = level - 1;
    TriMesh coarse = level > 0 ? subdivide(base, uniform).mesh : base;
    Level l(coarse);
    if (level == 0) {
        TriMesh out = coarse;
        out.positions = limitPositions(l);
        return out;
    }
    auto even = evenPositions(l), odd = oddPositions(l);
    std::vector<uint8_t> all(l.topology().edgeCount(), 1);
    TriMesh out = refine(l, all, EvenUpdate::All, even, odd).mesh;
    std::vector<glm::dvec3> evenLimit = limitPositions(l), oddLimit = oddLimitPositions(l, even, odd);
    std::copy(evenLimit.begin(), evenLimit.end(), out.positions.begin());
    std::copy(oddLimit.begin(), oddLimit.end(), out.positions.begin() + evenLimit.size());
    return out;
}

} // namespace

LimitReference::LimitReference(const TriMesh& control, const MeasureOptions& options)
    : options_(options), diagonal_(boundingBoxDiagonal(control.positions)),
      mesh_(limitReference(control, options.referenceLevel)), bvh_(mesh_.positions, mesh_.triangles) {}

Measurement LimitReference::measure(const TriMesh& test) const {
    Measurement m;
    m.referenceLevel = options_.referenceLevel;
    m.referenceFaces = mesh_.triangleCount();
    m.diagonal = diagonal_;
    const double D = diagonal_ > 0 ? diagonal_ : 1.0;
    const uint64_t cap = options_.maxSamples;

    // Test → limit: vertices, then one uniformly distributed point per triangle.
    std::vector<glm::dvec3> testPoints;
    const uint64_t nv = test.vertexCount(), nt = test.triangleCount();
    for (uint64_t i = 0; i < nv + nt; ++i) {
        if (!keep(i, nv + nt, cap, 1)) continue;
        if (i < nv) {
            testPoints.push_back(test.positions[i]);
            continue;
        }
        const Tri& t = test.triangles[i - nv];
        double r1 = unit(splitmix64(i * 2 + 0x51)), r2 = unit(splitmix64(i * 2 + 0x52));
        if (r1 + r2 > 1) {
            r1 = 1 - r1;
            r2 = 1 - r2;
        }
        const auto& P = test.positions;
        testPoints.push_back(P[t[0]] + r1 * (P[t[1]] - P[t[0]]) + r2 * (P[t[2]] - P[t[0]]));
    }
    m.toLimit = distances(testPoints, bvh_, D);

    // Limit → test: the reference's vertices are exact limit points.
    std::vector<glm::dvec3> limitPoints;
    const uint64_t nr = mesh_.vertexCount();
    for (uint64_t i = 0; i < nr; ++i)
        if (keep(i, nr, cap, 2)) limitPoints.push_back(mesh_.positions[i]);
    TriangleBvh testBvh(test.positions, test.triangles);
    m.fromLimit = distances(limitPoints, testBvh, D);

    m.max = std::max(m.toLimit.max, m.fromLimit.max);
    double n1 = static_cast<double>(m.toLimit.samples), n2 = static_cast<double>(m.fromLimit.samples);
    if (n1 + n2 > 0)
        m.rms = std::sqrt((m.toLimit.rms * m.toLimit.rms * n1 + m.fromLimit.rms * m.fromLimit.rms * n2) /
                          (n1 + n2));
    return m;
}

int defaultReferenceLevel(const TriMesh& control, int levels, uint64_t faceBudget) {
    int r = levels + 2;
    while (r > 1 && static_cast<double>(control.triangleCount()) * std::pow(4.0, r) >
                        static_cast<double>(faceBudget))
        --r;
    return std::max(r, 1);
}

} // namespace limn::loop
