// Binding points of the machine probe (gl/probe/machine_probe.cpp includes this file too); its storage
// names are 60-69 (glsl/common/bindings.glsl). Only #define lines and comments. The probe runs alone, so its
// units and uniform blocks may use any slot.
#ifndef BOUNCE_PROBE_BINDINGS_GLSL
#define BOUNCE_PROBE_BINDINGS_GLSL

#define SSBO_PROBE_SOURCE 60 // bandwidth_buffer.comp
#define SSBO_PROBE_TARGET 61
#define UBO_PROBE_RECORDS 0  // uniform.frag, uniform.comp (kernels.glsl: uniformLoop)
#define UNIT_PROBE_FIRST 0   // bandwidth.frag: four inputs, 0..3; the other kernels use the first only

#endif
