#include "mesh/openmesh_io.h"

#include "base/error.h"
#include "mesh/openmesh_guard.h"
#include "mesh/text_format.h"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/Mesh/BaseKernel.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <map>
#include <sstream>

namespace limn {

namespace {

using namespace OpenMesh;

// Records what OpenMesh's PLY/OFF readers parse, without building a half-edge structure.
// OpenMesh hands PLY properties it has no slot for to a property kernel (Options::Custom). That
// is how MeshLab's per-corner "texcoord" face lists, which writePly writes, reach limn; without a
// kernel OpenMesh reads only a list's first number and misreads every face after it.
class PropertyKernel : public BaseKernel {
public:
    size_t n_vertices() const override { return vertices_; }
    size_t n_faces() const override { return faces_; }
    // Keeps a slot in every property for each vertex and face read so far.
    void grow(size_t vertices, size_t faces) {
        if (vertices != vertices_) vprops_resize(vertices_ = vertices);
        if (faces != faces_) fprops_resize(faces_ = faces);
    }

private:
    size_t vertices_ = 0, faces_ = 0;
};

class RecordingImporter : public IO::BaseImporter {
public:
    Mesh mesh;
    std::vector<glm::dvec2> vertexUV;
    bool hasVertexUV = false;
    std::vector<std::vector<glm::dvec2>> faceUV; // per face, per corner (PLY face texcoord lists)
    bool hasFaceUV = false;
    size_t edges = 0;

    VertexHandle add_vertex(const Vec3f& p) override { return add_vertex(Vec3d(p)); }
    VertexHandle add_vertex(const Vec3d& p) override {
        mesh.positions.push_back({p[0], p[1], p[2]});
        vertexUV.emplace_back(0.0, 0.0);
        properties.grow(mesh.positions.size(), mesh.faceCount());
        return VertexHandle(static_cast<int>(mesh.positions.size() - 1));
    }
    VertexHandle add_vertex() override { return add_vertex(Vec3d(0, 0, 0)); }
    HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(-1); }
    FaceHandle add_face(const VHandles& indices) override {
        std::vector<uint32_t> face;
        face.reserve(indices.size());
        for (auto vh : indices) {
            if (vh.idx() < 0) throwBadInput("a face refers to a negative vertex index");
            face.push_back(static_cast<uint32_t>(vh.idx()));
        }
        mesh.addFace(face);
        faceUV.emplace_back();
        properties.grow(mesh.positions.size(), mesh.faceCount());
        return FaceHandle(static_cast<int>(mesh.faceCount() - 1));
    }
    FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(-1); }
    void add_face_texcoords(FaceHandle fh, VertexHandle, const std::vector<Vec2f>& tc) override {
        if (fh.idx() < 0 || static_cast<size_t>(fh.idx()) >= faceUV.size()) return;
        auto& dst = faceUV[fh.idx()];
        dst.clear();
        for (const auto& t : tc) dst.emplace_back(t[0], t[1]);
        hasFaceUV = true;
    }
    void add_face_texcoords(FaceHandle fh, VertexHandle vh,
                            const std::vector<Vec3f>& tc) override {
        std::vector<Vec2f> t2;
        for (const auto& t : tc) t2.emplace_back(t[0], t[1]);
        add_face_texcoords(fh, vh, t2);
    }
    void set_texcoord(VertexHandle vh, const Vec2f& t) override {
        if (vh.idx() >= 0 && static_cast<size_t>(vh.idx()) < vertexUV.size()) {
            vertexUV[vh.idx()] = {t[0], t[1]};
            hasVertexUV = true;
        }
    }
    void set_texcoord(VertexHandle vh, const Vec3f& t) override { set_texcoord(vh, Vec2f(t[0], t[1])); }
    void set_point(VertexHandle vh, const Vec3f& p) override {
        if (vh.idx() >= 0 && static_cast<size_t>(vh.idx()) < mesh.positions.size())
            mesh.positions[vh.idx()] = {p[0], p[1], p[2]};
    }
    // Attributes limn does not use.
    void set_face_texindex(FaceHandle, int) override {}
    void set_halfedge(VertexHandle, HalfedgeHandle) override {}
    void set_normal(VertexHandle, const Vec3f&) override {}
    void set_normal(VertexHandle, const Vec3d&) override {}
    void set_color(VertexHandle, const Vec3uc&) override {}
    void set_color(VertexHandle, const Vec4uc&) override {}
    void set_color(VertexHandle, const Vec3f&) override {}
    void set_color(VertexHandle, const Vec4f&) override {}
    void set_status(VertexHandle, const Attributes::StatusInfo&) override {}
    void set_next(HalfedgeHandle, HalfedgeHandle) override {}
    void set_face(HalfedgeHandle, FaceHandle) override {}
    void request_face_texcoords2D() override {}
    void set_texcoord(HalfedgeHandle, const Vec2f&) override {}
    void set_texcoord(HalfedgeHandle, const Vec3f&) override {}
    void set_status(HalfedgeHandle, const Attributes::StatusInfo&) override {}
    void set_color(EdgeHandle, const Vec3uc&) override {}
    void set_color(EdgeHandle, const Vec4uc&) override {}
    void set_color(EdgeHandle, const Vec3f&) override {}
    void set_color(EdgeHandle, const Vec4f&) override {}
    void set_status(EdgeHandle, const Attributes::StatusInfo&) override {}
    void set_normal(FaceHandle, const Vec3f&) override {}
    void set_normal(FaceHandle, const Vec3d&) override {}
    void set_color(FaceHandle, const Vec3uc&) override {}
    void set_color(FaceHandle, const Vec4uc&) override {}
    void set_color(FaceHandle, const Vec3f&) override {}
    void set_color(FaceHandle, const Vec4f&) override {}
    void set_status(FaceHandle, const Attributes::StatusInfo&) override {}
    void add_texture_information(int, std::string) override {}
    size_t n_vertices() const override { return mesh.positions.size(); }
    size_t n_faces() const override { return mesh.faceCount(); }
    size_t n_edges() const override { return edges; }
    BaseKernel* kernel() override { return &properties; }

    PropertyKernel properties;

    // Per-corner UVs from a PLY face list "texcoord" (u0 v0 u1 v1 ...), of floats or doubles.
    template <class T>
    void takeFaceTexcoords() {
        FPropHandleT<std::vector<T>> handle;
        if (!properties.get_property_handle(handle, "texcoord")) return;
        for (size_t f = 0; f < faceUV.size(); ++f) {
            const auto& values = properties.property(handle, FaceHandle(static_cast<int>(f)));
            faceUV[f].clear();
            for (size_t i = 0; i + 1 < values.size(); i += 2)
                faceUV[f].emplace_back(values[i], values[i + 1]);
            if (values.size() % 2) faceUV[f].emplace_back(); // caught as a count mismatch
        }
        hasFaceUV = true;
    }
};

// OpenMesh reports parse errors on its own error stream; limn reports them itself.
struct QuietOpenMesh {
    QuietOpenMesh() {
        omerr().disable();
        omlog().disable();
        omout().disable();
    }
};

template <class T>
void appendXYZ(std::string& out, const T& p) {
    appendNumber(out, p.x);
    out += ' ';
    appendNumber(out, p.y);
    out += ' ';
    appendNumber(out, p.z);
}

// The vertex lines PLY and OFF both write: "x y z", one per vertex.
void appendPositionLines(std::string& out, const Mesh& m) {
    for (const auto& p : m.positions) {
        appendXYZ(out, p);
        out += '\n';
    }
}

// A face's "n v0 v1 ..." of PLY's and OFF's face lines.
void appendFaceVertices(std::string& out, std::span<const uint32_t> face) {
    out += std::to_string(face.size());
    for (uint32_t v : face) out += " " + std::to_string(v);
}

} // namespace

Mesh readWithOpenMesh(std::span<const uint8_t> bytes, const std::string& extension,
                      Warnings& warnings) {
    static QuietOpenMesh quiet;
    (void)quiet;
    std::string text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    if (extension == ".off")
        checkOffForOpenMesh(text, warnings);
    else
        checkPlyForOpenMesh(text);
    // A failed read throws, which ends OpenMesh's loops that do not stop at the end of the data
    // (openmesh_guard.cpp).
    std::istringstream in(text, std::ios::binary);
    in.exceptions(std::ios::failbit | std::ios::badbit);
    RecordingImporter importer;
    IO::Options options =
        IO::Options::VertexTexCoord | IO::Options::FaceTexCoord | IO::Options::Custom;
    try {
        if (!IO::IOManager().read(in, extension, importer, options))
            throwBadInput("OpenMesh could not parse this " + extension.substr(1) +
                          " file (malformed header or data)");
    } catch (const std::ios_base::failure&) {
        throwBadInput("the " + extension.substr(1) +
                      " data ends early or has a malformed value (counts in the header, or a "
                      "face's vertex count, exceed the data)");
    }
    importer.takeFaceTexcoords<float>();
    importer.takeFaceTexcoords<double>();
    Mesh m = std::move(importer.mesh);
    if (importer.hasFaceUV) {
        for (size_t f = 0; f < m.faceCount(); ++f) {
            const auto& uv = importer.faceUV[f];
            if (uv.size() != m.faceSize(f))
                throwBadInput("face " + std::to_string(f) + " has " + std::to_string(uv.size()) +
                              " texture coordinates for " + std::to_string(m.faceSize(f)) +
                              " corners");
            for (const auto& t : uv) {
                m.uvIndices.push_back(static_cast<uint32_t>(m.uvs.size()));
                m.uvs.push_back(t);
            }
        }
    } else if (importer.hasVertexUV) {
        m.uvs = importer.vertexUV;
        m.uvIndices = m.faceVertices;
    }
    validateMesh(m);
    return m;
}

std::string writePly(const Mesh& m) {
    std::string out = "ply\nformat ascii 1.0\ncomment written by limn\n";
    out += "element vertex " + std::to_string(m.vertexCount()) + "\n";
    out += "property double x\nproperty double y\nproperty double z\n";
    out += "element face " + std::to_string(m.faceCount()) + "\n";
    out += "property list uchar int vertex_indices\n";
    if (m.hasUVs()) out += "property list uchar float texcoord\n";
    out += "end_header\n";
    appendPositionLines(out, m);
    for (size_t f = 0; f < m.faceCount(); ++f) {
        auto face = m.face(f);
        appendFaceVertices(out, face);
        if (m.hasUVs()) {
            out += " " + std::to_string(face.size() * 2);
            for (uint32_t t : m.faceUVs(f)) {
                out += ' ';
                appendNumber(out, static_cast<float>(m.uvs[t].x));
                out += ' ';
                appendNumber(out, static_cast<float>(m.uvs[t].y));
            }
        }
        out += '\n';
    }
    return out;
}

std::string writeOff(const Mesh& m) {
    std::string out =
        "OFF\n" + std::to_string(m.vertexCount()) + " " + std::to_string(m.faceCount()) + " 0\n";
    appendPositionLines(out, m);
    for (size_t f = 0; f < m.faceCount(); ++f) {
        appendFaceVertices(out, m.face(f));
        out += '\n';
    }
    return out;
}

} // namespace limn
