// Binding points of the machine probe (gl/probe/machine_probe.cpp includes this file too). Only
// #define lines and comments. The probe runs alone, so it may use any slot.
#ifndef BOUNCE_PROBE_BINDINGS_GLSL
#define BOUNCE_PROBE_BINDINGS_GLSL

#define SSBO_PROBE_SOURCE 7      // bandwidth_buffer.comp
#define SSBO_PROBE_TARGET 8
#define UBO_PROBE_RECORDS 0      // uniform.frag, uniform.comp (kernels.glsl: uniformLoop)
#define UNIT_PROBE_FIRST 0       // bandwidth.frag: four inputs, 0..3; the other kernels use the first only

#endif
