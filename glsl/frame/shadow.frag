#version 450 core
// Depth only: the shadow views store hardware depth compared with sampler2DArrayShadow.
void main() {}
