// Malformed OBJ files, each with the message that refuses it (line or element named), for the
// reader in process and for limn-classify.
#pragma once

#include <string>
#include <vector>

namespace limn::test::hostile_obj {

using namespace std::string_literals;

inline const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

struct Case {
    std::string name, obj, message;
};

inline const std::vector<Case> kCases = {
    {"bad_number", "v 1 x 3\n", "line 1: 'x' is not a number (vertex coordinate)"},
    {"number_out_of_range", "v 1e999 0 0\n", "line 1: '1e999' is not a number"},
    {"short_vertex", "v 1 2\n", "line 1: a 'v' line needs 3 coordinates"},
    {"bad_texcoord", "vt u\n", "line 1: 'u' is not a number (texture coordinate)"},
    {"nan_position", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
     "vertex 0 has a non-finite position (NaN or Inf)"},
    {"inf_position", kTriangle + "v 0 0 inf\nf 1 2 4\n", "vertex 3 has a non-finite position"},
    {"index_zero", kTriangle + "f 0 1 2\n", "line 4: vertex index 0 is invalid"},
    {"index_not_a_number", kTriangle + "f 1 2 three\n", "line 4: 'three' is not an integer"},
    {"relative_index_too_negative", kTriangle + "f -4 -2 -1\n",
     "line 4: vertex index -4 is before the first"},
    {"index_past_the_end", kTriangle + "f 1 2 4\n",
     "face 0 refers to vertex 3 but there are only 3"},
    {"two_vertex_face", kTriangle + "f 1 2\n",
     "line 4: a face needs at least 3 vertices, this one has 2"},
    {"empty_face", kTriangle + "f\n", "line 4: a face needs at least 3 vertices, this one has 0"},
    {"degenerate_face", kTriangle + "f 1 2 2\n", "face 0 is degenerate: it uses vertex 1 twice"},
    {"uv_index_past_the_end", kTriangle + "vt 0 0\nf 1/1 2/2 3/1\n",
     "corner 1 refers to UV 1 but there are only 1"},
    {"uv_beyond_float", kTriangle + "vt 1e39 0\nf 1/1 2/1 3/1\n",
     "UV 0 is 1e+39 from the origin, beyond the 1e18"},
    {"uv_index_zero", kTriangle + "vt 0 0\nf 1/1 2/0 3/1\n",
     "texture coordinate index 0 is invalid"},
    {"uv_on_some_corners", kTriangle + "vt 0 0\nf 1/1 2 3/1\n",
     "some corners of this face have a texture coordinate, some not"},
    {"empty_file", "", "the mesh has no vertices"},
    {"comments_only", "# nothing\n\n", "the mesh has no vertices"},
    {"no_faces", kTriangle, "the mesh has no faces"},
    {"binary_data", "v 0 0 0\n\x01\x02\0\x03\n"s, "line 2: binary data in an OBJ file"},
    {"tag_truncated_floats", kTriangle + "f 1 2 3\nt crease 2/1/0 0 1\n",
     "line 5: tag 'crease' has fewer floats than it declares"},
    {"tag_truncated_ints", kTriangle + "f 1 2 3\nt crease 2/1/0 0\n",
     "line 5: tag 'crease' has fewer ints than it declares"},
    {"tag_bad_counts", kTriangle + "f 1 2 3\nt crease 2/1\n",
     "line 5: tag counts must look like nint/nfloat/nstring"},
    {"tag_no_counts", kTriangle + "f 1 2 3\nt crease\n", "line 5: a 't' line needs a name"},
    {"tag_huge_counts", kTriangle + "f 1 2 3\nt crease 99999999/1/0 0 1 1\n",
     "line 5: tag counts out of range"},
    {"crease_vertex_out_of_range", kTriangle + "f 1 2 3\nt crease 2/1/0 0 9 1\n",
     "crease tag 0 (0,9) refers to a vertex out of range"},
    {"crease_negative_vertex", kTriangle + "f 1 2 3\nt crease 2/1/0 -1 0 1\n",
     "line 5: crease vertex index -1 is out of range"},
    {"crease_nan", kTriangle + "f 1 2 3\nt crease 2/1/0 0 1 nan\n", "it must be finite and >= 0"},
    {"corner_out_of_range", kTriangle + "f 1 2 3\nt corner 1/1/0 3 1\n",
     "corner tag 0 (vertex 3) refers to a vertex out of range"},
    {"hole_out_of_range", kTriangle + "f 1 2 3\nt hole 1/0/0 1\n",
     "hole tag 0 refers to face 1 but there are only 1"},
    {"bad_boundary_rule", kTriangle + "f 1 2 3\nt interpolateboundary 1/0/0 7\n",
     "line 5: interpolateboundary must be 0, 1 or 2, not 7"},
    {"bad_crease_method", kTriangle + "f 1 2 3\nt creasemethod 0/0/1 sharp\n",
     "line 5: creasemethod must be normal or chaikin, not 'sharp'"},
};

} // namespace limn::test::hostile_obj
