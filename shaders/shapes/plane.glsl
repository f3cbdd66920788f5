// Generic plane z = 0, normal +z.
bool intersectPlane(vec3 o, vec3 d, float tMin, float tMax, out float t, out vec3 normal) {
    if (d.z == 0.0) return false;
    t = -o.z / d.z;
    normal = vec3(0.0, 0.0, 1.0);
    return t > tMin && t < tMax;
}
