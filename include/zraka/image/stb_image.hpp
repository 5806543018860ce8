#pragma once
// stb_image, compiled once per program with the decoders zraka reads: PNG (reference images,
// testing.hpp) and Radiance HDR (environment maps, environment_file.hpp). If the including
// program already included stb_image.h itself, its declarations (and its one implementation)
// are used instead; a program that compiles stb_image's implementation itself must include it
// before any zraka header, not after, and keep the PNG and HDR decoders.
#ifndef STBI_INCLUDE_STB_IMAGE_H
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_HDR
#include <stb/stb_image.h>
#undef STB_IMAGE_IMPLEMENTATION
#endif
