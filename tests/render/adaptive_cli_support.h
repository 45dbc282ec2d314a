// Helpers shared by the view-adaptive tessellation's CLI tests (adaptive_*_cli_test.cpp): input
// meshes written as OBJ files, the classify | tables preparation, camera arguments, image
// comparison.
#pragma once

#include "image/srgb_image.h"
#include "test_support.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace limn::test {

// The paper's demo sphere (model_tables.h's paperSphere) of radius 5, as an OBJ file.
std::string writeSphere(const std::filesystem::path& path);
// A closed prism whose two caps are n-gons (n = 7, twisted and bulged so that nothing is flat):
// every cap vertex has valence 3 and each cap's centre, after the first level, valence n.
std::string writePrism(const std::filesystem::path& path, int n);
// limn-classify OBJ (with `classify`'s options) | limn-tables --depth `depth` into dir/in.limn.
std::string prepare(const std::string& obj, int depth, const ScratchDir& dir, std::vector<std::string> classify = {});
// "x,y,z" for --eye and --target.
std::string triple(const glm::dvec3& v);
// Pixels covered in either image (not the background colour of a's corner pixel, background in
// every view here), and of those, how many differ by more than 8/255 in a channel.
std::pair<size_t, size_t> coveredAndDiffering(const Image& a, const Image& b);

} // namespace limn::test
