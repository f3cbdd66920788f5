// The scene's read-only arrays, read through storage texel buffers: each
// structure of layout.h is a run of uvec4 texels (its *_TEXELS), loaded
// with imageLoad and its floats taken back bit for bit. On llvmpipe an
// imageLoad is a few vector loads and a transpose with no branch, where a
// storage-buffer read inside a loop or an if is a scalar loop over the 8
// lanes, even when they read one address (docs/lavapipe.md); on a discrete
// GPU both go through its caches alike. Included by trace.comp; the mesh,
// CSG and pixmap arrays are declared beside their code.

layout(set = 0, binding = BINDING_OBJECTS, rgba32ui) uniform readonly uimageBuffer objectGeometryTexels;
layout(set = 0, binding = BINDING_MATERIALS, rgba32ui) uniform readonly uimageBuffer materialTexels;

vec4 texelAsVec4(uvec4 texel) { return uintBitsToFloat(texel); }

// Row `row` (0..2) of GpuObjectGeometry[index].objectFromWorld.
vec4 objectRow(uint index, uint row) {
    return texelAsVec4(imageLoad(objectGeometryTexels, int(index * OBJECT_GEOMETRY_TEXELS + row)));
}

// GpuObjectGeometry[index].shape.
uvec4 objectShape(uint index) {
    return imageLoad(objectGeometryTexels, int(index * OBJECT_GEOMETRY_TEXELS + 3u));
}

GpuMaterial materialOf(uint index) {
    int first = int(index * MATERIAL_TEXELS);
    return GpuMaterial(texelAsVec4(imageLoad(materialTexels, first)),
                       texelAsVec4(imageLoad(materialTexels, first + 1)),
                       texelAsVec4(imageLoad(materialTexels, first + 2)),
                       texelAsVec4(imageLoad(materialTexels, first + 3)),
                       texelAsVec4(imageLoad(materialTexels, first + 4)),
                       texelAsVec4(imageLoad(materialTexels, first + 5)));
}

#if VKRAY_LIGHTS
layout(set = 0, binding = BINDING_LIGHTS, rgba32ui) uniform readonly uimageBuffer lightTexels;

GpuLight lightOf(uint index) {
    int first = int(index * LIGHT_TEXELS);
    return GpuLight(texelAsVec4(imageLoad(lightTexels, first)),
                    texelAsVec4(imageLoad(lightTexels, first + 1)));
}
#endif

// Node `index` of a BVH read through texel buffer `nodes` (GpuBvhNode[]).
#define BVH_NODE(nodes, index)                                                               \
    GpuBvhNode(texelAsVec4(imageLoad(nodes, int((index) * BVH_NODE_TEXELS))),                 \
               texelAsVec4(imageLoad(nodes, int((index) * BVH_NODE_TEXELS + 1u))))

#if VKRAY_OBJECT_BVH
layout(set = 0, binding = BINDING_OBJECT_NODES, rgba32ui) uniform readonly uimageBuffer objectNodeTexels;
layout(set = 0, binding = BINDING_OBJECT_INDEX, r32ui) uniform readonly uimageBuffer objectIndexTexels;

GpuBvhNode objectNode(uint index) { return BVH_NODE(objectNodeTexels, index); }
uint objectAt(uint entry) { return imageLoad(objectIndexTexels, int(entry)).x; }
#endif

#if VKRAY_PRECISION_FP64
layout(set = 0, binding = BINDING_DOUBLE_OBJECTS, rgba32ui) uniform readonly uimageBuffer doubleObjectTexels;

// A dvec4 from its two texels: x y, then z w, each double as (low, high) words.
dvec4 doubleTexels(int first) {
    uvec4 xy = imageLoad(doubleObjectTexels, first), zw = imageLoad(doubleObjectTexels, first + 1);
    return dvec4(packDouble2x32(xy.xy), packDouble2x32(xy.zw), packDouble2x32(zw.xy),
                 packDouble2x32(zw.zw));
}

// Row `row` (0..2) of GpuDoubleObject[index].objectFromWorld.
dvec4 doubleObjectRow(uint index, uint row) {
    return doubleTexels(int(index * DOUBLE_OBJECT_TEXELS + 2u * row));
}

// GpuDoubleObject[index].parameters.
dvec4 doubleObjectParameters(uint index) {
    return doubleTexels(int(index * DOUBLE_OBJECT_TEXELS + 6u));
}
#endif
