// Floats as uints that sort like the floats: for every finite a < b, ordered_bits(a) < ordered_bits(b)
// (negative floats have every bit flipped, non-negative ones the sign bit set; -0 sorts just below +0).
// So atomicMin/atomicMax on uint find float minima and maxima of any sign, in any order, exactly.
// Engine copy: surface::ordered_bits() in engine/surface/level_set.cpp.
#ifndef RANRYU_SURFACE_ORDERED_FLOAT_GLSL
#define RANRYU_SURFACE_ORDERED_FLOAT_GLSL

uint ordered_bits(float f) {
    uint u = floatBitsToUint(f);
    return (u & 0x80000000u) != 0u ? ~u : (u | 0x80000000u);
}
uvec3 ordered_bits(vec3 v) { return uvec3(ordered_bits(v.x), ordered_bits(v.y), ordered_bits(v.z)); }

float from_ordered_bits(uint u) { return uintBitsToFloat((u & 0x80000000u) != 0u ? (u & 0x7FFFFFFFu) : ~u); }
vec3 from_ordered_bits(uvec3 u) { return vec3(from_ordered_bits(u.x), from_ordered_bits(u.y), from_ordered_bits(u.z)); }

#endif
