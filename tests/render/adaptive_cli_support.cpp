#include "adaptive_cli_support.h"

#include "model_tables.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace limn::test {

std::string writeSphere(const std::filesystem::path& path) {
    const Mesh m = paperSphere(5);
    std::ofstream o(path);
    char line[128];
    for (const glm::dvec3& p : m.positions) {
        std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
        o << line;
    }
    for (size_t f = 0; f < m.faceCount(); ++f) {
        o << "f";
        for (uint32_t v : m.face(f)) o << " " << v + 1;
        o << "\n";
    }
    return path.string();
}


std::string writePrism(const std::filesystem::path& path, int n) {
    std::ofstream o(path);
    char line[128];
    for (int ring = 0; ring < 2; ++ring)
        for (int k = 0; k < n; ++k) {
            const double a = 2 * M_PI * (k + 0.3 * ring) / n, r = 1 + 0.2 * std::cos(3 * a);
            std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", r * std::cos(a), r * std::sin(a), ring ? 1.3 : -0.4 * r);
            o << line;
        }
    o << "f";
    for (int k = n; k-- > 0;) o << " " << k + 1;
    o << "\nf";
    for (int k = 0; k < n; ++k) o << " " << n + k + 1;
    o << "\n";
    for (int k = 0; k < n; ++k)
        o << "f " << k + 1 << " " << (k + 1) % n + 1 << " " << n + (k + 1) % n + 1 << " " << n + k + 1 << "\n";
    return path.string();
}

std::string prepare(const std::string& obj, int depth, const ScratchDir& dir, std::vector<std::string> classify) {
    const std::string limn = (dir / "in.limn").string();
    classify.insert(classify.begin(), {tool("limn-classify").string(), obj, "-o", limn});
    auto r = run(classify);
    if (r.exitCode != 0) throw std::runtime_error(r.err);
    r = run({tool("limn-tables").string(), limn, "-q", "-o", limn, "--depth", std::to_string(depth)});
    if (r.exitCode != 0) throw std::runtime_error(r.err);
    return limn;
}

std::string triple(const glm::dvec3& v) {
    char s[128];
    std::snprintf(s, sizeof s, "%.9g,%.9g,%.9g", v.x, v.y, v.z);
    return s;
}

std::pair<size_t, size_t> coveredAndDiffering(const Image& a, const Image& b) {
    const uint8_t* bg = a.pixels.data();
    size_t covered = 0, differ = 0;
    for (size_t i = 0; i < size_t(a.width) * a.height; ++i) {
        const uint8_t *p = &a.pixels[i * a.channels], *q = &b.pixels[i * b.channels];
        if (std::equal(p, p + 3, bg) && std::equal(q, q + 3, bg)) continue;
        ++covered;
        int d = 0;
        for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(int(p[k]) - int(q[k])));
        differ += d > 8;
    }
    return {covered, differ};
}

} // namespace limn::test
