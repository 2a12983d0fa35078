// Floats as ints whose signed order is the floats' order, for atomicMin and atomicMax over
// floats (the glass extent's box, the BVH build's centroid bounds).
#ifndef REFRACTION_ORDERED_GLSL
#define REFRACTION_ORDERED_GLSL

int floatToOrdered(float f) {
    int i = floatBitsToInt(f);
    return i < 0 ? i ^ 0x7FFFFFFF : i;
}

float orderedToFloat(int i) {
    return intBitsToFloat(i < 0 ? i ^ 0x7FFFFFFF : i);
}

#endif
