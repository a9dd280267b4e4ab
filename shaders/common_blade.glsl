// Blade geometry shared by the passes (physics, culling, drawing). The C++ mirror is in
// runtime/src/seeding.cpp (bladeWidthDirection) and the CPU reference.

const float MEADOW_PI = 3.14159265358979;

// Reference tangent of a surface with normal `up`: the first axis of the blade's turntable. A
// direction angle of 0 puts the blade's width along it; the angle turns the width about `up`.
vec3 bladeReferenceTangent(vec3 up) {
    // World +Z is crossed with up unless up is nearly parallel to it, then world +X is.
    vec3 axis = abs(up.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    return normalize(cross(up, axis));
}

// Unit width direction (the blade's bitangent, Jahrmann & Wimmer 2017, Sec. 3): the reference
// tangent turned by the direction angle about up.
vec3 bladeWidthDirection(vec3 up, float directionAngle) {
    vec3 t = bladeReferenceTangent(up);
    vec3 b = cross(up, t);
    return cos(directionAngle) * t + sin(directionAngle) * b;
}

// Point on the quadratic Bezier spine B(v) = (1-v)^2 v0 + 2(1-v)v v1 + v^2 v2, by de Casteljau
// (Jahrmann & Wimmer 2017, Sec. 6.1), also returning the unit tangent.
vec3 bladeSpinePoint(vec3 v0, vec3 v1, vec3 v2, float v, out vec3 tangent) {
    vec3 a = mix(v0, v1, v);
    vec3 b = mix(v1, v2, v);
    vec3 d = b - a;
    tangent = length(d) > 1e-7 ? normalize(d) : normalize(v2 - v0 + vec3(0.0, 1e-6, 0.0));
    return mix(a, b, v);
}
