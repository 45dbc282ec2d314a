// The C interface between image_file.cpp and the OpenImageIO reader plugin (oiio_plugin.cpp),
// which is a separate shared object loaded with dlopen on first use. Plain C types only: no C++
// object or exception crosses it.
#pragma once

#include <cstddef>
#include <cstdint>

extern "C" {

// Bumped whenever a signature below changes; the loader refuses a plugin of another version.
inline constexpr int kLimnImageAbiVersion = 1;
typedef int (*LimnImageAbiVersion)(void);

// Called once by the reader with the image's size; returns where to put width * height *
// channels floats, or null to refuse (too large).
typedef float* (*LimnImageAllocate)(void* context, uint32_t width, uint32_t height,
                                    uint32_t channels);

// Reads every channel as float (8/16-bit integers scaled to [0, 1], floats as stored), rows top
// to bottom, from the file `path`, or from `bytes` (`size` of them) when not null; `path` then
// only names the format ("image.png"). Returns 0 on success, else non-zero with a NUL-terminated
// message in `error` (at most `errorSize` bytes, truncated).
typedef int (*LimnImageRead)(const char* path, const void* bytes, size_t size, void* context,
                             LimnImageAllocate allocate, char* error, size_t errorSize);

} // extern "C"
