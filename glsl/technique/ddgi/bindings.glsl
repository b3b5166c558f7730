// Storage names (220-239) and texture units of the ddgi family's own data (Majercik et al. 2019, 2021), for
// GLSL and C++ alike (gl/technique/ddgi/bindings.h includes this file); the units are ones
// glsl/common/bindings.glsl leaves to techniques. Only #define lines and comments.
#ifndef BOUNCE_DDGI_BINDINGS_GLSL
#define BOUNCE_DDGI_BINDINGS_GLSL

#define SSBO_DDGI_PROBES 220 // probes.glsl: per probe, xyz its offset from its grid point, w 1 active, 0 inactive
#define SSBO_DDGI_RAYS 221   // ddgi_trace.comp: per probe and ray, rgb the radiance it brought back, a the hit's
                             // distance (negative at a back face, the inside of a solid)

#define UNIT_DDGI_IRRADIANCE 21 // probes.glsl: the irradiance atlas, 8 x 8 texels per probe (6 x 6 and a border)
#define UNIT_DDGI_DEPTH 22      // probes.glsl: the distance moments' atlas, 16 x 16 per probe (14 x 14 and a border)

#endif
