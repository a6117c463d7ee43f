// The one translation unit with tinygltf's implementation. tinygltf only parses JSON and
// containers here: images are decoded by the loader's own callback (ImageDecode.h, JpegDecode.h),
// so its stb_image paths are compiled out (TINYGLTF_NO_STB_IMAGE*, set for the whole target).
#define TINYGLTF_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
#include <tiny_gltf.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
