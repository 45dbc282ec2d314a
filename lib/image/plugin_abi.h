// The C interface between image_file.cpp and the OpenImageIO plugin (oiio_plugin.cpp),
// which is a separate shared object loaded with dlopen on first use. Plain C types only: no C++
// object or exception crosses it.
#pragma once

#include <cstddef>
#include <cstdint>

extern "C" {

// Bumped whenever a signature below changes; the loader refuses a plugin of another version.
inline constexpr int kLimnImageAbiVersion = 2;
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

// Called once by the writer with the encoded file's size; returns where to copy its bytes, or
// null to refuse.
typedef uint8_t* (*LimnImageAllocateBytes)(void* context, size_t size);

// Encodes width * height * channels floats (rows top to bottom, channel `names[i]` at index i,
// "A" taken as alpha and "Z" as depth) as an OpenEXR file in memory (32-bit float channels, ZIP
// compression, no time stamp or software text), handing the bytes to `allocate`. The caller
// writes them (atomically, through limn::OutputFile). Returns 0 on success, else non-zero with
// a message in `error` as above.
typedef int (*LimnImageWriteExr)(uint32_t width, uint32_t height, uint32_t channels,
                                 const char* const* names, const float* pixels, void* context,
                                 LimnImageAllocateBytes allocate, char* error, size_t errorSize);

} // extern "C"
