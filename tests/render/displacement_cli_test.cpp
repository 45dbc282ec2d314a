// Texture displacement (paper 000, 3.4 and 4.5) as users run it: the offset is
// S (sample - M) along the normal, recomputed here from the map (decoded with OpenImageIO, not
// limn's reader), images and meshes are the same bytes twice, bad maps are clean errors.
// The watertight and crack-pixel checks are in displacement_cracks_cli_test.cpp.
#include "displacement_support.h"

#include <OpenImageIO/imageio.h>

#include <array>
#include <cmath>
#include <iostream>

using namespace limn;
using namespace limn::test;
using namespace limn::test::displacement;

namespace {

// ---------------------------------------------------------------------------------------------
// The offset itself, recomputed here: UV from the face's corner UVs (bilinear in the quad's
// Ptex (u, v), which is what linear face-varying interpolation gives inside a quad), the map read
// with OpenImageIO and sampled bilinearly (texel centres at half-integers, v = 0 at the bottom
// row, wrap-around: limn-render --help), times S along the undisplaced normal.

struct Map {
    int width = 0, height = 0;
    std::vector<float> values; // channel 0, rows top to bottom
};

Map readMap(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw std::runtime_error("cannot open " + path);
    const OIIO::ImageSpec& spec = in->spec();
    Map m;
    m.width = spec.width;
    m.height = spec.height;
    std::vector<float> all(size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()))
        throw std::runtime_error("cannot read " + path);
    for (size_t i = 0; i < all.size(); i += spec.nchannels) m.values.push_back(all[i]);
    return m;
}

double sample(const Map& m, double u, double v) {
    const double x = u * m.width - 0.5, y = (1 - v) * m.height - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y);
    auto at = [&](double xi, double yi) {
        long long X = ((long long)xi % m.width + m.width) % m.width;
        long long Y = ((long long)yi % m.height + m.height) % m.height;
        return double(m.values[size_t(Y) * m.width + size_t(X)]);
    };
    const double fx = x - x0, fy = y - y0;
    return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
           fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

TEST(Displacement, OffsetIsScaleTimesSampleAlongTheNormal) {
    for (const char* model : {"quad/spot_control_mesh.obj", "quad/osd_catmark_lefthanded.obj"})
        for (bool uniform : {false, true}) {
            SCOPED_TRACE(std::string(model) + (uniform ? " uniform" : " adaptive"));
            ScratchDir dir;
            const std::string obj = modelPath(model).string();
            const ReferenceObj ref = readReferenceObj(obj);
            ASSERT_TRUE(ref.hasUVs());
            // Ptex faces (OpenSubdiv numbering): a quad is one, an n-gon n sub-quads whose corners
            // are vertex k, the midpoint to k+1, the centroid, the midpoint from k-1. Linear
            // face-varying UVs take those points' UVs and are bilinear inside each (sub-)quad.
            std::vector<std::array<glm::dvec2, 4>> ptexUV;
            for (size_t f = 0; f < ref.faces.size(); ++f) {
                const size_t n = ref.faces[f].size();
                std::vector<glm::dvec2> c(n);
                glm::dvec2 centroid(0);
                for (size_t k = 0; k < n; ++k) {
                    const auto& t = ref.uvs.at(size_t(ref.faceUVs[f][k]));
                    c[k] = {t.first, t.second};
                    centroid += c[k] / double(n);
                }
                if (n == 4) {
                    ptexUV.push_back({c[0], c[1], c[2], c[3]});
                    continue;
                }
                for (size_t k = 0; k < n; ++k)
                    ptexUV.push_back({c[k], (c[k] + c[(k + 1) % n]) / 2.0, centroid,
                                      (c[k] + c[(k + n - 1) % n]) / 2.0});
            }
            const std::string limn = prepare(obj, 3, uniform, dir, "in");
            const std::string mapPath = heightmap(limn, "uv", dir);
            const Map map = readMap(mapPath);
            const double S = 0.07 * diagonalOf(obj), M = 0.25;

            const Drawn plain = drawn(limn, {}, dir, 4);
            const Drawn moved = drawn(limn,
                                      {"--displace", mapPath, "--displace-scale", std::to_string(S),
                                       "--displace-mid", "0.25"},
                                      dir, 4);
            ASSERT_EQ(plain.vertices.size(), moved.vertices.size());
            size_t checked = 0;
            double worst = 0, largest = 0;
            for (size_t i = 0; i < plain.vertices.size(); ++i) {
                const PlyVertex& a = plain.vertices[i];
                const PlyVertex& b = moved.vertices[i];
                ASSERT_EQ(a.ptex, b.ptex);
                // Interior of its face: one UV, no averaging by the seam fix.
                const double u = a.uv[0], v = a.uv[1];
                if (!(u > 1e-6 && u < 1 - 1e-6 && v > 1e-6 && v < 1 - 1e-6)) continue;
                const auto& c = ptexUV.at(size_t(a.ptex));
                const glm::dvec2 uv = (1 - u) * (1 - v) * c[0] + u * (1 - v) * c[1] + u * v * c[2] +
                                      (1 - u) * v * c[3];
                const double h = S * (sample(map, uv.x, uv.y) - M);
                const glm::dvec3 n = glm::normalize(glm::dvec3(a.n[0], a.n[1], a.n[2]));
                const glm::dvec3 want = glm::dvec3(a.p[0], a.p[1], a.p[2]) + h * n;
                const glm::dvec3 got(b.p[0], b.p[1], b.p[2]);
                worst = std::max(worst, glm::length(got - want));
                largest = std::max(largest, std::abs(h));
                ++checked;
            }
            EXPECT_GT(checked, plain.vertices.size() / 4);
            EXPECT_GT(largest, 0.01 * S) << "the map should move the surface";
            EXPECT_LE(worst, 1e-5 * S / 0.07) << checked << " interior vertices";
            std::cout << model << (uniform ? " uniform" : " adaptive") << ": " << checked
                      << " interior vertices, worst offset error " << worst / S
                      << " of the scale S, largest offset " << largest / S << " S\n";
        }
}

TEST(Displacement, SameBytesTwice) {
    ScratchDir dir;
    const std::string obj = modelPath("quad/spot_control_mesh.obj").string();
    const std::string limn = prepare(obj, 2, false, dir, "spot");
    const std::string map = heightmap(limn, "surface", dir);
    std::vector<uint8_t> png[2], ply[2];
    for (int i = 0; i < 2; ++i) {
        const auto p = dir / ("out" + std::to_string(i));
        runOk({bin("limn-render"), limn, "--size", "160x120", "--displace", map, "--displace-scale",
               "0.05", "--displace-mid", "0.5", "--texture",
               modelPath("textures/spot_texture.png").string(), "--mesh-out", p.string() + ".ply",
               "-o", p.string() + ".png"});
        png[i] = readBytes(p.string() + ".png");
        ply[i] = readBytes(p.string() + ".ply");
    }
    EXPECT_EQ(png[0], png[1]);
    EXPECT_EQ(ply[0], ply[1]);
}

TEST(Displacement, BadMapsAreErrorsWithoutOutput) {
    ScratchDir dir;
    const std::string limn =
        prepare(modelPath("quad/spot_control_mesh.obj").string(), 1, false, dir, "spot");
    const std::string out = (dir / "out.png").string();
    writeFile(dir / "notamap.png", "this is not a PNG");
    for (const auto& map : {(dir / "missing.png").string(), (dir / "notamap.png").string()}) {
        auto r = run({bin("limn-render"), limn, "--displace", map, "-o", out});
        EXPECT_EQ(r.exitCode, 1) << r.err;
        EXPECT_NE(r.err.find("limn-render: error: " + map), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(out));
    }
    // The displaced normals come from a compute pass: the vertex-stage path refuses.
    const std::string map = heightmap(limn, "uv", dir);
    auto r = run({bin("limn-render"), limn, "--displace", map, "--eval", "vertex", "-o", out});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    // An EXR's finite but huge value times the scale overflows the GPU's float: the image came
    // out blank with exit 0 (--mesh-out was refused). Refused before rendering, both ways.
    const std::string huge = (dir / "huge.exr").string();
    {
        std::vector<float> values(16, 0.5f);
        values[5] = 3e38f;
        auto o = OIIO::ImageOutput::create(huge);
        ASSERT_TRUE(o);
        ASSERT_TRUE(o->open(huge, OIIO::ImageSpec(4, 4, 1, OIIO::TypeDesc::FLOAT)));
        ASSERT_TRUE(o->write_image(OIIO::TypeDesc::FLOAT, values.data()));
        ASSERT_TRUE(o->close());
    }
    for (const std::string extra : {"", "--mesh-out"}) {
        std::vector<std::string> args = {bin("limn-render"), limn, "--size", "64x48", "--displace", huge,
                                         "--displace-scale", "10", "-o", out};
        if (!extra.empty()) args.insert(args.end(), {extra, (dir / "m.ply").string()});
        r = run(args);
        EXPECT_EQ(r.exitCode, 1) << r.err;
        EXPECT_NE(r.err.find("beyond the 1e18"), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(out));
        EXPECT_FALSE(std::filesystem::exists(dir / "m.ply"));
    }
    // A large but carried displacement renders.
    r = run({bin("limn-render"), limn, "--size", "64x48", "--displace", huge, "--displace-scale", "1e-30", "-o", out});
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

} // namespace
