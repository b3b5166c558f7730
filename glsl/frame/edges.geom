#version 450 core
// The edges that bound a surface on screen, drawn as strips three pixels wide along them (after Persson's
// geometric post-process antialiasing, 2011), each writing its line into the pixels it touches
// (edges.frag). An edge bounds what lies on one side of it where no triangle continues the surface across
// it (a boundary), where the triangle across it faces the other way (a silhouette), or where the two meet at
// a crease (their normals more than about 25 degrees apart); an edge inside a smooth surface is not drawn.
// The line is a x + b y + c in window coordinates (pixels): the signed distance from the edge, positive on
// this triangle's side, (a, b) a unit normal. It comes from the clip-space corners as homogeneous 2D points
// (x, y, w): the line through two of them is their cross product, and a point of the triangle has on each
// edge's line the sign of the triangle's determinant, whatever the corners' w (homogeneous rasterisation,
// Olano and Greer 1997); the same determinant's sign is the side the triangle faces. The strip itself is
// built from the edge clipped to the view.
layout(triangles_adjacency) in; // corners 0, 2, 4; after each edge the far corner of the triangle across it
layout(triangle_strip, max_vertices = 12) out;

uniform vec2 viewport; // the target's width and height

in vec3 vWorld[];
out vec3 gWorld; // the edge's point (perspective-correct along it, the same across the strip)
flat out vec3 gLine;

const float kCreaseCos = 0.9;
// Pixels each side of the edge (a pixel whose square the line crosses has its centre within 0.71 of it) and
// past its ends.
const float kHalfWidth = 1.5, kPastEnds = 0.75;

float orientation(vec3 a, vec3 b, vec3 c) { return dot(a, cross(b, c)); }

// The part of the clip-space segment a-b inside the view, its sides widened by a tenth, and in front of the
// near plane (Liang and Barsky's parametric clipping): a strip stays a few pixels long and wide on screen
// however near the camera the edge runs. False where none of it is.
// `range`: the clipped part's parameters along the original segment.
bool clipToView(inout vec4 a, inout vec4 b, out vec2 range)
{
    const vec4 planes[5] = vec4[5](vec4(-1, 0, 0, 1.1), vec4(1, 0, 0, 1.1), vec4(0, -1, 0, 1.1), vec4(0, 1, 0, 1.1),
                                   vec4(0, 0, 1, 1));
    vec4 d = b - a;
    float t0 = 0.0, t1 = 1.0;
    for (int i = 0; i < 5; ++i) {
        float fa = dot(planes[i], a), fd = dot(planes[i], d);
        if (fd == 0.0) {
            if (fa < 0.0) return false;
        } else if (fd > 0.0) {
            t0 = max(t0, -fa / fd);
        } else {
            t1 = min(t1, -fa / fd);
        }
    }
    range = vec2(t0, t1);
    if (!(t0 < t1)) return false;
    b = a + t1 * d;
    a = a + t0 * d;
    return true;
}

void main()
{
    vec4 c[3];
    vec3 p[3];
    for (int i = 0; i < 3; ++i) {
        c[i] = gl_in[2 * i].gl_Position;
        p[i] = c[i].xyw;
    }
    float det = orientation(p[0], p[1], p[2]);
    if (det == 0.0) return; // seen edge-on: no side
    vec3 normal = normalize(cross(vWorld[2] - vWorld[0], vWorld[4] - vWorld[0]));
    for (int k = 0; k < 3; ++k) {
        // Edge k runs from corner k to corner k + 1 (inputs 2k and 2k + 2), the triangle across it is
        // (k + 1, k, far) in the mesh's winding, and the builder put the own opposite corner at a boundary.
        int a = 2 * k, b = (2 * k + 2) % 6, far = 2 * k + 1, own = (2 * k + 4) % 6;
        bool bounds = vWorld[far] == vWorld[own];
        if (!bounds) {
            float across = orientation(p[(k + 1) % 3], p[k], gl_in[far].gl_Position.xyw);
            vec3 m = cross(vWorld[a] - vWorld[b], vWorld[far] - vWorld[b]);
            bounds = sign(across) != sign(det) || dot(normal, m) < kCreaseCos * length(m);
        }
        if (!bounds) continue;
        // The line through corners k and k + 1 as a function of NDC (x, y, 1), then of window coordinates
        // (x_ndc = 2 x / width - 1), positive on the triangle's side.
        vec3 l = cross(p[k], p[(k + 1) % 3]) * sign(det);
        vec3 w = vec3(2.0 * l.x / viewport.x, 2.0 * l.y / viewport.y, l.z - l.x - l.y);
        float g = length(w.xy);
        if (!(g > 0.0)) continue; // seen end-on
        vec4 e0 = c[k], e1 = c[(k + 1) % 3];
        vec4 t = vec4(0.0, 1.0, 0.0, 0.0);
        if (!clipToView(e0, e1, t.xy)) continue;
        vec3 world0 = mix(vWorld[a], vWorld[b], t.x), world1 = mix(vWorld[a], vWorld[b], t.y);
        vec2 w0 = (e0.xy / e0.w * 0.5 + 0.5) * viewport, w1 = (e1.xy / e1.w * 0.5 + 0.5) * viewport;
        vec2 along = w1 - w0;
        if (!(dot(along, along) > 1e-12)) continue;
        along = normalize(along);
        vec2 side = vec2(-along.y, along.x) * kHalfWidth;
        vec2 corners[4] = vec2[4](w0 - along * kPastEnds - side, w0 - along * kPastEnds + side,
                                  w1 + along * kPastEnds - side, w1 + along * kPastEnds + side);
        for (int v = 0; v < 4; ++v) {
            // Each end's w, for the world point to interpolate perspective-correctly along the edge.
            float clipW = v < 2 ? e0.w : e1.w;
            gl_Position = vec4((corners[v] / viewport * 2.0 - 1.0) * clipW, 0.0, clipW);
            gWorld = v < 2 ? world0 : world1;
            gLine = w / g;
            EmitVertex();
        }
        EndPrimitive();
    }
}
