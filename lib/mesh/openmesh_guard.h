// Checks that PLY and OFF bytes are safe to hand to OpenMesh's readers (used by openmesh_io.cpp).
// OpenMesh trusts its input: hostile headers made it write through an empty vector, read counts
// into uninitialized variables, loop billions of times and reserve gigabytes (found by fuzz_ply;
// openmesh_guard.cpp lists each case). Each check throws Error(BadInput) naming the problem.
#pragma once

#include "base/warnings.h"

#include <string_view>

namespace limn {

// OFF: the header keyword (OpenMesh reads only plain text OFF correctly from a stream) and the
// counts against the bytes that follow.
void checkOffForOpenMesh(std::string_view text, Warnings& warnings);

// PLY: the header in the strict line grammar of the PLY specification, the element counts
// against the bytes that follow, and in text PLY every list length against the data.
void checkPlyForOpenMesh(std::string_view text);

} // namespace limn
