// One patch vertex per visible blade: the culling pass wrote the indices of the blades to draw.
layout(std430, binding = VISIBLE_INDEX_SSBO_BINDING) readonly buffer VisibleIndices {
    uint visibleIndex[];
};

out flat uint vBladeIndex;

void main() {
    vBladeIndex = visibleIndex[gl_VertexID];
    gl_Position = vec4(0.0);  // the tessellation stages read the blade from its buffer
}
