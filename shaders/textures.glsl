// Texture colour k(p) at a hit (docs/shading.md, "Textures"): it scales the ambient
// and diffuse reflection coefficients. Evaluated at the point g in the
// generic space of the surface that was hit (for CSG, the primitive's).
// VKRAY_TEXTURES compiles the solid textures in, VKRAY_PIXMAPS the image one.

const float TEXTURE_PI = 3.14159265358979;

#if VKRAY_PIXMAPS
layout(set = 0, binding = BINDING_PIXMAPS, rgba32ui) uniform readonly uimageBuffer pixmapTexels;
layout(set = 0, binding = BINDING_TEXELS, r32ui) uniform readonly uimageBuffer imageTexels;

// atan and asin to a few float spacings: a texel's row or column is chosen
// from them, and Vulkan lets a driver's own be 4096 spacings off (lavapipe's
// asin near -0.5 was over 8e-5 off, some 1400 spacings: a sphere's texel row
// changed where the reference saw the point 20 times the float bound clear
// of the border). Range-reduced odd polynomials, as Cephes' atanf and asinf
// reduce them: at most 2.6 spacings over 200 000 arguments, in float
// arithmetic emulated on the host.
float preciseAtanUnit(float x) {  // x in [0, inf)
    float base = 0.0;
    if (x > 2.414213562373095) {  // tan(3 pi / 8)
        base = 0.5 * TEXTURE_PI;
        x = -1.0 / x;
    } else if (x > 0.4142135623730950) {  // tan(pi / 8)
        base = 0.25 * TEXTURE_PI;
        x = (x - 1.0) / (x + 1.0);
    }
    float z = x * x;
    return base + x + x * z * (((8.05374449538e-2 * z - 1.38776856032e-1) * z +
                                 1.99777106478e-1) * z - 3.33329491539e-1);
}
float preciseAtan2(float y, float x) {
    if (x == 0.0) return y > 0.0 ? 0.5 * TEXTURE_PI : (y < 0.0 ? -0.5 * TEXTURE_PI : 0.0);
    float a = preciseAtanUnit(abs(y / x));
    if (x < 0.0) a = TEXTURE_PI - a;
    return y < 0.0 ? -a : a;
}
float preciseAsin(float x) {  // x in [-1, 1]
    float a = abs(x);
    bool far = a > 0.5;  // there asin a = pi/2 - 2 asin(sqrt((1 - a) / 2))
    float z = far ? 0.5 * (1.0 - a) : a * a;
    float s = far ? sqrt(z) : a;
    float r = s + s * z * ((((4.2163199048e-2 * z + 2.4181311049e-2) * z + 4.5470025998e-2) * z +
                            7.4953002686e-2) * z + 1.6666752422e-1);
    if (far) r = 0.5 * TEXTURE_PI - 2.0 * r;
    return x < 0.0 ? -r : r;
}

// The angle about the generic z axis as u in [0, 1].
float aroundZ(vec3 g) { return 0.5 + preciseAtan2(g.y, g.x) / (2.0 * TEXTURE_PI); }

// (u, v) of generic point g on a surface of `kind`; genericNormal tells a
// cylinder's caps (normal along z) from its wall.
vec2 surfaceUv(uint kind, vec3 g, vec3 genericNormal) {
    switch (kind) {
    case KIND_SPHERE: return vec2(aroundZ(g), 0.5 + preciseAsin(clamp(g.z, -1.0, 1.0)) / TEXTURE_PI);
    case KIND_PLANE: return fract(g.xy / 2.0 + 0.5);  // one tile every 2 units
    case KIND_SQUARE: return (g.xy + 1.0) / 2.0;
    case KIND_TAPERED_CYLINDER:
        if (genericNormal.x == 0.0 && genericNormal.y == 0.0) return (g.xy + 1.0) / 2.0;
        return vec2(aroundZ(g), g.z);
    case KIND_CUBE: {
        // The face of the axis with the largest |g|; the other two in order.
        vec3 a = abs(g);
        if (a.x >= a.y && a.x >= a.z) return (g.yz + 1.0) / 2.0;
        if (a.y >= a.z) return (g.xz + 1.0) / 2.0;
        return (g.xy + 1.0) / 2.0;
    }
    case KIND_TORUS:
        return vec2(aroundZ(g), 0.5 + preciseAtan2(g.z, sqrt(dot(g.xy, g.xy)) - TORUS_MAJOR_RADIUS) /
                                          (2.0 * TEXTURE_PI));
    default: return fract((g.xy + 1.0) / 2.0);  // meshes
    }
}

// The nearest texel at (u, v): u wraps, v is clamped, v = 1 is the top row.
vec3 pixmapTexel(uint slot, vec2 uv) {
    uvec4 image = imageLoad(pixmapTexels, int(slot));  // GpuPixmap.image
    int width = int(image.y), height = int(image.z);
    float u = fract(uv.x), v = clamp(uv.y, 0.0, 1.0);
    int x = clamp(int(floor(u * float(width))), 0, width - 1);
    int y = clamp(int(floor((1.0 - v) * float(height))), 0, height - 1);
    int first = int(image.x + 3u * (uint(y) * uint(width) + uint(x)));
    return uintBitsToFloat(uvec3(imageLoad(imageTexels, first).x, imageLoad(imageTexels, first + 1).x,
                                 imageLoad(imageTexels, first + 2).x));
}
#endif

// k(p) at generic point g of a surface of shape `kind` and material `surface`.
vec3 textureColor(GpuMaterial surface, uint kind, vec3 g, vec3 genericNormal) {
    uint code = floatBitsToUint(surface.material.w);
    vec4 parameters = surface.texture;
#if VKRAY_TEXTURES
    if (code == TEXTURE_CHECKERBOARD) {
        // Cells of side `size`, shifted half a cell so that the generic
        // shapes' faces (0 and +-1) lie inside cells, not on their borders.
        vec3 cell = floor(g / parameters.x + 0.5);
        bool odd = ((int(cell.x) + int(cell.y) + int(cell.z)) & 1) != 0;
        return odd ? parameters.yzw : vec3(1.0);
    }
    if (code == TEXTURE_WOOD) {
        // Rings of width parameters.x about the z axis, shifted half a ring
        // like the checkerboard's cells, so that radius 1 (a cylinder's wall)
        // and 0 (the axis) lie inside rings, not on their borders.
        bool odd = (int(floor(sqrt(dot(g.xy, g.xy)) / parameters.x + 0.5)) & 1) != 0;
        return odd ? parameters.yzw : vec3(1.0);
    }
#endif
#if VKRAY_PIXMAPS
    if (code == TEXTURE_IMAGE)
        return pixmapTexel(floatBitsToUint(parameters.x), surfaceUv(kind, g, genericNormal));
#endif
    return vec3(1.0);
}
