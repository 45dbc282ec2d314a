// limn-render's glTF base colour materials: factor and texture, from an external file, a GLB
// buffer view and a data: URI, and through limn-classify's MATL chunk. The glTF assets are
// written here with a texture whose colours the checks know; every render runs with --validate,
// so exit code 0 also means no validation errors.
#include "look_cli_support.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>
#include <sstream>

using namespace limn;
using namespace limn::test;
using namespace limn::look_test;

namespace {

// Quadrants of the test texture as seen in the image (top-left, top-right, bottom-left,
// bottom-right), sRGB.
constexpr uint8_t kQuadrant[4][3] = {{200, 40, 40}, {40, 200, 40}, {40, 40, 200}, {200, 200, 40}};

std::vector<uint8_t> quadrantTexture() {
    Image t;
    t.width = t.height = 64;
    t.channels = 3;
    t.pixels.resize(64 * 64 * 3);
    for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x)
            std::memcpy(&t.pixels[(y * 64 + x) * 3], kQuadrant[(y >= 32) * 2 + (x >= 32)], 3);
    return encodePng(t);
}

std::vector<uint8_t> solidTexture(uint8_t r, uint8_t g, uint8_t b) {
    Image t;
    t.width = t.height = 4;
    t.channels = 3;
    for (int i = 0; i < 16; ++i) t.pixels.insert(t.pixels.end(), {r, g, b});
    return encodePng(t);
}

std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t n = uint32_t(bytes[i]) << 16;
        if (i + 1 < bytes.size()) n |= uint32_t(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) n |= bytes[i + 2];
        out += digits[(n >> 18) & 63];
        out += digits[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? digits[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? digits[n & 63] : '=';
    }
    return out;
}

template <class T>
void append(std::vector<uint8_t>& out, const T& value) {
    const auto* p = reinterpret_cast<const uint8_t*>(&value);
    out.insert(out.end(), p, p + sizeof(T));
}

enum class Storage { External, Glb, DataUri };

// A 4 x 4 grid of squares in the XY plane (x, y in 0..4), facing +Z, as 32 triangles, with
// TEXCOORD_0 = (x / 4, 1 - y / 4) (glTF's UVs start at the image's top left, so the plane shows
// the texture upright), and a material with `factor` and, when `texture` is not empty, that
// image as baseColorTexture. Writes DIR/NAME.gltf (+ NAME.bin, NAME.png) or DIR/NAME.glb; returns
// its path.
std::string writePlane(const ScratchDir& dir, const std::string& name, Storage storage,
                       const std::vector<uint8_t>& texture, const std::string& factor = "") {
    std::vector<uint8_t> buffer;
    for (int j = 0; j <= 4; ++j)
        for (int i = 0; i <= 4; ++i) {
            append(buffer, float(i));
            append(buffer, float(j));
            append(buffer, 0.0f);
        }
    for (int j = 0; j <= 4; ++j)
        for (int i = 0; i <= 4; ++i) {
            append(buffer, float(i) / 4);
            append(buffer, 1.0f - float(j) / 4);
        }
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const uint16_t a = uint16_t(j * 5 + i), b = uint16_t(a + 1), c = uint16_t(a + 6),
                           d = uint16_t(a + 5);
            for (uint16_t v : {a, b, c, a, c, d}) append(buffer, v);
        }
    const size_t geometry = buffer.size(); // 300 + 200 + 192 = 692, a multiple of 4
    const bool textured = !texture.empty();
    if (textured && storage == Storage::Glb) buffer.insert(buffer.end(), texture.begin(), texture.end());
    while (buffer.size() % 4) buffer.push_back(0);

    std::ostringstream j;
    j << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"indices":2,"material":0}]}],)"
      << R"("materials":[{"pbrMetallicRoughness":{)";
    if (!factor.empty()) j << R"("baseColorFactor":[)" << factor << "]" << (textured ? "," : "");
    if (textured) j << R"("baseColorTexture":{"index":0})";
    j << "}}],";
    if (textured) {
        j << R"("textures":[{"source":0}],"images":[)";
        if (storage == Storage::External) j << R"({"uri":")" << name << R"(.png"})";
        const bool jpeg = texture.size() > 2 && texture[0] == 0xFF && texture[1] == 0xD8;
        if (storage == Storage::Glb)
            j << R"({"bufferView":3,"mimeType":")" << (jpeg ? "image/jpeg" : "image/png") << R"("})";
        if (storage == Storage::DataUri) j << R"({"uri":"data:image/png;base64,)" << base64(texture) << R"("})";
        j << "],";
    }
    j << R"("accessors":[{"bufferView":0,"componentType":5126,"count":25,"type":"VEC3","min":[0,0,0],"max":[4,4,0]},)"
      << R"({"bufferView":1,"componentType":5126,"count":25,"type":"VEC2"},)"
      << R"({"bufferView":2,"componentType":5123,"count":96,"type":"SCALAR"}],)"
      << R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":300},)"
      << R"({"buffer":0,"byteOffset":300,"byteLength":200},{"buffer":0,"byteOffset":500,"byteLength":192})";
    if (textured && storage == Storage::Glb)
        j << R"(,{"buffer":0,"byteOffset":)" << geometry << R"(,"byteLength":)" << texture.size() << "}";
    j << R"(],"buffers":[{"byteLength":)" << buffer.size();
    if (storage == Storage::External) j << R"(,"uri":")" << name << R"(.bin")";
    if (storage == Storage::DataUri)
        j << R"(,"uri":"data:application/octet-stream;base64,)" << base64(buffer) << R"(")";
    j << "}]}";
    std::string json = j.str();

    if (storage == Storage::Glb) {
        while (json.size() % 4) json += ' ';
        std::vector<uint8_t> glb;
        append(glb, uint32_t(0x46546C67)); // "glTF"
        append(glb, uint32_t(2));
        append(glb, uint32_t(12 + 8 + json.size() + 8 + buffer.size()));
        append(glb, uint32_t(json.size()));
        append(glb, uint32_t(0x4E4F534A)); // "JSON"
        glb.insert(glb.end(), json.begin(), json.end());
        append(glb, uint32_t(buffer.size()));
        append(glb, uint32_t(0x004E4942)); // "BIN\0"
        glb.insert(glb.end(), buffer.begin(), buffer.end());
        const std::string path = (dir / (name + ".glb")).string();
        writeFile(path, std::string(glb.begin(), glb.end()));
        return path;
    }
    if (storage == Storage::External) {
        writeFile(dir / (name + ".bin"), std::string(buffer.begin(), buffer.end()));
        if (textured) writeFile(dir / (name + ".png"), std::string(texture.begin(), texture.end()));
    }
    const std::string path = (dir / (name + ".gltf")).string();
    writeFile(path, json);
    return path;
}

// The plane seen face-on (it fills 85% of the square image, centred): the centre pixel of each
// quadrant lies well inside the texture's quadrant of the same place.
const std::pair<uint32_t, uint32_t> kQuadrantPixel[4] = {{48, 48}, {112, 48}, {48, 112}, {112, 112}};

Image renderPlane(const ScratchDir& dir, const std::string& input,
                          std::vector<std::string> options = {}, std::string* err = nullptr) {
    options.insert(options.begin(), input);
    options.insert(options.end(), {"--view", "0,0", "--size", "160x160", "-o", (dir / "plane.png").string()});
    auto r = limnRender(options);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    if (err) *err = r.err;
    return readPng(dir / "plane.png");
}

// Which channels are bright (more than twice the dimmest channel, the light scales all alike).
std::string bright(const uint8_t* p) {
    const int lo = std::max(1, int(std::min({p[0], p[1], p[2]})));
    std::string s;
    for (int c = 0; c < 3; ++c)
        if (p[c] > 2 * lo) s += "RGB"[c];
    return s;
}

std::string expectedBright(int quadrant) {
    return bright(kQuadrant[quadrant]);
}

} // namespace

// The texture of the material is drawn, from each of the three places glTF keeps images, and
// through the container (limn-classify's MATL chunk passes limn-tables): each quadrant of the
// plane shows its quadrant's colour, and all four ways give the same bytes as --texture.
TEST(GltfMaterial, BaseColorTextureFromFileGlbAndDataUri) {
    ScratchDir dir;
    const auto tex = quadrantTexture();
    writeFile(dir / "tex.png", std::string(tex.begin(), tex.end()));
    std::vector<std::vector<uint8_t>> images;
    for (Storage storage : {Storage::External, Storage::Glb, Storage::DataUri}) {
        const std::string name = storage == Storage::External ? "ext" : storage == Storage::Glb ? "glb" : "data";
        const std::string gltf = writePlane(dir, name, storage, tex);
        const std::string limn = prepare(dir, gltf, name, 2);
        const Image img = renderPlane(dir, limn);
        for (int q = 0; q < 4; ++q) {
            const auto [x, y] = kQuadrantPixel[q];
            EXPECT_EQ(bright(img.at(x, y)), expectedBright(q)) << name << " quadrant " << q;
        }
        images.push_back(img.pixels);
        // The pipeline as a user runs it: limn-classify | limn-tables | limn-render.
        auto c = run({bin("limn-classify"), gltf, "-q"});
        ASSERT_EQ(c.exitCode, 0) << c.err;
        auto t = run({bin("limn-tables"), "-q", "-d", "2"}, c.out);
        ASSERT_EQ(t.exitCode, 0) << t.err;
        auto r = limnRender({"--view", "0,0", "--size", "160x160"}, t.out);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(readPng(dir / "plane.png").pixels, decodePng(std::vector<uint8_t>(r.out.begin(), r.out.end())).pixels);
    }
    EXPECT_EQ(images[0], images[1]);
    EXPECT_EQ(images[0], images[2]);
    // The same as giving the image with --texture (a white factor multiplies nothing).
    const std::string ext = (dir / "ext.limn").string();
    const Image given = renderPlane(dir, ext, {"--texture", (dir / "tex.png").string()});
    EXPECT_EQ(given.pixels, images[0]);
}

// The depfile of a render straight from a .gltf names its external buffer and image.
TEST(GltfMaterial, DepfileNamesTheExternalTexture) {
    ScratchDir dir;
    const std::string gltf = writePlane(dir, "ext", Storage::External, quadrantTexture());
    auto r = limnRender({gltf, "-q", "--size", "32x32", "-o", (dir / "o.png").string(), "--depfile",
                     (dir / "o.d").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string dep = readFile(dir / "o.d");
    EXPECT_NE(dep.find("ext.png"), std::string::npos) << dep;
    EXPECT_NE(dep.find("ext.bin"), std::string::npos) << dep;
}

// --texture replaces the material's texture; --color replaces its factor (and multiplies the
// texture): red light on the texture's green quadrant is dark.
TEST(GltfMaterial, TextureAndColorOptionsOverride) {
    ScratchDir dir;
    const std::string limn = prepare(dir, writePlane(dir, "p", Storage::Glb, quadrantTexture()), "p", 2);
    const auto blue = solidTexture(30, 30, 220);
    writeFile(dir / "blue.png", std::string(blue.begin(), blue.end()));
    const Image over = renderPlane(dir, limn, {"--texture", (dir / "blue.png").string()});
    for (const auto& [x, y] : kQuadrantPixel) EXPECT_EQ(bright(over.at(x, y)), "B");
    const Image red = renderPlane(dir, limn, {"--color", "1,0,0"});
    for (int q = 0; q < 4; ++q) {
        const auto [x, y] = kQuadrantPixel[q];
        const uint8_t* p = red.at(x, y);
        EXPECT_LE(int(p[1]), 25) << q; // no green or blue light but the white highlight
        EXPECT_LE(int(p[2]), 25) << q;
        if (q == 1 || q == 2) EXPECT_LT(int(p[0]), 110) << q; // red 40 of 255 in the texture
        else EXPECT_GT(int(p[0]), 150) << q;
    }
}

// baseColorFactor alone tints the model (lit shading of the control mesh and of the surface);
// --color wins over it.
TEST(GltfMaterial, BaseColorFactorTintsAndColorOverrides) {
    ScratchDir dir;
    const std::string gltf = writePlane(dir, "f", Storage::Glb, {}, "0.8,0.2,0.05,1");
    for (const std::string& input : {gltf, prepare(dir, gltf, "f", 2), prepare(dir, gltf, "g", -1)}) {
        const Image img = renderPlane(dir, input);
        for (const auto& [x, y] : kQuadrantPixel) {
            const uint8_t* p = img.at(x, y);
            EXPECT_GT(int(p[0]), int(p[1]) + 40) << input;
            EXPECT_GT(int(p[1]), int(p[2])) << input;
        }
        const Image blue = renderPlane(dir, input, {"--color", "0.1,0.1,0.9"});
        for (const auto& [x, y] : kQuadrantPixel) EXPECT_EQ(bright(blue.at(x, y)), "B") << input;
    }
}

// A textured mesh file given straight to limn-render (no tables): its control mesh is drawn with
// the texture, quadrant by quadrant as the texture file has it (the plane is flat, so the control
// mesh lies where the surface would), and nothing is said about it.
TEST(GltfMaterial, ControlMeshOfATexturedMeshFileIsTextured) {
    ScratchDir dir;
    const std::string gltf = writePlane(dir, "straight", Storage::Glb, quadrantTexture());
    std::string err;
    const Image img = renderPlane(dir, gltf, {}, &err);
    for (int q = 0; q < 4; ++q) {
        const auto [x, y] = kQuadrantPixel[q];
        EXPECT_EQ(bright(img.at(x, y)), expectedBright(q)) << "quadrant " << q;
    }
    EXPECT_EQ(err, "");
    // --shade normal asks for the normals: the texture is left out, and only -v says so.
    renderPlane(dir, gltf, {"--shade", "normal", "-v"}, &err);
    EXPECT_NE(err.find("base colour texture is drawn with --shade lit or texture"), std::string::npos) << err;
}

// A texture that cannot be decoded: a warning, and the factor alone is drawn.
TEST(GltfMaterial, CorruptTextureWarnsAndDrawsTheFactor) {
    ScratchDir dir;
    std::vector<uint8_t> broken = quadrantTexture();
    broken.resize(broken.size() / 2); // a PNG cut in half
    const std::string limn = prepare(dir, writePlane(dir, "b", Storage::Glb, broken, "0.02,0.9,0.02,1"), "b", 2);
    std::string err;
    const Image img = renderPlane(dir, limn, {}, &err);
    EXPECT_NE(err.find("base colour texture cannot be read"), std::string::npos) << err;
    for (const auto& [x, y] : kQuadrantPixel) EXPECT_EQ(bright(img.at(x, y)), "G");
}

// Khronos' BoxTextured (GLB, embedded PNG) through the pipeline: the logo's colours show, not the
// grey of the untextured model.
TEST(GltfMaterial, BoxTexturedShowsItsTexture) {
    ScratchDir dir;
    const std::string limn = prepare(dir, modelPath("gltf/BoxTextured/BoxTextured.glb").string(), "box", 2);
    auto r = limnRender({limn, "--size", "128x128", "--background", kKey, "-o", (dir / "box.png").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image img = readPng(dir / "box.png");
    size_t covered = 0, coloured = 0;
    for (uint32_t y = 0; y < img.height; ++y)
        for (uint32_t x = 0; x < img.width; ++x) {
            const uint8_t* p = img.at(x, y);
            if (p[0] == 255 && p[1] == 0 && p[2] == 255) continue;
            ++covered;
            coloured += std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}) > 40;
        }
    ASSERT_GT(covered, 2000u);
    EXPECT_GT(coloured, covered / 20);
}

// A JPEG texture in a GLB (decoded by the OpenImageIO plugin from memory; the JPEG is written
// here by OpenImageIO): the quadrants keep their colours through the lossy coding.
TEST(GltfMaterial, JpegTextureInAGlb) {
    ScratchDir dir;
    const Image png = decodePng(quadrantTexture());
    const std::string path = (dir / "q.jpg").string();
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(path, OIIO::ImageSpec(int(png.width), int(png.height), 3, OIIO::TypeDesc::UINT8)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, png.pixels.data()));
    ASSERT_TRUE(out->close());
    const std::vector<uint8_t> jpeg = readBytes(path);
    ASSERT_EQ(jpeg[0], 0xFF);
    const std::string limn = prepare(dir, writePlane(dir, "j", Storage::Glb, jpeg), "j", 2);
    const Image img = renderPlane(dir, limn);
    for (int q = 0; q < 4; ++q) {
        const auto [x, y] = kQuadrantPixel[q];
        EXPECT_EQ(bright(img.at(x, y)), expectedBright(q)) << q;
    }
}
