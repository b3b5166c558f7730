// A work group's sum of one value per invocation, in a fixed order (the same sum in every run): a tree
// reduction in shared memory. Define before including: GROUP_SUM_TYPE (float, vec2, ...) and
// GROUP_SUM_SIZE (the work group's invocations, a power of two). Every invocation of the group must call
// groupSum, the same number of times (it holds barriers); each gets the group's sum.
#ifndef BOUNCE_GROUP_SUM_GLSL
#define BOUNCE_GROUP_SUM_GLSL

shared GROUP_SUM_TYPE groupSumPartial[GROUP_SUM_SIZE];

GROUP_SUM_TYPE groupSum(GROUP_SUM_TYPE mine)
{
    uint t = gl_LocalInvocationIndex;
    groupSumPartial[t] = mine;
    barrier();
    for (uint stride = uint(GROUP_SUM_SIZE) / 2u; stride > 0u; stride /= 2u) {
        if (t < stride) groupSumPartial[t] += groupSumPartial[t + stride];
        barrier();
    }
    GROUP_SUM_TYPE sum = groupSumPartial[0];
    barrier(); // a second call may overwrite the partial sums only once every invocation has read this one
    return sum;
}

#endif
