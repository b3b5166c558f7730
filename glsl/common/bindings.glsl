// Binding points of the frame's data, named once for GLSL and C++: shaders include this file through
// the headers that declare the blocks (gbuffer.glsl, scene.glsl, shadow.glsl, rsm.glsl, multires.glsl,
// raycast.glsl), and gl/frame/bindings.h includes the very same file, so that the C++ that binds a
// buffer and the shader that reads it cannot disagree. Only #define lines and comments: the file is
// valid GLSL and valid C++.
//
// Shader storage names (Buffer::bindBase(GL_SHADER_STORAGE_BUFFER, name)): a name says which buffer a
// storage block reads, it is not a GL binding point. Each program gives its own active blocks the points
// 0..k-1 (gl/resource/storage_bindings.h), so a name costs no driver's limit and none is shared: every SSBO_*
// of every bindings.glsl is a number of its own (tests/gl/bindings_test.cpp). The frame's are 0-29,
// glsl/frame/sort_bindings.glsl's 30-39, glsl/frame/points/bindings.glsl's 40-59, glsl/probe/bindings.glsl's
// 60-69; a family names its own in glsl/technique/<family>/bindings.glsl, in a free range of twenty from 100
// up.
#ifndef BOUNCE_BINDINGS_GLSL
#define BOUNCE_BINDINGS_GLSL

#define SSBO_MATERIALS 0         // scene.glsl: Material per material index
#define SSBO_LIGHTS 1            // scene.glsl: the lights, their shadow views and the area lights' triangles
#define SSBO_SCENE_VERTICES 4    // scene.glsl (SCENE_GEOMETRY): GpuVertex, 9 floats each
#define SSBO_SCENE_INDICES 5     // scene.glsl (SCENE_GEOMETRY): three per triangle
#define SSBO_SCENE_EMISSIVE 6    // scene.glsl (SCENE_GEOMETRY): emissive triangles and their power CDF
#define SSBO_RSM_VIEWS 10        // rsm.glsl: RsmView per RSM layer
#define SSBO_BVH_NODES 18        // raycast.glsl: the threaded BVH
#define SSBO_BVH_TRIANGLES 19    // raycast.glsl: triangles in BVH order
#define SSBO_RAY_BATCH_RAYS 20   // frame/raycast_batch.glsl: rays of RayBatch (bounce rays, tests)
#define SSBO_RAY_BATCH_RESULTS 21

// Texture units (glBindTextureUnit(unit, texture)). Units 21 and up belong to the technique.
#define UNIT_G_GEOMETRY 0        // gbuffer.glsl: eye depth and normal
#define UNIT_MULTIRES_UNMODULATED 1 // frame/multires_upsample.glsl (UNMODULATED): the second, unmodulated buffer
#define UNIT_G_DIFFUSE 2
#define UNIT_G_SPECULAR 3
#define UNIT_G_EMISSION 4
#define UNIT_SHADOW_MAPS 5       // shadow.glsl: one layer per shadow view
#define UNIT_BASE_COLOR 6        // gbuffer.frag, rsm.frag: base-colour textures, one layer each
#define UNIT_RSM_SOLID_ANGLES 7  // rsm.frag: exact texel solid angles, one layer per view
#define UNIT_RSM_FIRST 8         // rsm.glsl: position, normal, flux, depth range, normal min, max: 8..13
#define UNIT_MULTIRES_FIRST 14   // multires.glsl: position, normal, diffuse, depth range, normal min, max: 14..19
#define UNIT_MULTIRES_ILLUMINATION 20 // frame/multires_upsample.glsl: the flattened illumination buffer
// The composite, tone-map and joint-upsample passes bind no G-buffer units; their inputs take the first units.
#define UNIT_COMPOSITE_DIRECT 0
#define UNIT_COMPOSITE_INDIRECT 1
#define UNIT_TONEMAP_RADIANCE 0
#define UNIT_AREA_UNSHADOWED 0    // frame/direct_ratio.frag (reads no G-buffer): the emitters' unshadowed light
#define UNIT_AREA_VISIBILITY 1    //   and the sums of w V and w, averaged by the temporal reuse
#define UNIT_UPSAMPLE_COARSE_INDIRECT 0 // frame/joint_upsample.frag (the demo's frame budget)
#define UNIT_UPSAMPLE_COARSE_GEOMETRY 1 // the two frames' gGeometry (common/gbuffer.glsl)
#define UNIT_UPSAMPLE_FULL_GEOMETRY 2
#define UNIT_SHADOW_DEPTHS 32     // shadow.glsl (SHADOW_PCSS): the shadow maps' depths, no comparison
// Temporal reuse (frame/temporal_reuse.frag, gl/frame/temporal_reuse.h) reads the G-buffer too, so its inputs
// take units of their own past the technique's (21-31) and the shadow depths.
#define UNIT_TEMPORAL_CURRENT 33          // the signal this frame computed
#define UNIT_TEMPORAL_HISTORY 34          // the pass's previous output for the signal
#define UNIT_TEMPORAL_HISTORY_LENGTH 35   // frames that history averages (R32F)
#define UNIT_TEMPORAL_PREVIOUS_GEOMETRY 36 // a copy of the previous frame's gGeometry (common/gbuffer.glsl)
#define UNIT_NORMAL_MAP 37        // common/normal_map.glsl (NORMAL_MAPS): the scene's normal textures, one layer each
// Moving frames' edge antialiasing (frame/edge_aa.frag, gl/frame/edge_antialias.h) reads the G-buffer too.
#define UNIT_EDGE_IMAGE 38        // the frame's image as composited
#define UNIT_EDGE_LINES 39        // frame/edges.frag: each pixel's nearest edge of the triangle it sees

// Uniform buffers (glBindBufferBase(GL_UNIFORM_BUFFER, slot)). Slot 0 and slots 2 and up belong to the
// technique that binds them.
#define UBO_GBUFFER_CAMERA 1     // gbuffer.glsl: the camera that rendered the G-buffer

// Image units (glBindImageTexture) are bound right before the dispatch that uses them and belong to
// that pass: each compute shader numbers its images from 0.

#endif
