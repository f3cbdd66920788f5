// The one translation unit that compiles stb_image and stb_image_write. Only
// the PNG decoder is built: readImage accepts .png files alone, and the other
// decoders would be untested attack surface for files named *.png.
#define STBI_ONLY_PNG
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
