// Random and quasi-random numbers of every family: integer hashes, the streams built on them, radical
// inverses, and the one way a random word becomes a float in [0, 1).
#ifndef BOUNCE_RANDOM_GLSL
#define BOUNCE_RANDOM_GLSL

// The top 24 bits of a random word as a float in [0, 1): every value exact (24 bits fit a float's
// mantissa), the largest 1 - 2^-24, so that a draw never reaches 1. Every uniform draw goes through it.
float unitFloat(uint bits)
{
    return float(bits >> 8) * (1.0 / 16777216.0);
}

// A 32-bit integer hash (Wellons' "lowbias32", from his hash prospector): every input bit reaches every
// output bit. The point gathers' random numbers (microrender/gather.comp, pointproj/gather.comp).
uint hashU(uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// The next number in [0, 1) of a stream of hashU: the state steps by the golden ratio's 32-bit fraction
// (a Weyl sequence) and is hashed. Point projection's draws (pointproj/gather.comp).
float random01(inout uint state)
{
    state = hashU(state + 0x9e3779b9u);
    return unitFloat(state);
}

// PCG (O'Neill 2014) as a hash and as a stream: the photon family's random numbers (one stream per photon
// path, seeded by its index, in photon_trace.comp; hashes of pixels, clusters and rays in the gathers).
uint pcgHash(uint v)
{
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
float nextRandom(inout uint state)
{
    state = state * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    word = (word >> 22u) ^ word;
    return unitFloat(word);
}

// Two numbers in [0, 1) from one hash word h: h's own and its PCG hash's. A ray's or a pixel's pair in
// the photon gathers (photon_gather.comp, photon_gather.glsl, photon_glossy.comp).
vec2 unitPair(uint h)
{
    return vec2(unitFloat(h), unitFloat(pcgHash(h)));
}

// Radical inverse in base 2 (van der Corput), and in any base, for low-discrepancy sets (the photons'
// emission in photon_trace.comp, the gathers' Hammersley sets).
float radicalInverse2(uint i)
{
    return unitFloat(bitfieldReverse(i));
}
float radicalInverse(uint i, uint base)
{
    float inv = 1.0 / float(base), f = inv, r = 0.0;
    while (i > 0u) {
        r += f * float(i % base);
        i /= base;
        f *= inv;
    }
    return min(r, 0.99999994);
}

#endif
