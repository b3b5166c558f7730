#include "gl/technique/technique.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace bounce::gl {

const TechniqueInfo& findTechnique(const std::string& name)
{
    for (const TechniqueInfo& t : techniques())
        if (t.name == name) return t;
    std::string known;
    for (const TechniqueInfo& t : techniques()) known += (known.empty() ? "" : ", ") + t.name;
    throw std::invalid_argument("unknown technique '" + name + "'; known: " + known);
}

std::string gbufferChannelName(GBufferChannel c)
{
    switch (c) {
    case GBufferChannel::Position: return "position";
    case GBufferChannel::Normal: return "normal";
    case GBufferChannel::Diffuse: return "diffuse";
    case GBufferChannel::Specular: return "specular";
    case GBufferChannel::Emission: return "emission";
    case GBufferChannel::Depth: return "depth";
    case GBufferChannel::Direct: return "direct";
    }
    return "unknown";
}

nlohmann::json TechniqueInfo::toJson() const
{
    nlohmann::json j = {{"name", name},
                        {"paper", paper},
                        {"lightPaths", core::lightPathsName(lightPaths)},
                        {"summary", summary},
                        {"progressive", progressive},
                        {"quickSets", quickSets}};
    j["parameters"] = nlohmann::json::array();
    for (const ParamDecl& p : params) j["parameters"].push_back(p.toJson());
    j["passes"] = nlohmann::json::array();
    for (const PassDecl& p : passes) {
        nlohmann::json pj = {{"name", p.name}, {"meaning", p.meaning}};
        if (!p.when.empty()) pj["when"] = p.when;
        j["passes"].push_back(pj);
    }
    j["reads"] = nlohmann::json::array();
    for (GBufferChannel c : reads) j["reads"].push_back(gbufferChannelName(c));
    return j;
}

const std::vector<PassDecl>& framePasses()
{
    static const std::vector<PassDecl> p = {
        {"shadow", "shadow maps of every light (gl/frame/shadow_maps.cpp)", ""},
        {"gbuffer", "the G-buffer: eye depth and normal, diffuse, specular and emission where the scene has them", ""},
        {"direct", "emission and direct light with shadow maps", ""},
        {"composite", "direct + the technique's indirect light", "the technique adds indirect light"},
        {"accumulate", "the mean of the still frames (jittered pixel centres)", "the view was still last frame"},
        {"direct.samples",
         "the direct light of the frame's further points in the pixel summed, then averaged with its own",
         "still.directSamples > 1 in a still frame, moving.directSamples in a moving one"},
        {"temporal",
         "the indirect light of a technique that declares temporalReuse, and with temporal.direct the frame's "
         "direct light in moving frames, blended with their reprojected histories (gl/frame/temporal_reuse.h)",
         "frame parameter temporal on"},
        {"edge-aa.lines",
         "the edges that bound a surface on screen (boundaries, silhouettes, creases) drawn as strips, each "
         "pixel keeping the nearest one's line",
         "frame parameter edgeAA on, not a still frame"},
        {"edge-aa", "the composited light mixed across those edges by the area each side covers",
         "frame parameter edgeAA on, not a still frame"},
    };
    return p;
}

const std::vector<ParamDecl>& frameParams()
{
    static const std::vector<ParamDecl> p = {
        {"shadow.size", ParamType::Int, 1024, 16, 8192,
         "shadow-map resolution per view (texels per side); a spot's or point light's largest (shadow.footprint)"},
        {"shadow.footprint", ParamType::Float, 4, 0, 64,
         "a spot's or point light's shadow-map texels per screen pixel over what the camera sees of it: each "
         "view's side from its footprint, a power of two between 256 and shadow.size (0: every view at "
         "shadow.size). Raise shadow.size to let views the camera sees close up get more"},
        {"shadow.pcf", ParamType::Int, 1, 0, 4, "PCF kernel radius in texels (0: one tap)"},
        {"shadow.cascades", ParamType::Int, 3, 0, 6,
         "a directional light's shadow views fitted to slices of the camera's frustum (cascaded shadow maps; "
         "still frames with shadow.still=maps only), before its view of the whole scene (0: that view only)"},
        {"shadow.linear", ParamType::Bool, 1, 0, 1, "hardware bilinear depth comparison (off: hard shadow edges)"},
        {"textures.size", ParamType::Int, 512, 1, 4096,
         "base-colour textures are resampled to this size (normal maps keep their own, up to 2048)"},
        {"normalMaps", ParamType::Bool, 1, 0, 1,
         "the G-buffer's normals bent by the scene's glTF normal maps (off: the vertex normals; `bounce reference "
         "--no-normal-maps` is the path tracer's side)"},
        choiceParam("shadow.area", {"hard", "pcss"}, 0,
                    "area lights' shadows while the view moves: hard from the emitter's centroid, or penumbrae "
                    "estimated by percentage-closer soft shadows (Fernando 2005); still frames sample the emitter "
                    "either way"),
        choiceParam("shadow.still", {"rays", "maps"}, 0,
                    "the still frames' shadows: one ray per light and pixel through the frame's BVH towards the "
                    "frame's point on the light (converges to the path tracer's, contacts included), or the "
                    "shadow maps with a shifted tap per frame (a bias that scales with the texel stays); moving "
                    "frames read the shadow maps either way"),
        {"still.directSamples", ParamType::Int, 1, 1, 64,
         "still frames: the direct light's points in the pixel per frame, the frame's own (where the technique "
         "gathers) and N - 1 more, each a G-buffer and direct pass of its own, averaged: the direct light "
         "converges N times as fast in frames, for what those passes cost (worth it where a technique's "
         "frame costs far more than they do)"},
        {"moving.directSamples", ParamType::Int, 1, 1, 64,
         "moving frames: the direct light's points in the pixel per frame, its centre (where the technique "
         "gathers and the reuse reprojects) and N - 1 more, each a G-buffer and direct pass of its own, "
         "averaged: the moving frame's shadow edges, thin geometry and textures antialiased, for N times what "
         "those passes cost; with temporal.direct the reuse blends the mean"},
        {"accumulate", ParamType::Bool, 1, 0, 1,
         "while the view is still, sample each frame at another point inside the pixel and show the mean of "
         "the frames (converges to box-filtered pixels; the area lights' shadows to soft ones)"},
        {"temporal", ParamType::Bool, 0, 0, 1,
         "temporal reuse: a technique's indirect light (those that declare it; and the frame's direct light "
         "with temporal.direct) blended with its history reprojected through the previous camera, rejected "
         "where depth or normal disagree with every pixel around, clamped to the current neighbourhood "
         "(gl/frame/temporal_reuse.h)"},
        {"temporal.alpha", ParamType::Float, 0.2, 0.01, 1,
         "temporal reuse's weight of the new frame once the history is 1/alpha frames long (1: no reuse)"},
        {"temporal.clamp", ParamType::Bool, 1, 0, 1,
         "clamp the history to the current frame's 3x3 neighbourhood (against ghosting after a light or "
         "object moves; off: such changes fade over about 1/alpha frames, and noise that flips whole regions "
         "at once averages out, which one frame's neighbourhood clamps away)"},
        choiceParam("temporal.filter", {"catmull-rom", "bilinear"}, 0,
                    "how temporal reuse resamples its history at the point's previous position: Catmull-Rom's "
                    "cubic over the 4x4 texels around it where all sixteen are the pixel's surface (else the "
                    "bilinear blend of the four nearest), or always the bilinear blend, which blurs the history "
                    "a little at every frame the camera moves"),
        {"temporal.direct", ParamType::Bool, 0, 0, 1,
         "with temporal on, the frame's direct light too: moving frames sample a new shadow-map shift and "
         "point on each emitter every frame; emitting triangles give their exact unshadowed light times the "
         "visible share, whose sums alone are blended with their reprojected history (the ratio estimator, "
         "gl/frame/README.md), and a scene with no emitter blends its whole direct light (pixel centres, "
         "as every moving frame), clamped as temporal.clamp says when its shadows are rays (shadow.still); "
         "the emitters' share and shifted shadow maps unclamped (one point on each emitter, one shift, for "
         "the whole frame, so one frame's neighbourhood holds one point's shadow); a light change drops that "
         "history"},
        {"edgeAA", ParamType::Bool, 0, 0, 1,
         "moving frames (not still frames, which average jittered pixels): each pixel that an edge of the "
         "geometry crosses takes the light of the surface beyond the edge over the area it covers there, from "
         "the edge's line in screen space (geometric post-process antialiasing, gl/frame/edge_antialias.h)"},
        choiceParam("gbuffer.fragment", {"material", "constant"}, 0,
                    "profiling: constant writes the G-buffer without reading materials or textures (wrong images)"),
    };
    return p;
}

FrameSettings frameSettingsFrom(const ParamValues& v, int width, int height)
{
    FrameSettings s;
    s.width = width;
    s.height = height;
    s.shadowMapSize = v.getInt("shadow.size");
    s.pcfRadius = v.getInt("shadow.pcf");
    s.shadowCascades = v.getInt("shadow.cascades");
    s.shadowFootprint = float(v.get("shadow.footprint"));
    s.pcfLinear = v.getBool("shadow.linear");
    s.textureSize = v.getInt("textures.size");
    s.normalMaps = v.getBool("normalMaps");
    s.accumulate = v.getBool("accumulate");
    s.temporal = v.getBool("temporal");
    s.temporalAlpha = float(v.get("temporal.alpha"));
    s.temporalClamp = v.getBool("temporal.clamp");
    s.temporalDirect = v.getBool("temporal.direct");
    s.temporalCatmullRom = v.getChoice(frameParams(), "temporal.filter") == "catmull-rom";
    s.edgeAntialias = v.getBool("edgeAA");
    s.areaPcss = v.getChoice(frameParams(), "shadow.area") == "pcss";
    s.stillRayShadows = v.getChoice(frameParams(), "shadow.still") == "rays";
    s.stillDirectSamples = v.getInt("still.directSamples");
    s.movingDirectSamples = v.getInt("moving.directSamples");
    s.gbufferConstantFragment = v.getChoice(frameParams(), "gbuffer.fragment") == "constant";
    return s;
}

} // namespace bounce::gl
