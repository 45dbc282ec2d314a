#include "mesh/examples.h"

#include <array>
#include <cmath>
#include <initializer_list>
#include <map>
#include <numbers>

namespace limn {

namespace {

constexpr double kPi = std::numbers::pi;

double round6(double x) {
    return std::round(x * 1e6) / 1e6 + 0.0;
} // + 0.0 turns -0 into 0
glm::dvec3 round6(glm::dvec3 p) {
    return {round6(p.x), round6(p.y), round6(p.z)};
}
glm::dvec2 round6(glm::dvec2 p) {
    return {round6(p.x), round6(p.y)};
}

void addFace(Mesh& m, std::initializer_list<uint32_t> vertices,
             std::initializer_list<uint32_t> uvs) {
    m.addFace(std::span<const uint32_t>(vertices.begin(), vertices.size()));
    m.uvIndices.insert(m.uvIndices.end(), uvs);
}

// The surface of the cube [-n,n]^3 cut into n x n quads per face, on the even integer lattice,
// so shared points are found exactly. Vertices are numbered in the order faces first use them.
class BoxLattice {
  public:
    explicit BoxLattice(int n) : n_(n) {
        // Per face: the outward axis and sign, then tangent axes u, v with u x v pointing
        // outward, so the cells below are counter-clockwise seen from outside.
        struct Side {
            int axis, sign, u, v;
        };
        const Side sides[6] = {{0, +1, 1, 2}, {0, -1, 2, 1}, {1, +1, 2, 0},
                               {1, -1, 0, 2}, {2, +1, 0, 1}, {2, -1, 1, 0}};
        for (int s = 0; s < 6; ++s) {
            // The face's own tile in a 3 x 2 UV atlas, with a margin against texture bleeding.
            auto uvBase = static_cast<uint32_t>(mesh_.uvs.size());
            for (int j = 0; j <= n; ++j)
                for (int i = 0; i <= n; ++i)
                    mesh_.uvs.push_back(round6(glm::dvec2{(s % 3 + 0.05 + 0.9 * i / n) / 3,
                                                          (s / 3 + 0.05 + 0.9 * j / n) / 2}));
            auto point = [&](int i, int j) {
                std::array<int, 3> p{};
                p[sides[s].axis] = sides[s].sign * n;
                p[sides[s].u] = 2 * i - n;
                p[sides[s].v] = 2 * j - n;
                return vertex(p);
            };
            auto uv = [&](int i, int j) { return uvBase + static_cast<uint32_t>(j * (n + 1) + i); };
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i)
                    addFace(mesh_,
                            {point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)},
                            {uv(i, j), uv(i + 1, j), uv(i + 1, j + 1), uv(i, j + 1)});
        }
    }

    uint32_t at(std::array<int, 3> p) const { return index_.at(p); }
    const std::map<std::array<int, 3>, uint32_t>& points() const { return index_; }
    Mesh& mesh() { return mesh_; }

  private:
    uint32_t vertex(std::array<int, 3> p) {
        auto [it, added] = index_.emplace(p, static_cast<uint32_t>(index_.size()));
        if (added) mesh_.positions.push_back(glm::dvec3(p[0], p[1], p[2]) / double(n_));
        return it->second;
    }

    int n_;
    std::map<std::array<int, 3>, uint32_t> index_;
    Mesh mesh_;
};

} // namespace

Mesh makeCube() {
    return std::move(BoxLattice(1).mesh());
}

Mesh makeQuadSphere(int n) {
    Mesh m = std::move(BoxLattice(n).mesh());
    for (auto& p : m.positions) p = round6(p / std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z));
    return m;
}

Mesh makeTorus(int ring, int tube) {
    const double major = 1.0, minor = 0.4;
    Mesh m;
    for (int j = 0; j < tube; ++j)
        for (int i = 0; i < ring; ++i) {
            double theta = 2 * kPi * i / ring, phi = 2 * kPi * j / tube;
            double r = major + minor * std::cos(phi);
            m.positions.push_back(round6(
                glm::dvec3{r * std::cos(theta), r * std::sin(theta), minor * std::sin(phi)}));
        }
    // The UV grid has one more row and column than the vertex grid: the texture does not wrap.
    for (int j = 0; j <= tube; ++j)
        for (int i = 0; i <= ring; ++i)
            m.uvs.push_back(round6(glm::dvec2{double(i) / ring, double(j) / tube}));
    auto v = [&](int i, int j) { return static_cast<uint32_t>((j % tube) * ring + i % ring); };
    auto t = [&](int i, int j) { return static_cast<uint32_t>(j * (ring + 1) + i); };
    // d/dtheta x d/dphi is the outward normal, so (i, j) -> (i+1, j) -> ... is counter-clockwise.
    for (int j = 0; j < tube; ++j)
        for (int i = 0; i < ring; ++i)
            addFace(m, {v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)},
                    {t(i, j), t(i + 1, j), t(i + 1, j + 1), t(i, j + 1)});
    return m;
}

Mesh makeTwistingTorus(int ring, int tube, int k, int n) {
    Mesh m = makeTorus(ring, tube);
    const double major = 1.0, a = 0.45, b = 0.2;
    const double spin = kPi * k / n; // a half turn over the loop
    for (int j = 0; j < tube; ++j)
        for (int i = 0; i < ring; ++i) {
            const double theta = 2 * kPi * i / ring, phi = 2 * kPi * j / tube;
            // The ellipse in the tube's (radial, up) plane, turned by theta (one full turn along
            // the ring, so the seam at theta = 0 meets itself) plus the frame's spin.
            const double turn = theta + spin, x = a * std::cos(phi), y = b * std::sin(phi);
            const double radial = x * std::cos(turn) - y * std::sin(turn);
            const double up = x * std::sin(turn) + y * std::cos(turn);
            const double r = major + radial;
            m.positions[size_t(j) * ring + i] =
                round6(glm::dvec3{r * std::cos(theta), r * std::sin(theta), up});
        }
    return m;
}

Mesh makePentagonTower() {
    Mesh m;
    // Vertices: floor ring 0..4, eaves ring 5..9, apex 10.
    for (double z : {0.0, 1.2})
        for (int k = 0; k < 5; ++k)
            m.positions.push_back(
                round6(glm::dvec3{std::cos(2 * kPi * k / 5), std::sin(2 * kPi * k / 5), z}));
    m.positions.push_back({0.0, 0.0, 1.9});
    // UVs: walls as a strip (v 0 to 0.4) whose top row the roof shares; a separate apex value per
    // roof triangle; the floor as a disc of its own.
    for (double v : {0.0, 0.4})
        for (int k = 0; k <= 5; ++k) m.uvs.push_back(round6(glm::dvec2{k / 5.0, v}));
    for (int k = 0; k < 5; ++k) m.uvs.push_back(round6(glm::dvec2{(k + 0.5) / 5, 0.7}));
    for (int k = 0; k < 5; ++k)
        m.uvs.push_back(round6(glm::dvec2{0.5 + 0.12 * std::cos(2 * kPi * k / 5),
                                          0.85 + 0.12 * std::sin(2 * kPi * k / 5)}));
    auto floor = [](int k) { return static_cast<uint32_t>(k % 5); };
    auto eave = [](int k) { return static_cast<uint32_t>(5 + k % 5); };
    auto wallUV = [](int k, int row) { return static_cast<uint32_t>(row * 6 + k); };
    // The floor seen from below: clockwise seen from above.
    addFace(m, {floor(4), floor(3), floor(2), floor(1), floor(0)}, {21, 20, 19, 18, 17});
    for (int k = 0; k < 5; ++k) {
        addFace(m, {floor(k), floor(k + 1), eave(k + 1), eave(k)},
                {wallUV(k, 0), wallUV(k + 1, 0), wallUV(k + 1, 1), wallUV(k, 1)});
        addFace(m, {eave(k), eave(k + 1), 10},
                {wallUV(k, 1), wallUV(k + 1, 1), static_cast<uint32_t>(12 + k)});
    }
    return m;
}

Mesh makeCreasedCube() {
    BoxLattice box(2);
    Mesh m = std::move(box.mesh());
    // Tags every lattice segment on the straight cube edge from `a` to `b`.
    auto crease = [&](std::array<int, 3> a, std::array<int, 3> b, float sharpness) {
        std::array<int, 3> p = a;
        while (p != b) {
            std::array<int, 3> q = p;
            for (int axis = 0; axis < 3; ++axis)
                q[axis] += q[axis] < b[axis] ? 2 : q[axis] > b[axis] ? -2 : 0;
            m.tags.creases.push_back({box.at(p), box.at(q), sharpness});
            p = q;
        }
    };
    const std::array<int, 3> rim[4] = {{-2, -2, 2}, {2, -2, 2}, {2, 2, 2}, {-2, 2, 2}};
    for (int k = 0; k < 4; ++k) crease(rim[k], rim[(k + 1) % 4], kInfiniteSharpness);
    for (const auto& top : rim) crease({top[0], top[1], -2}, top, 2.0f);
    m.tags.corners.push_back({box.at({-2, -2, -2}), 3.0f});
    return m;
}

Mesh makeGridWithHole(int n) {
    Mesh m;
    std::map<std::pair<int, int>, uint32_t> index; // only points some face uses
    auto vertex = [&](int i, int j) {
        auto [it, added] =
            index.emplace(std::pair{i, j}, static_cast<uint32_t>(m.positions.size()));
        if (added) {
            double x = 2.0 * i / n - 1, y = 2.0 * j / n - 1;
            m.positions.push_back(round6(glm::dvec3{x, y, 0.25 * (1 - (x * x + y * y) / 2)}));
            m.uvs.push_back(round6(glm::dvec2{double(i) / n, double(j) / n}));
        }
        return it->second;
    };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            bool hole = (i == n / 2 - 1 || i == n / 2) && (j == n / 2 - 1 || j == n / 2);
            if (hole) continue;
            uint32_t a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1),
                     d = vertex(i, j + 1);
            addFace(m, {a, b, c, d}, {a, b, c, d}); // one UV per vertex: no seams
        }
    m.tags.boundary = BoundaryRule::EdgeAndCorner;
    return m;
}

std::vector<Example> builtinExamples() {
    std::vector<Example> out;
    out.push_back({"cube", "8 valence-3 vertices, a UV tile per face", makeCube()});
    out.push_back({"quad_sphere",
                   "cube on a sphere: 8 valence-3 vertices among valence-4 ones, UV seams",
                   makeQuadSphere(4)});
    out.push_back(
        {"torus", "every vertex regular, UV seams where the texture wraps", makeTorus(16, 8)});
    out.push_back(
        {"pentagon_tower", "pentagon floor, quad walls, roof of triangles", makePentagonTower()});
    out.push_back({"creased_cube", "infinitely sharp and semi-sharp creases, a semi-sharp corner",
                   makeCreasedCube()});
    out.push_back({"grid_with_hole", "open grid with a hole: two boundary loops, edge-and-corner",
                   makeGridWithHole(8)});
    return out;
}

std::vector<ExampleSequence> builtinSequences() {
    std::vector<ExampleSequence> out;
    ExampleSequence twist{"twist", "a torus with an elliptic tube twisting as it spins: 24 frames, one topology", {}};
    for (int k = 0; k < 24; ++k) twist.frames.push_back(makeTwistingTorus(24, 12, k, 24));
    out.push_back(std::move(twist));
    return out;
}

} // namespace limn
