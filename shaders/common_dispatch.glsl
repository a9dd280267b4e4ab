// Dispatches wider than one dimension's 65535 work groups (the minimum GL guarantees): the
// host spreads the groups over x and y (gl::dispatchGroups), and a shader asks for its flat
// work group or invocation index here. Groups past the end return at their first line.
uint flatWorkGroup() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }
// Every compute shader of meadow has local_size_x = BLADE_WORKGROUP_SIZE (gl_WorkGroupSize is
// declared only after the stage's layout line, which follows this file).
uint flatInvocation() {
    return flatWorkGroup() * uint(BLADE_WORKGROUP_SIZE) + gl_LocalInvocationID.x;
}
