// Micro-rendering's importance warp (Ritschel et al. 2009, §2.3), tabulated: the CPU half of it and the
// twin of glsl/technique/microrender/warp.glsl (tests/core/brdf_warp_test.cpp checks the closed forms here;
// the GL tests check the GLSL through the gather). No GL here.
//
// The paper takes the BRDF slice f(wo, w) for a fixed wo, parameterised by w's x and y in the local frame
// (z the normal), as a 2D pdf, and maps uniform micro-buffer coordinates (x, y) in [0,1)^2 through its
// inverse marginal and conditional CDFs: wx = M^-1(x), wy = C^-1(y | wx), wz = sqrt(1 - wx^2 - wy^2). Since
// dw = dwx dwy / wz, a pdf proportional to f over the disk is a pdf proportional to f cos over solid angle:
// "the cosine term is implicitly included due to the chosen parameterization".
//
// Tabulation. The marginal runs over a in [-1, 1] with wx = sin(pi a / 2) and the conditional over
// v = wy / s in [-1, 1] (s = sqrt(1 - wx^2) = cos(pi a / 2): the disk's chord at wx mapped to a fixed
// interval), so the table is a K x K grid of bins over (a, v), bin (i, j) holding the probability mass of
// f(w) (pi / 2) s^2 (the Jacobian of (a, v)) integrated over the bin. The map is piecewise linear inside a
// bin (a piecewise-constant pdf), so the forward and inverse maps are exact inverses of each other
// wherever a bin has mass. (Uniform bins in wx itself leave the density's sqrt(1 - wx^2) edge inside the
// outer bins and gave Lambert pixel weights 40% apart; in a, the edge is quadratic and holds no pixel.) One table per lobe ("we always tabulate the PDF and
// compute the inverse distributions numerically"):
//   table 0: Lambert, f = 1 / pi (mass ~ s);
//   tables 1..: the project's GGX lobe D Vis (core/brdf.h, F = 1) for wo = (sin theta_o, 0, cos theta_o)
//   on a grid of cos theta_o and alpha; the gather point's local frame puts wo's tangent part on +x.
// A gather point mixes the tables of its lobes by their estimated reflectance (mixWarpMass) and builds the
// CDFs of the mixture (BrdfWarp): the paper computes "the BRDF warping for every single micro-rendering".
//
// Pixel solid angles. A micro-pixel of an R x R buffer holds probability 1 / R^2, so its solid angle is
// Omega = 1 / (R^2 pdf(w)) with pdf(w) = q_ij wz / ((pi / 2) s^2) the solid-angle density (q_ij = mass_ij
// K^2 / 4, the density over (a, v)). The paper uses the gradient magnitude of Phi, a first-order
// approximation of the same Jacobian. f cos Omega = f (pi / 2) s^2 / (R^2 q_ij) (wz cancels, so the rim is
// finite), and these weights
// sum over the buffer to rho = int f cos dw up to the quadrature error of R^2 equal-mass cells: with the
// table proportional to f the weights are all rho / R^2 and the result is rho times the mean of the
// micro-pixels.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace bounce::core {

struct BrdfWarpTables {
    int bins = 0;                 // K
    std::vector<float> cosThetaO; // grid of cos theta_o (bin centres of (0, 1])
    std::vector<float> alphas;    // grid of GGX alpha, ascending
    std::vector<float> mass;      // tables x K x K, row i (wx) major; each table sums to 1
    int tableCount() const { return int(mass.size()) / (bins * bins); }
    // Table 1 + ia * cosThetaO.size() + ic for the grid point nearest (cos theta_o, alpha in log scale).
    int ggxTable(float cosThetaO, float alpha) const;
};

// Lambert and GGX tables. Default: 32 x 32 bins, 16 values of cos theta_o, alpha from 0.01 to 1.
BrdfWarpTables makeBrdfWarpTables(int bins = 32, int cosSteps = 16,
                                  const std::vector<float>& alphas = {0.01f, 0.02f, 0.04f, 0.07f, 0.1f, 0.15f, 0.22f,
                                                                      0.32f, 0.45f, 0.65f, 1.0f});

// The mixture of table 0 (weight 1 - specularShare) and table ggx (specularShare), K x K, summing to 1.
std::vector<float> mixWarpMass(const BrdfWarpTables& tables, float specularShare, int ggx);

// The share of the micro-buffer the glossy lobe gets (the twin of warp.glsl's warpSpecularShare): the
// lobes' estimated reflectances, w lum(F(n.wo)) for glossy and lum(c_diff) (1 - w lum(F(n.wo))) for diffuse,
// normalised; 0 without a glossy lobe, 1 without a diffuse one.
float warpSpecularShare(const glm::vec3& diffuse, const glm::vec3& f0, float weight, float cosThetaO);

// The CDFs of one K x K mass table and the map between the unit square and the hemisphere (z up).
class BrdfWarp {
public:
    BrdfWarp(const std::vector<float>& mass, int bins);

    // Phi: (x, y) in [0,1)^2 to a unit direction with z >= 0.
    glm::vec3 toDirection(const glm::vec2& u) const;
    // Phi^-1: a direction with z >= 0 to (x, y) in [0,1]^2.
    glm::vec2 toUnit(const glm::vec3& w) const;
    // The solid-angle density at w (0 where its bin has no mass).
    float pdf(const glm::vec3& w) const;
    // cos theta x the solid angle of a pixel of an R x R buffer at w: f cos Omega with f factored out,
    // = (pi / 2) s^2 / (R^2 q) (0 where the bin has no mass).
    float cosineSolidAngle(const glm::vec3& w, int resolution) const;
    // The solid angle Omega of that pixel (infinite at the rim, where cos = 0).
    float pixelSolidAngle(const glm::vec3& w, int resolution) const;

    // Micro-pixel c of an R x R buffer covers [c / R, (c + 1) / R)^2 of the unit square; its direction is
    // taken at (c + 0.5 + j) / R, j in (-0.5, 0.5)^2 the gather sample's jitter ("we jitter the local
    // coordinate system slightly at every gather sample to avoid banding").
    static glm::vec2 cellSample(glm::ivec2 cell, glm::vec2 jitter, int resolution);
    // The micro-pixel of a unit-square point.
    static glm::ivec2 cellOf(glm::vec2 u, int resolution);

    int bins() const { return bins_; }
    const std::vector<float>& marginalCdf() const { return marginal_; } // K + 1 entries
    const std::vector<float>& conditionalCdf() const { return rows_; }  // K rows of K + 1 entries
    const std::vector<float>& mass() const { return mass_; }

private:
    int bins_;
    std::vector<float> mass_, marginal_, rows_;
    glm::ivec2 binOf(const glm::vec3& w, glm::vec2& frac) const;
};

} // namespace bounce::core
