// The one translation unit that compiles stb_image and stb_image_write. Only
// the PNG and BMP decoders are built (readImage reads .png, and .bmp for
// Hill's pixmaps); each is reached only through its own extension and
// signature (image_io.cpp), and fuzzed (fuzz/image_fuzz.cpp).
#define STBI_ONLY_PNG
#define STBI_ONLY_BMP
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
