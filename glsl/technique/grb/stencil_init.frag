#version 450 core
// Stencil routing's set-up (Bavoil et al. 2007, as the paper's Sec. 2.1 and 4.2 use it): one full-screen
// draw per sample writes that sample's stencil (its index plus the slice's offset, the reference
// value, GL_REPLACE) and no other, through the sample mask.
uniform int sampleIndex;
void main()
{
    gl_SampleMask[0] = 1 << sampleIndex;
}
