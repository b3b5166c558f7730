// Ray casting against the scene's triangles on the GPU: the BVH of core/bvh.h (its header says how it
// is built and laid out), uploaded by gl/frame/ray_caster.h. Usable from compute and fragment shaders.
//
//   bool closestHit(vec3 origin, vec3 dir, float tMin, float tMax, out Hit hit); // tMin < t < tMax
//   bool anyHit(vec3 origin, vec3 dir, float tMin, float tMax);
//
// dir need not be unit length: t is in units of dir. Hit.triangle is the global triangle index (meshes
// in order, triangles in order: gl::GpuScene's index-buffer order); hit point =
// (1 - b.x - b.y) v0 + b.x v1 + b.y v2.
//
// The walk needs no stack (a multiple-threaded BVH, Hachisuka 2015): each of six copies of the tree is
// threaded depth-first with its children in the order a ray along one major direction meets them; a
// node's miss link skips its subtree. llvmpipe runs every masked loop iteration on all lanes, so a
// per-lane stack array would cost every lane every push; here a lane carries one int.
// The triangle test is the watertight one of Woop, Benthin & Wald 2013 (JCGT 2(1)); `precise` keeps
// the compiler from fusing the edge functions differently for the two triangles sharing an edge.
//
// Alpha masks (glTF MASK): with ALPHA_MASK defined (RayCaster::defines(), only for scenes that have
// masked materials) a hit in a mask's hole is skipped and the walk goes on, as Embree's filter does in
// the path tracer. The test reads the triangle's material, uvs and base-colour texture: the frame's
// scene data must be bound (Frame::bindSceneData), and a shader that includes common/scene.glsl itself
// must define SCENE_GEOMETRY before it.
#ifndef BOUNCE_RAYCAST_GLSL
#define BOUNCE_RAYCAST_GLSL

// The SSBO binding points (gl/frame/ray_caster.h has the same numbers as C++ constants).
#include "common/bindings.glsl"

#ifdef ALPHA_MASK
#ifndef SCENE_GEOMETRY
#define SCENE_GEOMETRY
#endif
#include "common/scene.glsl"
#include "common/base_color.glsl"

// Whether barycentrics b of the triangle lie in a hole of its material's mask (core::Material::cutsOut).
bool bvhCutOut(uint triangle, vec2 b)
{
    Material m = materials[sceneTriangleMaterial(triangle)];
    if (!(intBitsToFloat(m.flags.z) > 0.0)) return false; // opaque: no texture read
    vec2 uv = sceneTriangleUv(triangle, b);
    return alphaCutOut(m, baseColorTexel(m, uv).a);
}
#endif

struct BvhNode {
    vec3 lo;
    int miss;    // next node when the box is missed or the subtree is done; -1 ends the walk
    vec3 hi;
    int leaf;    // -1: interior (first child = next node); else first triangle << 5 | count
};

struct BvhTriangle {
    vec3 v0;
    uint index;  // global triangle index
    vec3 v1;
    float pad1;
    vec3 v2;
    float pad2;
};

layout(std430, binding = SSBO_BVH_NODES) readonly buffer BvhNodes { BvhNode bvhNodes[]; };
layout(std430, binding = SSBO_BVH_TRIANGLES) readonly buffer BvhTriangles { BvhTriangle bvhTriangles[]; };

struct Hit {
    uint triangle;
    float t;
    vec2 b;      // barycentrics of v1 and v2 (Embree's u, v)
};

// The ray as the triangle test and the slab test want it (core::WatertightRay).
struct BvhRay {
    vec3 origin;
    vec3 rowX, rowY, rowZ; // the shear that takes the ray to +z (Woop et al. 2013, Sec. 3)
    vec3 invDir;
    int root;              // first node of the copy for the ray's major direction
};

// a * b - p exactly, for p = a * b rounded (Dekker 1971, with Veltkamp's split of each factor into halves
// of 12 bits whose products are exact): every product and sum rounded as written (precise) and no fma,
// which GLSL lets a driver round twice (an fma-based residual was wrong on llvmpipe).
float rayProductError(float a, float b, float p)
{
    precise float ca = 4097.0 * a, cb = 4097.0 * b;
    precise float ah = ca - (ca - a), bh = cb - (cb - b);
    precise float al = a - ah, bl = b - bh;
    precise float e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    return e;
}

// a - q b for a quotient q near a / b: a - q b rounded is exact there (Sterbenz), less the product's error.
float rayResidual(float a, float b, float q)
{
    precise float p = q * b;
    precise float r = (a - p) - rayProductError(q, b, p);
    return r;
}

// a / b rounded to nearest, as IEEE 754 divides and so as core::Bvh divides on the CPU. GLSL allows 2.5 ulp
// for a / b, and NVIDIA's compiler gives a times an approximate reciprocal: the shear and the hit distance
// then differ from the CPU walk's by an ulp, and a ray aimed at an edge picks the other triangle (an H100
// and an H200 did). The driver's quotient is corrected by its residual, then whichever of it and its two
// neighbours leaves the smallest residual is the nearest float to a / b (a quotient of floats is never
// halfway between two). b is never 0 here (bvhRay's tiny components, bvhHitTriangle's det test).
// A driver that divides as IEEE 754 does (BOUNCE_IEEE_DIVISION: llvmpipe) skips the correction, a third of
// the GPU walk's time there. RAYCAST_INEXACT_DIVISION (tests) starts from a quotient one ulp off, as a
// GPU's may be, and corrects it on any driver.
float rayDivide(float a, float b)
{
#if defined(BOUNCE_IEEE_DIVISION) && !defined(RAYCAST_INEXACT_DIVISION)
    precise float q = a / b;
    return q;
#else
    precise float q = a / b;
#ifdef RAYCAST_INEXACT_DIVISION
    q = uintBitsToFloat(floatBitsToUint(q) + 1u);
#endif
    precise float refined = q + rayResidual(a, b, q) / b;
    float below = uintBitsToFloat(floatBitsToUint(refined) - 1u), above = uintBitsToFloat(floatBitsToUint(refined) + 1u);
    float best = refined, bestResidual = abs(rayResidual(a, b, refined));
    float r = abs(rayResidual(a, b, below));
    if (r < bestResidual) best = below, bestResidual = r;
    r = abs(rayResidual(a, b, above));
    if (r < bestResidual) best = above;
    return best;
#endif
}

// x.x * y.x + x.y * y.y + x.z * y.z, each product rounded and summed left to right as glm::dot on the CPU
// does: dot() is one built-in, which a driver may evaluate with fused multiply-adds even where precise.
float rayDot(vec3 x, vec3 y)
{
    precise float d = x.x * y.x + x.y * y.y + x.z * y.z;
    return d;
}

BvhRay bvhRay(vec3 origin, vec3 dir)
{
    BvhRay r;
    r.origin = origin;
    vec3 a = abs(dir);
    int kz = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    if (dir[kz] < 0.0) { int s = kx; kx = ky; ky = s; }
    float sx = rayDivide(dir[kx], dir[kz]), sy = rayDivide(dir[ky], dir[kz]), sz = rayDivide(1.0, dir[kz]);
    r.rowX = vec3(0.0);
    r.rowY = vec3(0.0);
    r.rowZ = vec3(0.0);
    r.rowX[kx] = 1.0;
    r.rowX[kz] = -sx;
    r.rowY[ky] = 1.0;
    r.rowY[kz] = -sy;
    r.rowZ[kz] = sz;
    // 1/0 = inf, and 0 * inf = NaN for a box face through the origin: a tiny component instead.
    vec3 d = mix(sign(dir) * 1e-30, dir, greaterThan(a, vec3(1e-30)));
    d = mix(vec3(1e-30), d, notEqual(d, vec3(0.0)));
    r.invDir = vec3(rayDivide(1.0, d.x), rayDivide(1.0, d.y), rayDivide(1.0, d.z));
    r.root = (2 * kz + (dir[kz] < 0.0 ? 1 : 0)) * (bvhNodes.length() / 6);
    return r;
}

// Ize 2013 ("Robust BVH ray traversal", JCGT 2(2)): the far distance times 1 + 2 gamma(3); the best
// hit so far times 1 + 8 ulp, so that a triangle a few ulps nearer than its box's entry is not culled.
bool bvhHitBox(BvhRay r, vec3 lo, vec3 hi, float tMin, float tMax)
{
    precise vec3 t0 = (lo - r.origin) * r.invDir;
    precise vec3 t1 = (hi - r.origin) * r.invDir;
    vec3 tNear = min(t0, t1), tFar = max(t0, t1);
    float enter = max(max(tNear.x, tNear.y), max(tNear.z, tMin));
    float leave = min(min(tFar.x, tFar.y), tFar.z) * 1.0000003576;
    return enter <= min(leave, tMax * 1.00000095367);
}

bool bvhHitTriangle(BvhRay r, BvhTriangle tri, float tMin, float tMax, out float t, out vec2 b)
{
    // The CPU walk's operations in its order (core/bvh.cpp, intersectTriangle), each rounded alike.
    precise vec3 a = tri.v0 - r.origin, bb = tri.v1 - r.origin, c = tri.v2 - r.origin;
    precise float ax = rayDot(r.rowX, a), ay = rayDot(r.rowY, a);
    precise float bx = rayDot(r.rowX, bb), by = rayDot(r.rowY, bb);
    precise float cx = rayDot(r.rowX, c), cy = rayDot(r.rowY, c);
    precise float u = cx * by - cy * bx;
    precise float v = ax * cy - ay * cx;
    precise float w = bx * ay - by * ax;
    t = 0.0;
    b = vec2(0.0);
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return false;
    precise float det = u + v + w;
    if (det == 0.0) return false;
    precise float rcp = rayDivide(1.0, det);
    precise float tScaled = u * rayDot(r.rowZ, a) + v * rayDot(r.rowZ, bb) + w * rayDot(r.rowZ, c);
    precise float tHit = tScaled * rcp;
    precise vec2 bHit = vec2(v, w) * rcp;
    t = tHit;
    b = bHit;
    return t > tMin && t < tMax;
}

// The walk shared by both queries; anyHit stops at the first triangle.
bool bvhWalk(vec3 origin, vec3 dir, float tMin, float tMax, bool stopAtFirst, out Hit hit)
{
    BvhRay r = bvhRay(origin, dir);
    hit.triangle = 0u;
    hit.t = tMax;
    hit.b = vec2(0.0);
    bool found = false;
    int node = r.root;
    while (node >= 0) {
        BvhNode n = bvhNodes[node];
        if (!bvhHitBox(r, n.lo, n.hi, tMin, hit.t)) {
            node = n.miss;
        } else if (n.leaf < 0) {
            node += 1;
        } else {
            int first = n.leaf >> 5, end = first + (n.leaf & 31);
            for (int i = first; i < end; ++i) {
                BvhTriangle tri = bvhTriangles[i];
                float t;
                vec2 b;
                bool accepted = bvhHitTriangle(r, tri, tMin, hit.t, t, b);
#ifdef ALPHA_MASK
                accepted = accepted && !bvhCutOut(tri.index, b);
#endif
                if (accepted) {
                    found = true;
                    hit.triangle = tri.index;
                    hit.t = t;
                    hit.b = b;
                }
            }
            node = (found && stopAtFirst) ? -1 : n.miss;
        }
    }
    return found;
}

bool closestHit(vec3 origin, vec3 dir, float tMin, float tMax, out Hit hit)
{
    return bvhWalk(origin, dir, tMin, tMax, false, hit);
}

bool anyHit(vec3 origin, vec3 dir, float tMin, float tMax)
{
    Hit hit;
    return bvhWalk(origin, dir, tMin, tMax, true, hit);
}

#endif
