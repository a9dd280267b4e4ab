// Splits the culling pass's single draw command into chunks of BLADE_DRAW_CHUNK blades for
// glMultiDrawArraysIndirect. Mesa's llvmpipe corrupts tessellated output when one draw emits
// too many vertices; small draws are also what a GPU runs best. Chunk k draws blades
// [k * BLADE_DRAW_CHUNK, min((k + 1) * BLADE_DRAW_CHUNK, count)); empty chunks draw nothing.
layout(local_size_x = BLADE_WORKGROUP_SIZE) in;

layout(std430, binding = DRAW_COMMAND_SSBO_BINDING) readonly buffer Command { DrawCommandGpu command; };
layout(std430, binding = DRAW_CHUNK_SSBO_BINDING) writeonly buffer Chunks { DrawCommandGpu chunks[]; };

uniform uint uChunkCount;

void main() {
    uint k = flatInvocation();
    if (k >= uChunkCount) return;
    uint first = k * uint(BLADE_DRAW_CHUNK);
    uint count = command.vertexCount > first ? min(command.vertexCount - first, uint(BLADE_DRAW_CHUNK)) : 0u;
    chunks[k] = DrawCommandGpu(count, 1u, command.firstVertex + first, 0u);
}
