// Generic square: the part of z = 0 with |x| <= 1 and |y| <= 1 (closed).
bool intersectSquare(rvec3 o, rvec3 d, real tMin, real tMax, out real t, out rvec3 normal) {
    if (d.z == 0.0) return false;
    t = -o.z / d.z;
    if (!(t > tMin && t < tMax)) return false;
    rvec2 p = o.xy + t * d.xy;
    normal = rvec3(0.0, 0.0, 1.0);
    return abs(p.x) <= 1.0 && abs(p.y) <= 1.0;
}
