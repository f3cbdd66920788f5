// Generic plane z = 0, normal +z.
bool intersectPlane(rvec3 o, rvec3 d, real tMin, real tMax, out real t, out rvec3 normal) {
    if (d.z == 0.0) return false;
    t = -o.z / d.z;
    normal = rvec3(0.0, 0.0, 1.0);
    return t > tMin && t < tMax;
}
