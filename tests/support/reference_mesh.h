// Independent reference for golden tests: a deliberately simple OBJ reader (written separately
// from lib/mesh/obj.cpp, sharing no code with it) and the counts that `limn-info --json` reports,
// computed from OpenSubdiv's Far topology (the oracle, ../shared/docs/opensubdiv.md) and the
// definitions in formats/limn.md section 5. Nothing here calls limn's libraries.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace limn::test {

struct ReferenceObj {
    int vertexCount = 0;
    std::vector<std::array<double, 3>> positions;
    std::vector<std::vector<int>> faces;   // 0-based vertex indices
    std::vector<std::vector<int>> faceUVs; // 0-based vt indices, empty when a face has none
    std::vector<std::pair<double, double>> uvs;
    std::vector<std::pair<std::pair<int, int>, float>> creases;
    std::vector<std::pair<int, float>> corners;
    std::vector<int> holes;
    std::optional<int> interpolateBoundary; // the OBJ tag value: 0 none, 1 edge+corner, 2 edge
    bool chaikin = false, smoothTriangles = false;

    // Index of the first face that uses a vertex twice, or -1.
    int firstDegenerateFace() const;
    // UVs count only when every face has them (limn drops partial UVs, formats/limn.md).
    bool hasUVs() const;
};

// Reads the OBJ subset of OpenSubdiv's regression shapes and Keenan Crane's meshes: v, vt,
// f v[/vt[/vn]] with 1-based or negative indices, `t` tags. Throws std::runtime_error.
ReferenceObj readReferenceObj(const std::string& path);
ReferenceObj parseReferenceObj(const std::string& text);

struct ReferenceCounts {
    int vertices = 0, faces = 0, edges = 0, boundaryEdges = 0, nonManifoldEdges = 0;
    std::map<int, int> faceSizes, interiorValence;
    int extraordinary = 0, regularFaces = 0, irregularFaces = 0, holeFaces = 0, uvSeamEdges = 0;
};

// Everything from OpenSubdiv's base level, with the boundary rule from the mesh's tag (else
// EDGE_ONLY). regularFaces counts the REGULAR patches at depth 0 of an adaptive patch table
// (useInfSharpPatch and useSingleCreasePatch on, generateLegacySharpCornerPatches off).
ReferenceCounts referenceCounts(const ReferenceObj& obj);

// Compares the counts with `limn-info --json` output; returns one line per differing field
// (fields in `skip` are left out). Empty when everything agrees.
std::vector<std::string> infoMismatches(const ReferenceCounts& expected, const std::string& json,
                                        const std::set<std::string>& skip = {});

} // namespace limn::test
