// The one GL header the rest of Bounce includes: the GL 4.5 core loader that glad generates at build time.
// Its entry points are process-wide pointers that gl::Context loads (and reloads when a context of another
// backend is made current), so no GL call may come before a context exists.
#pragma once

#include <glad/gl.h>
