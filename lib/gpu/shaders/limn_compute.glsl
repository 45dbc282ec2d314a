// limn's compute-pass conventions (lib/gpu/commands.h, CommandBuffer::dispatch).
//
// Every compute shader's push-constant block starts with the dispatch header, which the host
// fills; the pass's own push constants follow at offset 16:
//
//   layout(push_constant) uniform Push {
//       LIMN_DISPATCH_HEADER
//       layout(offset = 16) uint firstVertex;   // the pass's own fields
//   } pc;
//
//   void main() {
//       uint i = limnInvocationIndex(pc.limnRowInvocations);
//       if (i >= pc.limnCount) return;   // the grid is rounded up to whole workgroups
//       ...
//   }
//
// Work is one-dimensional (local_size_x only, at most 256: WebGPU's limit). Large dispatches
// become a 2D grid of workgroups, because WebGPU and many GPUs cap a dimension at 65535 groups.
// The index comes from gl_GlobalInvocationID and a row width the host passes: with Mesa 22.3's
// lavapipe, (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x +
// gl_LocalInvocationID.x produced only 79 distinct indices for 16 groups of 64 (as if the
// workgroup size were 1), although gl_WorkGroupSize.x alone reads 64. tests/gpu pins this.
#ifndef LIMN_COMPUTE_GLSL
#define LIMN_COMPUTE_GLSL

// limnCount: invocations that do work; limnRowInvocations: groups in x * local_size_x.
#define LIMN_DISPATCH_HEADER uint limnCount; uint limnRowInvocations; uint limnReserved0; uint limnReserved1;

uint limnInvocationIndex(uint rowInvocations) {
    return gl_GlobalInvocationID.y * rowInvocations + gl_GlobalInvocationID.x;
}

#endif
