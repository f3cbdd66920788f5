// Every variant flag is defined by the host, 0 or 1, and the count
// VKRAY_OBJECTS (host/gpu/shader_variant.cpp,
// variantFlags(): the one list, which a test holds this file to). GLSL reads
// an undefined name in `#if` as 0 without a word, so a flag the host forgot
// would leave code out in silence: here it stops the compile instead.
#if !defined(VKRAY_SHAPE_SPHERE) || !defined(VKRAY_SHAPE_PLANE) || !defined(VKRAY_SHAPE_SQUARE)
#error "a shape flag (VKRAY_SHAPE_SPHERE, _PLANE, _SQUARE) is not defined: the host defines every variant flag, 0 or 1"
#endif
#if !defined(VKRAY_SHAPE_CUBE) || !defined(VKRAY_SHAPE_TAPERED_CYLINDER) || !defined(VKRAY_SHAPE_TORUS)
#error "a shape flag (VKRAY_SHAPE_CUBE, _TAPERED_CYLINDER, _TORUS) is not defined: the host defines every variant flag, 0 or 1"
#endif
#if !defined(VKRAY_SHAPE_MESH) || !defined(VKRAY_CSG)
#error "VKRAY_SHAPE_MESH or VKRAY_CSG is not defined: the host defines every variant flag, 0 or 1"
#endif
#if !defined(VKRAY_SHADOWS) || !defined(VKRAY_REFLECTION) || !defined(VKRAY_REFRACTION)
#error "a shading flag (VKRAY_SHADOWS, _REFLECTION, _REFRACTION) is not defined: the host defines every variant flag, 0 or 1"
#endif
#if !defined(VKRAY_TEXTURES) || !defined(VKRAY_PIXMAPS) || !defined(VKRAY_ANTIALIAS)
#error "a shading flag (VKRAY_TEXTURES, _PIXMAPS, _ANTIALIAS) is not defined: the host defines every variant flag, 0 or 1"
#endif
#if !defined(VKRAY_LIGHTS) || !defined(VKRAY_OBJECT_BVH) || !defined(VKRAY_DEBUG_PIXEL)
#error "VKRAY_LIGHTS, VKRAY_OBJECT_BVH or VKRAY_DEBUG_PIXEL is not defined: the host defines every variant flag, 0 or 1"
#endif
#if !defined(VKRAY_STRESS_OUTPUT) || !defined(VKRAY_BLOCKS) || !defined(VKRAY_AOVS)
#error "VKRAY_STRESS_OUTPUT, VKRAY_BLOCKS or VKRAY_AOVS is not defined: the host defines every variant flag, 0 or 1"
#endif
#if !defined(VKRAY_PRECISION_NAIVE) || !defined(VKRAY_PRECISION_FP64) || !defined(VKRAY_FAULT_NO_OFFSET)
#error "VKRAY_PRECISION_NAIVE, VKRAY_PRECISION_FP64 or VKRAY_FAULT_NO_OFFSET is not defined: the host defines every variant flag, 0 or 1"
#endif
#if !defined(VKRAY_KEEP_TORI) || !defined(VKRAY_FEELER_HINTS) || !defined(VKRAY_WORLD_TRIANGLES)
#error "VKRAY_KEEP_TORI, VKRAY_FEELER_HINTS or VKRAY_WORLD_TRIANGLES is not defined: the host defines every variant flag, 0 or 1"
#endif
#if !defined(VKRAY_RAY_QUERY)
#error "VKRAY_RAY_QUERY is not defined: the host defines every variant flag, 0 or 1"
#endif
#if !defined(VKRAY_OBJECTS)
#error "VKRAY_OBJECTS is not defined: the host defines it, the object count of an unrolled walk or 0"
#endif
