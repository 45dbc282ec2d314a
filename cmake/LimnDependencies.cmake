# Every dependency comes from Debian 12 packages (scripts/setup.sh installs them).
# The recipes are the ones known to work here (../shared/docs/toolchain.md).
find_package(Threads REQUIRED)
find_package(PkgConfig REQUIRED)
find_package(glm CONFIG REQUIRED)
find_package(OpenMesh CONFIG REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
# Compressed glTF geometry, each decoded by its own library: KHR_draco_mesh_compression (Draco)
# and EXT_/KHR_meshopt_compression (meshoptimizer); nlohmann's JSON (tinygltf's own parser) reads
# the extensions before tinygltf does (lib/mesh/gltf_prepass.cpp).
find_package(draco CONFIG REQUIRED)
# Debian's libdraco.so bundles its own build of tinygltf, a different one, and exports its symbols:
# an executable that looked in libdraco before libtinygltf called Draco's TinyGLTF on limn's
# (limn-render aborted, 'free(): invalid pointer'). libtinygltf comes first in every executable's
# list of libraries (its first DT_NEEDED), so the dynamic linker finds its symbols there. (Draco's
# static archive is no way out: it brings its tinygltf in to define the stb functions libtinygltf
# needs.)
get_target_property(LIMN_TINYGLTF_LOCATION TinyGLTF::TinyGLTF LOCATION)
string(APPEND CMAKE_EXE_LINKER_FLAGS " -Wl,--push-state,--no-as-needed ${LIMN_TINYGLTF_LOCATION} -Wl,--pop-state")
find_package(meshoptimizer CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_package(Vulkan REQUIRED COMPONENTS glslangValidator)
pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)

# Debian's OpenSubdiv CMake config names static libraries the package does not ship.
find_path(OSD_INCLUDE_DIR opensubdiv/version.h REQUIRED)
find_library(OSD_CPU_LIBRARY osdCPU REQUIRED)
if(NOT TARGET OpenSubdiv::osdCPU)
  add_library(OpenSubdiv::osdCPU SHARED IMPORTED)
  set_target_properties(OpenSubdiv::osdCPU PROPERTIES
    IMPORTED_LOCATION "${OSD_CPU_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OSD_INCLUDE_DIR}")
endif()

find_package(GTest CONFIG REQUIRED)
find_package(benchmark CONFIG QUIET)
